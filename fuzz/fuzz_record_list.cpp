// Fuzz target: the record-list reader of `pounding gap --records`. The input is the list file;
// it sits beside the fixture records (record.AT2, record.txt), so fuzzed lines can name them
// and reach the per-line options. Bad input must end in InputError; a list that is read must
// give one validated record per entry, each an existing file.

#include <fstream>
#include <unistd.h>

#include "fixtures.hpp"
#include "pounding/input_error.hpp"
#include "pounding/io/record_list.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace pounding;
  static const std::filesystem::path list =
      fuzz::fixture_folder() / ("fuzzed-list-" + std::to_string(::getpid()) + ".txt");
  std::ofstream(list, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  excitation::ExcitationSpec scene;  // as a scene naming the PEER fixture would have it
  scene.file = fuzz::fixture_folder() / "record.AT2";
  scene.scale_to_pga_g = 0.3;
  try {
    const std::vector<analysis::RecordEntry> records = io::read_record_list(list, scene);
    if (records.empty() || records.size() > io::kMaxRecordsInSet) __builtin_trap();
    for (const analysis::RecordEntry& r : records) {
      if (!std::filesystem::is_regular_file(r.excitation.file)) __builtin_trap();
      r.excitation.validate();  // already valid: must not throw
    }
  } catch (const InputError&) {
  }
  return 0;
}
