// Fuzz target: the record readers and the processing after them. The first two bytes choose
// the format and options, the rest is the file. Bad input must end in InputError; then the
// ground motion must answer at any time, NaN included (NonFiniteTime), without reading
// outside its samples.

#include <cmath>
#include <fstream>
#include <limits>
#include <unistd.h>

#include "fixtures.hpp"
#include "pounding/excitation/ground_motion.hpp"
#include "pounding/input_error.hpp"

namespace {

pounding::excitation::ExcitationSpec spec_from(std::uint8_t format, std::uint8_t options) {
  using namespace pounding::excitation;
  ExcitationSpec spec;
  spec.read.format = static_cast<RecordFormat>(format % 3);
  spec.read.time_column = 1 + options % 3;
  if (options & 0x04) spec.read.accel_column = 1 + (options >> 4) % 3;
  if (spec.read.format == RecordFormat::single || (options & 0x08)) spec.read.dt_s = 0.01;
  if (options & 0x40) spec.dt_override_s = 0.005;
  if (options & 0x80) {
    spec.start_s = 0.015;
    spec.duration_s = 0.02;
  }
  spec.units = static_cast<AccelUnits>((options >> 5) % 3);
  return spec;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace pounding;
  if (size < 2) return 0;
  static const std::filesystem::path file = fuzz::fixture_folder() / ("fuzzed-record-" + std::to_string(::getpid()));
  std::ofstream(file, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data + 2), static_cast<std::streamsize>(size - 2));
  excitation::ExcitationSpec spec = spec_from(data[0], data[1]);
  spec.file = file;
  try {
    const excitation::GroundMotion motion = excitation::load_ground_motion(spec);
    for (double t : {motion.start_s(), motion.end_s(), 0.5 * (motion.start_s() + motion.end_s()), -1.0, 1e300}) {
      if (!std::isfinite(motion.accel_at(t))) __builtin_trap();  // samples are finite, so is a_g
    }
    try {
      motion.accel_at(std::numeric_limits<double>::quiet_NaN());
      __builtin_trap();  // must have thrown
    } catch (const excitation::NonFiniteTime&) {
    }
  } catch (const InputError&) {
  }
  return 0;
}
