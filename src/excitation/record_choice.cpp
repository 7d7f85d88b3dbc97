#include "pounding/excitation/record_choice.hpp"

#include <fmt/format.h>

#include "pounding/input_error.hpp"

namespace pounding::excitation {

bool RecordChoice::empty() const {
  return !file && !format && !units && !dt_s && !accel_column && !scale_factor && !pga_g && !direction_deg;
}

ExcitationSpec with_record(ExcitationSpec spec, const RecordChoice& choice) {
  if (choice.file) {
    std::error_code unreadable;  // e.g. a name too long for the system: refused like a missing file
    if (!std::filesystem::is_regular_file(*choice.file, unreadable)) {
      throw InputError("excitation.file", choice.file->string(), "no such record file");
    }
    // The old file's layout and cut mean nothing for another record.
    spec.file = *choice.file;
    spec.read = RecordReadOptions{.format = spec.read.format};
    spec.dt_override_s.reset();
    spec.start_s = 0.0;
    spec.duration_s.reset();
  }
  if (choice.format) {
    const auto format = parse_record_format(*choice.format);
    if (!format) throw InputError("excitation.format", *choice.format, "expected peer-at2, columns or single");
    // dt_s means the spacing for `single` and a re-spacing otherwise: carry it to its new role.
    const std::optional<double> dt = spec.read.dt_s ? spec.read.dt_s : spec.dt_override_s;
    spec.read.format = *format;
    spec.read.dt_s.reset();
    spec.dt_override_s.reset();
    (*format == RecordFormat::single ? spec.read.dt_s : spec.dt_override_s) = dt;
  }
  if (choice.units) {
    const auto units = parse_accel_units(*choice.units);
    if (!units) throw InputError("excitation.units", *choice.units, fmt::format("expected {}", kAccelUnitChoices));
    spec.units = *units;
  }
  if (choice.dt_s) (spec.read.format == RecordFormat::single ? spec.read.dt_s : spec.dt_override_s) = *choice.dt_s;
  if (choice.accel_column) spec.read.accel_column = *choice.accel_column;
  if (choice.scale_factor && choice.pga_g) {
    throw InputError("excitation.scale_factor", format_value(*choice.scale_factor),
                     "give either a scale factor or a PGA, not both");
  }
  if (choice.scale_factor) {
    spec.scale_factor = *choice.scale_factor;
    spec.scale_to_pga_g.reset();
  }
  if (choice.pga_g) {
    spec.scale_to_pga_g = *choice.pga_g;
    spec.scale_factor = 1.0;
  }
  if (choice.direction_deg) spec.direction_deg = *choice.direction_deg;
  spec.validate();
  return spec;
}

}  // namespace pounding::excitation
