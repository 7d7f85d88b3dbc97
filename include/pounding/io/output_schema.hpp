#pragma once
// The one list of summary.json's per-floor peaks and of its energy audit, and of the columns of
// contacts_history.csv and yielding.csv, read by the writers (run_writer.cpp), the Python module,
// `pounding outputs` and so the docs' column list (docs/guide/output-columns.md). history.csv's
// columns: solvers/history_schema.hpp; impacts: io/impact_schema.hpp.

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "pounding/dynamics/yielding_springs.hpp"
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

/// In output order, group by group.
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

/// In output order.
const std::vector<EnergyField>& energy_fields();

/// A column of contacts_history.csv (a row per contact carrying a force, at each history
/// instant). Its value is a double: the identity columns are whole numbers, which the CSV writer
/// ({fmt}'s shortest form) writes without a decimal point.
struct ContactForceColumn {
  std::string_view name;  // CSV header, unit suffixed
  std::string_view unit;  // empty: an index or a 1-based number
  std::string_view description;
  double (*value)(const solvers::ContactForceSample& sample) = nullptr;
};

/// In output order.
const std::vector<ContactForceColumn>& contact_force_columns();

/// A column of yielding.csv (a row per yielding column spring: one column of a storey, along x
/// or y), with its cell's text as the CSV holds it.
struct YieldingColumn {
  enum class Kind { integer, real, text };  // a real may be empty (first_yield_t_s: never yielded)
  std::string_view name;
  std::string_view unit;  // empty: a count, a name or a ratio
  Kind kind;
  std::string_view description;
  std::string (*cell)(const dynamics::YieldingSpring& spring, const solvers::SpringResult& result) = nullptr;
  bool shear_capacity_only = false;  // written only when some column has a shear capacity
  bool degrading_only = false;       // written only when some column's law degrades (IMK)
};

/// In output order.
const std::vector<YieldingColumn>& yielding_columns();
/// Those a run's yielding.csv holds: all, without the shear-capacity ones when no spring of
/// `springs` has a capacity, and without the degrading ones when none degrades.
std::vector<YieldingColumn> yielding_columns(const std::vector<dynamics::YieldingSpring>& springs);

/// The names of a file's columns (contact_force_columns(), yielding_columns()), in order: its header.
template <class Column>
std::vector<std::string> column_names(const std::vector<Column>& columns) {
  std::vector<std::string> names;
  names.reserve(columns.size());
  for (const Column& c : columns) names.emplace_back(c.name);
  return names;
}

/// Every output field, as `pounding outputs --json` prints it and pounding.output_schema()
/// returns it: `history` (column pattern, unit, per, description), `impacts` (JSON key, CSV
/// columns, unit, description), `peaks` (key, unit, group, description), `energy` (key, unit,
/// description), `contact_forces` (column, unit, description), `yielding` (column, unit, kind,
/// description).
nlohmann::ordered_json output_schema_json();

}  // namespace pounding::io
