#pragma once
// A record and its scaling chosen outside the scene file (`run --record ...`, a line of a record
// list), applied over the scene's [excitation] so that one scene serves many records.

#include <filesystem>
#include <optional>
#include <string>

#include "pounding/excitation/ground_motion.hpp"

namespace pounding::excitation {

/// What replaces the scene's record or its scaling; every unset field keeps the scene's value.
struct RecordChoice {
  /// A new record file, already resolved (relative paths are the caller's business). Replacing
  /// the record drops the keys that describe the old file: dt_s, time_column, accel_column,
  /// start_s, duration_s (the fields below may set dt_s and accel_column again).
  std::optional<std::filesystem::path> file{};
  std::optional<std::string> format{};   // "peer-at2", "columns", "single"
  std::optional<std::string> units{};    // kAccelUnitChoices (ground_motion.hpp)
  std::optional<double> dt_s{};          // as the key excitation.dt_s
  std::optional<int> accel_column{};     // as the key excitation.accel_column
  std::optional<double> scale_factor{};  // replaces scale_factor and drops scale_to_pga_g
  std::optional<double> pga_g{};         // replaces scale_to_pga_g and resets scale_factor to 1
  std::optional<std::string> sa{};       // "0.5g@T1": replaces the scaling by scale_to_sa (parse_sa_scaling)
  std::optional<double> direction_deg{};
  /// A pair's second component (H2, along direction + 90°), already resolved: read with the
  /// (new) record's format and units. Setting `file` without it drops the scene's H2 (it belongs
  /// to the old record).
  std::optional<std::filesystem::path> second_file{};
  std::optional<int> second_accel_column{};  // as the key excitation.second.accel_column

  bool empty() const;
};

/// `spec` with `choice` applied, validated (ExcitationSpec::validate()) and, when `choice` sets
/// a file, that file checked to exist. The record itself is not read.
/// @throws InputError keyed as the scene keys are (`excitation.file`, `excitation.format`,
///   `excitation.units`, `excitation.scale_factor` for scale_factor, `excitation.scale_to_pga_g`
///   for pga_g, `excitation.second.file`, ...) for an unknown format or unit, a missing file,
///   scale_factor and pga_g together, a second component's column without a second component,
///   or a value out of its range; callers rename the key to what the user typed.
ExcitationSpec with_record(ExcitationSpec spec, const RecordChoice& choice);

}  // namespace pounding::excitation
