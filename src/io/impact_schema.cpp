#include "pounding/io/impact_schema.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace pounding::io {
namespace {

using Type = ImpactField::Type;
using solvers::ImpactRecord;

std::vector<double> pair(const model::Point2& p) { return {p.x(), p.y()}; }

std::string suffixed(std::string name, std::string_view suffix) {
  if (!suffix.empty()) name += fmt::format("_{}", suffix);
  return name;
}

std::string csv_text(Type type, double value) {
  switch (type) {
    case Type::real: return std::isnan(value) ? std::string() : fmt::format("{}", value);  // NaN: not given
    case Type::integer: return fmt::format("{}", static_cast<long long>(value));
    case Type::flag: return value != 0.0 ? "1" : "0";
  }
  return "";
}

nlohmann::ordered_json json_value(Type type, double value) {
  switch (type) {
    case Type::real: return value;
    case Type::integer: return static_cast<long long>(value);
    case Type::flag: return value != 0.0;
  }
  return nullptr;
}

}  // namespace

std::string ImpactField::json_key() const {
  return components.empty() ? suffixed(std::string(name), unit) : std::string(name);
}

std::vector<std::string> ImpactField::csv_columns() const {
  if (components.empty()) return {json_key()};
  std::vector<std::string> columns;
  for (std::string_view component : components)
    columns.push_back(suffixed(suffixed(std::string(name), component), unit));
  return columns;
}

const std::vector<ImpactField>& impact_fields() {
  // One field a row, as a table.
  // clang-format off
  static const std::vector<ImpactField> kFields = {
      {"t", "s", {}, Type::real, [](const ImpactRecord& i) { return std::vector{i.t_s}; },
       "instant of the impact (a compliant law's: its onset)"},
      {"level", "", {}, Type::integer, [](const ImpactRecord& i) { return std::vector{double(i.level)}; },
       "contact level (1-based; summary.json's levels gives its floors and elevation); 0 slab to column"},
      {"floors", "", {"b1", "b2"}, Type::integer,
       [](const ImpactRecord& i) { return std::vector{double(i.floors[0]), double(i.floors[1])}; },
       "the floor of building 1 and of building 2 at that level; slab to column: the striking slab's floor and the "
       "struck column's storey, in building order"},
      {"elevation", "m", {}, Type::real, [](const ImpactRecord& i) { return std::vector{i.elevation_m}; },
       "the level's elevation above the ground; slab to column: the striking slab's"},
      {"striking_building", "", {}, Type::integer,
       [](const ImpactRecord& i) { return std::vector{double(i.striking_building)}; },
       "the building whose slab strikes (1 or 2; a row: 1-based in the scene): it owns the striking vertex, or, slab "
       "to column, the slab that strikes the column"},
      {"struck_building", "", {}, Type::integer,
       [](const ImpactRecord& i) { return std::vector{double(i.struck_building)}; },
       "the other building of the pair (1-based), whose slab edge or (slab to column) column is struck; in a row, "
       "`floors` are those of the pair's lower-numbered building and of its higher-numbered one",
       ImpactField::kRow | ImpactField::kSlabToColumn},
      {"vertex", "", {}, Type::integer, [](const ImpactRecord& i) { return std::vector{double(i.vertex)}; },
       "the striking vertex's 1-based number in its slab outline; 0 for a column point"},
      {"vertex_rest", "m", {"x", "y"}, Type::real, [](const ImpactRecord& i) { return pair(i.vertex_rest); },
       "that vertex at rest (plan x, y); slab to column: the column's point on its facade"},
      {"struck_edge", "", {}, Type::integer, [](const ImpactRecord& i) { return std::vector{double(i.edge)}; },
       "the struck edge's 1-based number in the other slab's outline (edge n runs from vertex n to n + 1); slab to "
       "column: the striking slab's edge that meets the column"},
      {"point", "m", {"x", "y"}, Type::real, [](const ImpactRecord& i) { return pair(i.point); },
       "where the vertex meets the edge at the impact (plan x, y)"},
      {"approach_velocity", "mps", {}, Type::real,
       [](const ImpactRecord& i) { return std::vector{i.approach_velocity_mps}; },
       "normal closing speed just before the impact (> 0)"},
      {"separation_velocity", "mps", {}, Type::real,
       [](const ImpactRecord& i) { return std::vector{i.separation_velocity_mps}; },
       "normal opening speed just after it"},
      {"impulse", "kNs", {}, Type::real, [](const ImpactRecord& i) { return std::vector{i.impulse_kNs}; },
       "normal impulse (a compliant law's: the integral of its force)"},
      {"duration", "s", {}, Type::real, [](const ImpactRecord& i) { return std::vector{i.duration_s}; },
       "how long a compliant contact lasted; 0 for the impulse law"},
      {"peak_force", "kN", {}, Type::real, [](const ImpactRecord& i) { return std::vector{i.peak_force_kN}; },
       "largest force of a compliant contact; 0 for the impulse law"},
      {"energy_lost", "kJ", {}, Type::real, [](const ImpactRecord& i) { return std::vector{i.energy_lost_kJ}; },
       "energy the impact took from the slabs (compliant laws: the contact force's work)"},
      {"starts_sustained_contact", "", {}, Type::flag,
       [](const ImpactRecord& i) { return std::vector{i.starts_hold ? 1.0 : 0.0}; },
       "true (1) when the pair is held in sustained contact after it"},
      {"column", "", {}, Type::integer, [](const ImpactRecord& i) { return std::vector{double(i.column)}; },
       "slab to column (level 0): the struck column's 1-based number in the struck building's list; 0 slab to slab",
       ImpactField::kSlabToColumn},
      {"height_ratio", "", {}, Type::real, [](const ImpactRecord& i) { return std::vector{i.height_ratio}; },
       "slab to column: where the slab meets the column, as a fraction of its storey's height from the floor below",
       ImpactField::kSlabToColumn},
      {"column_shear", "kN", {}, Type::real, [](const ImpactRecord& i) { return std::vector{i.column_shear_kN}; },
       "slab to column: the larger end shear the peak force causes in the fixed-fixed column",
       ImpactField::kSlabToColumn},
      {"column_moment", "kNm", {}, Type::real, [](const ImpactRecord& i) { return std::vector{i.column_moment_kNm}; },
       "slab to column: the largest bending moment (an end or under the load) the peak force causes in it",
       ImpactField::kSlabToColumn},
      {"column_shear_ratio", "", {}, Type::real, [](const ImpactRecord& i) { return std::vector{i.column_shear_ratio}; },
       "slab to column: column_shear_kN over the column building's column_shear_capacity_kN (above 1: the "
       "column fails in shear, which this model does not follow); empty (CSV) or null (JSON) when no capacity is given",
       ImpactField::kSlabToColumn},
      {"column_total_shear", "kN", {}, Type::real,
       [](const ImpactRecord& i) { return std::vector{i.column_total_shear_kN}; },
       "slab to column: the column's largest shear over the contact with its sway shear, along the axis of its "
       "capacity: the larger of the shears below and above the load (docs/model.md 6b)",
       ImpactField::kSlabToColumn},
      {"column_total_shear_t", "s", {}, Type::real,
       [](const ImpactRecord& i) { return std::vector{i.column_total_shear_t_s}; },
       "slab to column: when column_total_shear was reached (the largest of the samples the contact's steps are "
       "integrated on)",
       ImpactField::kSlabToColumn},
      {"column_sway_shear", "kN", {}, Type::real,
       [](const ImpactRecord& i) { return std::vector{i.column_sway_shear_kN}; },
       "slab to column: the column's sway shear then, along +x or +y (its spring's force, or k times its drift)",
       ImpactField::kSlabToColumn},
      {"column_total_shear_ratio", "", {}, Type::real,
       [](const ImpactRecord& i) { return std::vector{i.column_total_shear_ratio}; },
       "slab to column: column_total_shear_kN over the column's shear capacity (above 1: sway and impact together "
       "exceed it); empty (CSV) or null (JSON) when no capacity is given",
       ImpactField::kSlabToColumn},
  };
  // clang-format on
  return kFields;
}

ImpactFieldSet impact_field_set(const std::vector<contact::Candidate>& candidates) {
  const bool row = std::any_of(candidates.begin(), candidates.end(), [](const contact::Candidate& c) {
    return c.pair != std::array{0, 1};
  });
  return {.slab_to_column = contact::has_column_pairs(candidates), .row = row};
}

std::vector<const ImpactField*> impact_fields(ImpactFieldSet set) {
  std::vector<const ImpactField*> fields;
  for (const ImpactField& field : impact_fields()) {
    const bool wanted = field.scenes == ImpactField::kEveryScene ||
                        (set.slab_to_column && (field.scenes & ImpactField::kSlabToColumn)) ||
                        (set.row && (field.scenes & ImpactField::kRow));
    if (wanted) fields.push_back(&field);
  }
  return fields;
}

nlohmann::ordered_json impact_json(const ImpactRecord& impact, ImpactFieldSet set) {
  nlohmann::ordered_json document;
  for (const ImpactField* field : impact_fields(set)) {
    const std::vector<double> values = field->values(impact);
    if (field->components.empty()) {
      document[field->json_key()] = json_value(field->type, values.front());
      continue;
    }
    nlohmann::ordered_json array = nlohmann::ordered_json::array();
    for (double value : values) array.push_back(json_value(field->type, value));
    document[field->json_key()] = array;
  }
  return document;
}

std::vector<std::string> impact_csv_columns(ImpactFieldSet set) {
  std::vector<std::string> columns;
  for (const ImpactField* field : impact_fields(set)) {
    for (std::string& column : field->csv_columns()) columns.push_back(std::move(column));
  }
  return columns;
}

std::string impact_csv_row(const ImpactRecord& impact, ImpactFieldSet set) {
  std::string row;
  for (const ImpactField* field : impact_fields(set)) {
    for (double value : field->values(impact))
      row += fmt::format("{}{}", row.empty() ? "" : ",", csv_text(field->type, value));
  }
  return row;
}

}  // namespace pounding::io
