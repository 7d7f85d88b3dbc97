#pragma once
// The one list of an impact's fields, read by both writers: summary.json's `impacts` and
// impacts.csv (the streamed and the finished one), so the two files cannot drift apart.
//
// How a field is spelled. A scalar is the JSON key and the CSV column `name_unit` (just `name`
// when it has no unit: counts, 1-based numbers, flags). A pair (a plan point, or the floors of
// building 1 and 2) is a JSON array under `name` and the CSV columns `name_component_unit` (or
// `name_component`), components in array order: `point` -> point_x_m, point_y_m; `floors` ->
// floors_b1, floors_b2. A flag is a JSON boolean and a CSV 1 or 0.

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "pounding/contact/candidates.hpp"
#include "pounding/solvers/run_result.hpp"

namespace pounding::io {

struct ImpactField {
  enum class Type { real, integer, flag };
  std::string_view name;
  std::string_view unit;                     // "s", "m", "mps", "kNs", "kJ"; empty: none
  std::vector<std::string_view> components;  // empty: a scalar; else the array's components
  Type type = Type::real;
  /// The field's value (a scalar) or values (one per component) for an impact.
  std::vector<double> (*values)(const solvers::ImpactRecord& impact) = nullptr;
  std::string_view description{};  // one line, for `pounding outputs` and the docs
  /// The scenes whose runs write the field: every scene's (kEveryScene), or only those with
  /// slab-to-column candidates (contact::has_column_pairs) and/or rows (contact pairs other than
  /// buildings 1 and 2), so that other runs' files keep their columns.
  enum Scenes : unsigned { kEveryScene = 0, kSlabToColumn = 1, kRow = 2 };
  unsigned scenes = kEveryScene;

  /// The JSON key: `name_unit` for a scalar with a unit, else `name`.
  std::string json_key() const;
  /// The CSV columns, as described above.
  std::vector<std::string> csv_columns() const;
};

/// Every field, in output order (`pounding outputs` lists them).
const std::vector<ImpactField>& impact_fields();

/// Which of the fields marked for some scenes only a run writes.
struct ImpactFieldSet {
  bool slab_to_column = false;  // the slab-to-column fields
  bool row = false;             // the row fields
};
/// The set a run with `candidates` writes: slab_to_column when any is slab to column
/// (contact::has_column_pairs), row when any pairs buildings other than 1 and 2.
ImpactFieldSet impact_field_set(const std::vector<contact::Candidate>& candidates);

/// The fields a run writes: those marked for none of the scenes, and those `set` asks for.
std::vector<const ImpactField*> impact_fields(ImpactFieldSet set);

/// One impact as summary.json writes it, keys in field order.
nlohmann::ordered_json impact_json(const solvers::ImpactRecord& impact, ImpactFieldSet set = {});

/// impacts.csv's header columns, in field order.
std::vector<std::string> impact_csv_columns(ImpactFieldSet set = {});

/// One impacts.csv row (comma-separated, no newline); reals in the shortest text that reads back
/// to the same double.
std::string impact_csv_row(const solvers::ImpactRecord& impact, ImpactFieldSet set = {});

}  // namespace pounding::io
