#pragma once
// The one list of summary.json's per-floor peaks and of its energy audit, read by the writer
// (run_writer.cpp), by `pounding outputs` and so by the docs' column list
// (docs/guide/output-columns.md). history.csv's columns: solvers/history_schema.hpp; impacts:
// io/impact_schema.hpp.

#include <nlohmann/json.hpp>
#include <string_view>
#include <vector>

#include "pounding/solvers/run_result.hpp"

namespace pounding::io {

/// A peak every floor reports when its group is asked for (`[output] peaks`): the JSON key under
/// `peaks[].floors[]`, holding `value` (the largest |x|, with its sign) and `t_s` (when).
struct PeakField {
  enum class Group { displacements, accelerations, drifts };  // analysis::kPeakGroups, in order
  Group group;
  std::string_view key;   // e.g. "u_m"; a list (one peak per vertex or corner) ends in neither
  std::string_view unit;  // "m", "rad", "mps2", "radps2"; empty: a ratio or a record
  std::string_view description;
  /// The field's JSON value for `floor`; accelerations in m/s² also carry `value_g` (`g_mps2`).
  nlohmann::ordered_json (*value)(const solvers::FloorPeaks& floor, double g_mps2) = nullptr;
};

/// In output order: u_m, v_m, phi_rad, vertex_dx_m; ax_abs_mps2, ay_abs_mps2, phi_ddot_radps2;
/// drift_x, drift_y, corner_drift_x, corner_drift_y, worst_corner_drift.
const std::vector<PeakField>& peak_fields();

/// Whether `outputs` asked for `group`.
bool asked(const solvers::OutputSelection& outputs, PeakField::Group group);

/// A number of the energy audit (summary.json `energy`), in kJ unless `unit` says otherwise.
struct EnergyField {
  std::string_view key;   // JSON key, unit suffixed
  std::string_view unit;  // "kJ"; empty: a ratio
  std::string_view description;
  double (*value)(const solvers::EnergyAudit& energy) = nullptr;
  bool yielding_only = false;  // written only for runs whose columns yield
};

/// In output order: input, kinetic and strain energy at the end, damping, impact loss,
/// constraint work, algorithmic dissipation, residual, relative residual.
const std::vector<EnergyField>& energy_fields();

/// Every output field, as `pounding outputs --json` prints it and pounding.output_schema()
/// returns it: `history` (column pattern, unit, per, description), `impacts` (JSON key, CSV
/// columns, unit, description), `peaks` (key, unit, group, description), `energy` (key, unit,
/// description).
nlohmann::ordered_json output_schema_json();

}  // namespace pounding::io
