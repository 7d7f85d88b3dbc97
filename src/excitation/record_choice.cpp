#include "pounding/excitation/record_choice.hpp"

#include <fmt/format.h>

#include "pounding/input_error.hpp"

namespace pounding::excitation {

bool RecordChoice::empty() const {
  return !file && !format && !units && !dt_s && !accel_column && !scale_factor && !pga_g && !sa && !direction_deg &&
         !second_file && !second_accel_column;
}

namespace {

void require_record_file(const std::string& key, const std::filesystem::path& file) {
  std::error_code unreadable;  // e.g. a name too long for the system: refused like a missing file
  if (!std::filesystem::is_regular_file(file, unreadable)) throw InputError(key, file.string(), "no such record file");
}

/// The choice's second component: a new H2 read as H1 is, or the scene's H2 with another column.
void apply_second(ExcitationSpec& spec, const RecordChoice& choice) {
  if (choice.second_file) {
    require_record_file("excitation.second.file", *choice.second_file);
    spec.second = second_like(spec, *choice.second_file);
  } else if (choice.file) {
    spec.second.reset();
  }
  if (choice.second_accel_column) {
    if (!spec.second) {
      throw InputError("excitation.second.accel_column", std::to_string(*choice.second_accel_column),
                       "there is no second component: name its record file too");
    }
    spec.second->read.accel_column = *choice.second_accel_column;
  }
}

}  // namespace

ExcitationSpec with_record(ExcitationSpec spec, const RecordChoice& choice) {
  if (choice.file) {
    require_record_file("excitation.file", *choice.file);
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
  if (choice.sa && (choice.scale_factor || choice.pga_g)) {
    throw InputError("excitation.scale_to_sa", *choice.sa, "give one scaling: a spectral one, a PGA or a factor");
  }
  if (choice.scale_factor) {
    spec.scale_factor = *choice.scale_factor;
    spec.scale_to_pga_g.reset();
    spec.scale_to_sa.reset();
  }
  if (choice.pga_g) {
    spec.scale_to_pga_g = *choice.pga_g;
    spec.scale_factor = 1.0;
    spec.scale_to_sa.reset();
  }
  if (choice.sa) {
    spec.scale_to_sa = parse_sa_scaling(*choice.sa, "excitation.scale_to_sa");
    spec.scale_factor = 1.0;
    spec.scale_to_pga_g.reset();
  }
  if (choice.direction_deg) spec.direction_deg = *choice.direction_deg;
  apply_second(spec, choice);
  spec.validate();
  return spec;
}

}  // namespace pounding::excitation
