#include "pounding/io/scene_reader.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <tuple>
#include <vector>

namespace pounding::io::detail {
/// A failed internal check of toml++. @throws TomlCheckFailed always.
[[noreturn]] void toml_check_failed(const char* expression);
struct TomlCheckFailed : std::logic_error {
  using std::logic_error::logic_error;
};
}  // namespace pounding::io::detail

// toml++ 3.3's internal checks fail on some malformed scenes (fuzzing found "[+a]":
// parser.inl:3037, parse_key). Built with NDEBUG they become optimiser assumptions, so such a
// file is undefined behaviour wherever toml++ is compiled from its headers (as in the
// sanitizer build) by clang. Here they stay on and throw instead, and the scene is refused.
#define TOML_ASSERT(expr) ((expr) ? static_cast<void>(0) : ::pounding::io::detail::toml_check_failed(#expr))
#pragma push_macro("NDEBUG")
#undef NDEBUG
#include <toml++/toml.h>
#pragma pop_macro("NDEBUG")

#include "pounding/analysis/limit_states.hpp"
#include "pounding/analysis/run_scene.hpp"
#include "pounding/input_error.hpp"
#include "toml_text.hpp"

namespace pounding::io {

void detail::toml_check_failed(const char* expression) { throw TomlCheckFailed(expression); }

namespace {

using model::Point2;

constexpr std::size_t kMaxShownChars = 80;  // longer values are cut in messages

/// A value as the user typed it, for error messages. Formatted here with fmt, never by toml++'s
/// own formatter: that one reaches undefined behaviour for some doubles (toml++ 3.3,
/// toml_formatter.inl:94, a negative log10 converted to unsigned long).
std::string node_text(const toml::node& node) {
  std::string text;
  if (const auto* v = node.as_floating_point()) {
    text = format_value(v->get());
  } else if (const auto* v = node.as_integer()) {
    text = fmt::format("{}", v->get());
  } else if (const auto* v = node.as_boolean()) {
    text = v->get() ? "true" : "false";
  } else if (const auto* v = node.as_string()) {
    text = fmt::format("\"{}\"", v->get());
  } else if (const auto* v = node.as_array()) {
    text = "[";
    for (std::size_t i = 0; i < v->size() && text.size() < kMaxShownChars; ++i) {
      text += (i ? ", " : "") + node_text(*v->get(i));
    }
    text += "]";
  } else if (node.is_table()) {
    text = "{...}";
  } else if (const auto* v = node.as_date()) {
    text = fmt::format("{:04}-{:02}-{:02}", v->get().year, v->get().month, v->get().day);
  } else if (const auto* v = node.as_time()) {
    text = fmt::format("{:02}:{:02}:{:02}", v->get().hour, v->get().minute, v->get().second);
  } else if (node.is_date_time()) {
    text = "a date-time";
  }
  if (text.size() > kMaxShownChars) text = text.substr(0, kMaxShownChars) + "...";
  return text;
}

/// Levenshtein distance (insertions, deletions, substitutions), for "did you mean" hints.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitution = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
      diagonal = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, substitution});
    }
  }
  return row[b.size()];
}

/// The name among `names` closest to `key`, if it is a plausible typo of it: at most two edits,
/// and fewer than half the key's length (so "x" does not suggest "y").
std::optional<std::string> closest_name(std::string_view key, const std::vector<std::string>& names) {
  std::optional<std::string> best;
  std::size_t best_distance = std::min<std::size_t>(3, (key.size() + 1) / 2);
  for (const std::string& name : names) {
    const std::size_t distance = edit_distance(key, name);
    if (distance > 0 && distance < best_distance) best = name, best_distance = distance;
  }
  return best;
}

std::string located(const std::string& file, const toml::node& node) {
  const auto line = node.source().begin.line;
  return line > 0 ? fmt::format("{}:{}", file, line) : file;
}

/// One TOML table being read: remembers which keys were used so that leftovers (typos, keys
/// from another version) are reported instead of silently ignored.
class TableReader {
 public:
  TableReader(const toml::table& table, std::string path, std::string file)
      : table_(table), path_(std::move(path)), file_(std::move(file)) {}

  std::string key_path(std::string_view key) const {
    return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
  }
  const std::string& file() const { return file_; }

  const toml::node* find(std::string_view key) {
    used_.insert(std::string(key));
    return table_.get(key);
  }
  bool has(std::string_view key) const { return table_.contains(key); }
  /// Keys of this table that no lookup has asked for yet (unknown so far).
  std::vector<std::string> unasked_keys() const {
    std::vector<std::string> keys;
    for (const auto& [key, node] : table_) {
      if (!used_.count(std::string(key.str()))) keys.emplace_back(key.str());
    }
    return keys;
  }

  const toml::node& require(std::string_view key) {
    const toml::node* node = find(key);
    if (!node) {
      // A required key is looked up before unknown keys are reported: name the typo here.
      const std::optional<std::string> typo = closest_name(key, unasked_keys());
      throw InputError(key_path(key), "missing",
                       typo ? fmt::format("this key is required (is \"{}\" a typo of it?)", *typo)
                            : std::string("this key is required"),
                       located(file_, table_));
    }
    return *node;
  }

  InputError error(const toml::node& node, const std::string& key, const std::string& reason) const {
    return InputError(key, node_text(node), reason, located(file_, node));
  }

  double number_of(const toml::node& node, const std::string& key) const {
    if (const auto value = node.value<double>(); value && node.is_number()) return *value;
    throw error(node, key, "expected a number");
  }

  double number(std::string_view key) { return number_of(require(key), key_path(key)); }
  std::optional<double> optional_number(std::string_view key) {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    return number_of(*node, key_path(key));
  }
  double number_or(std::string_view key, double fallback) { return optional_number(key).value_or(fallback); }

  int integer_of(const toml::node& node, const std::string& key) const {
    if (!node.is_integer()) throw error(node, key, "expected a whole number");
    const auto value = *node.value<std::int64_t>();
    if (value < -1000000 || value > 1000000) throw error(node, key, "is out of range");
    return static_cast<int>(value);
  }
  int integer(std::string_view key) { return integer_of(require(key), key_path(key)); }
  std::optional<int> optional_integer(std::string_view key) {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    return integer_of(*node, key_path(key));
  }

  std::string string_of(const toml::node& node, const std::string& key) const {
    if (!node.is_string()) throw error(node, key, "expected a string");
    return *node.value<std::string>();
  }
  std::string string(std::string_view key) { return string_of(require(key), key_path(key)); }
  std::optional<std::string> optional_string(std::string_view key) {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    return string_of(*node, key_path(key));
  }

  std::optional<bool> optional_boolean(std::string_view key) {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    if (!node->is_boolean()) throw error(*node, key_path(key), "expected true or false");
    return **node->as_boolean();
  }

  const toml::array& array_of(const toml::node& node, const std::string& key) const {
    if (!node.is_array()) throw error(node, key, "expected an array");
    return *node.as_array();
  }

  std::vector<double> numbers_of(const toml::node& node, const std::string& key,
                                 std::optional<std::size_t> size = {}) const {
    const toml::array& array = array_of(node, key);
    if (size && array.size() != *size) {
      throw error(node, key, fmt::format("expected {} numbers", *size));
    }
    std::vector<double> values;
    for (std::size_t i = 0; i < array.size(); ++i) {
      values.push_back(number_of(array[i], fmt::format("{}[{}]", key, i + 1)));
    }
    return values;
  }

  Point2 point_of(const toml::node& node, const std::string& key) const {
    const auto xy = numbers_of(node, key, 2);
    return {xy[0], xy[1]};
  }

  TableReader subtable(std::string_view key) {
    const toml::node& node = require(key);
    if (!node.is_table()) throw error(node, key_path(key), "expected a table");
    return TableReader(*node.as_table(), key_path(key), file_);
  }
  std::optional<TableReader> optional_subtable(std::string_view key) {
    if (!has(key)) return std::nullopt;
    return subtable(key);
  }

  /// @throws InputError for the first key that was never asked for.
  void finish() const {
    for (const auto& [key, node] : table_) {
      if (!used_.count(std::string(key.str()))) {
        const std::optional<std::string> known =
            closest_name(key.str(), std::vector<std::string>(used_.begin(), used_.end()));
        throw InputError(key_path(key.str()), node_text(node),
                         known ? fmt::format("unknown key (did you mean \"{}\"?)", *known) : std::string("unknown key"),
                         located(file_, node));
      }
    }
  }

 private:
  const toml::table& table_;
  std::string path_;
  std::string file_;
  std::set<std::string> used_;
};

/// A number that must be positive and finite, checked where it is read so that the error of a
/// single value standing for every floor names the key typed, not an index the user never wrote.
double positive(TableReader& table, const toml::node& node, const std::string& key) {
  const double value = table.number_of(node, key);
  if (!(value > 0.0) || !std::isfinite(value)) throw table.error(node, key, "must be a positive finite number");
  return value;
}

/// A number within its physical range, checked where it is read (see positive()).
double in_range(TableReader& table, const toml::node& node, const std::string& key, const Range& range) {
  const double value = table.number_of(node, key);
  try {
    require_range(key, value, range);
  } catch (const InputError& error) {
    throw table.error(node, key, error.reason());
  }
  return value;
}

/// A per-storey value: one number for every storey (checked here, under the key typed), or a list
/// of one a storey, storey 1 (the ground storey) first (checked entry by entry by validate());
/// empty if the key is absent.
std::vector<double> per_storey(TableReader& table, const char* name, const Range& range, int storeys) {
  const toml::node* node = table.find(name);
  if (node == nullptr) return {};
  const std::string key = table.key_path(name);
  if (node->is_array()) return table.numbers_of(*node, key);
  return std::vector<double>(std::max(storeys, 0), in_range(table, *node, key, range));
}

std::vector<double> storey_heights(TableReader& table, int storeys) {
  table.require("storey_height_m");
  return per_storey(table, "storey_height_m", model::kStoreyHeightRange, storeys);
}

std::vector<double> per_floor_masses(TableReader& table, int storeys) {
  const toml::node& node = table.require("mass_t");
  const std::string key = table.key_path("mass_t");
  const toml::node* top = table.find("top_floor_mass_t");
  if (node.is_array()) {
    if (top) throw table.error(*top, table.key_path("top_floor_mass_t"), "only with a single mass_t value");
    return table.numbers_of(node, key);
  }
  std::vector<double> masses(std::max(storeys, 0), positive(table, node, key));
  if (top && !masses.empty()) {
    masses.back() = in_range(table, *top, table.key_path("top_floor_mass_t"), model::kFloorMass);
  }
  return masses;
}

std::vector<double> polar_moments(TableReader& table, const model::BuildingDefinition& b) {
  const toml::node* node = table.find("polar_moment_tm2");
  const std::string key = table.key_path("polar_moment_tm2");
  if (node && node->is_array()) return table.numbers_of(*node, key);
  if (node && node->is_number()) return std::vector<double>(b.mass_t.size(), positive(table, *node, key));
  if (node && !(node->is_string() && *node->value<std::string>() == "uniform")) {
    throw table.error(*node, key, "expected \"uniform\", a number or one number per floor");
  }
  // "uniform" (the default) needs a valid slab; skip it here if the slab is broken so that
  // validation reports the slab rather than a meaningless moment.
  std::vector<double> moments;
  if (b.slab.size() < 3 || !(b.slab.signed_area() > 0.0)) return std::vector<double>(b.mass_t.size(), 1.0);
  for (double mass : b.mass_t) moments.push_back(model::uniform_polar_moment(b.slab, mass));
  return moments;
}

/// One entry of `columns` given as a table: `x`, `y` (m), `b_m`, `h_m` (m) and optionally its own
/// `yield_force_kN` and `shear_capacity_kN` (one number or one a storey).
model::Column column_of_table(TableReader& table, const toml::node& node, const std::string& key, int storeys) {
  TableReader entry(*node.as_table(), key, table.file());
  model::Column column;
  column.position_m = Point2(entry.number("x"), entry.number("y"));
  column.b_m = in_range(entry, entry.require("b_m"), entry.key_path("b_m"), model::kColumnSize);
  column.h_m = in_range(entry, entry.require("h_m"), entry.key_path("h_m"), model::kColumnSize);
  column.yield_force_kN = per_storey(entry, "yield_force_kN", model::kColumnYieldForce, storeys);
  column.shear_capacity_kN = per_storey(entry, "shear_capacity_kN", model::kColumnShearCapacity, storeys);
  entry.finish();
  return column;
}

std::vector<model::Column> read_columns(TableReader& table, int storeys) {
  std::vector<model::Column> columns;
  if (const toml::node* node = table.find("columns")) {
    const std::string key = table.key_path("columns");
    const toml::array& array = table.array_of(*node, key);
    if (array.size() > model::kMaxColumns) {
      throw table.error(*node, key,
                        fmt::format("{} columns: a storey may have at most {}", array.size(), model::kMaxColumns));
    }
    for (std::size_t i = 0; i < array.size(); ++i) {
      const std::string entry_key = fmt::format("{}[{}]", key, i + 1);
      if (array[i].is_table()) {
        columns.push_back(column_of_table(table, array[i], entry_key, storeys));
        columns.back().key = fmt::format("columns[{}]", i + 1);
        continue;
      }
      if (!array[i].is_array()) {
        throw table.error(array[i], entry_key, "expected [x, y, b, h] or a table {x, y, b_m, h_m, ...}");
      }
      const auto v = table.numbers_of(array[i], entry_key, 4);
      columns.push_back({Point2(v[0], v[1]), v[2], v[3]});
    }
  }
  if (const toml::node* node = table.find("column_grid")) {
    const std::string key = table.key_path("column_grid");
    const toml::array& grids = table.array_of(*node, key);
    for (std::size_t g = 0; g < grids.size(); ++g) {
      const std::string grid_key = fmt::format("{}[{}]", key, g + 1);
      if (!grids[g].is_table()) throw table.error(grids[g], grid_key, "expected a table");
      TableReader grid(*grids[g].as_table(), grid_key, table.file());
      const auto xs = grid.numbers_of(grid.require("x"), grid.key_path("x"));
      const auto ys = grid.numbers_of(grid.require("y"), grid.key_path("y"));
      const double b = in_range(grid, grid.require("b_m"), grid.key_path("b_m"), model::kColumnSize);
      const double h = in_range(grid, grid.require("h_m"), grid.key_path("h_m"), model::kColumnSize);
      // One number for every storey or one a storey (a list checked by validate()).
      const std::vector<double> yield_force_kN = per_storey(grid, "yield_force_kN", model::kColumnYieldForce, storeys);
      const std::vector<double> shear_capacity_kN =
          per_storey(grid, "shear_capacity_kN", model::kColumnShearCapacity, storeys);
      grid.finish();
      // Counted before a column is made: 10 000 × 10 000 would be 10⁸ columns from 150 kB of text.
      const double total = static_cast<double>(columns.size()) + static_cast<double>(xs.size()) * ys.size();
      if (total > static_cast<double>(model::kMaxColumns)) {
        throw table.error(grids[g], grid_key,
                          fmt::format("{} x {} = {} columns (with those listed before): a storey may have at most {}",
                                      xs.size(), ys.size(), xs.size() * ys.size(), model::kMaxColumns));
      }
      // Each named by its grid lines, so a message points at the x or y value to change.
      for (std::size_t iy = 0; iy < ys.size(); ++iy) {
        for (std::size_t ix = 0; ix < xs.size(); ++ix) {
          columns.push_back({Point2(xs[ix], ys[iy]), b, h,
                             fmt::format("column_grid[{}] x[{}] y[{}]", g + 1, ix + 1, iy + 1), yield_force_kN,
                             shear_capacity_kN});
        }
      }
    }
  }
  return columns;
}

Eigen::Matrix3d matrix_of(TableReader& table, const toml::node& node, const std::string& key) {
  const toml::array& rows = table.array_of(node, key);
  if (rows.size() != 3) throw table.error(node, key, "expected a 3x3 matrix (3 rows of 3 numbers)");
  Eigen::Matrix3d matrix;
  for (int r = 0; r < 3; ++r) {
    const auto row = table.numbers_of(rows[r], fmt::format("{}[{}]", key, r + 1), 3);
    for (int c = 0; c < 3; ++c) matrix(r, c) = row[c];
  }
  return matrix;
}

std::vector<Eigen::Matrix3d> storey_matrices(TableReader& table, const toml::node& node, int storeys) {
  const std::string key = table.key_path("storey_stiffness");
  const toml::array& array = table.array_of(node, key);
  // One 3×3 matrix (rows of numbers) applies to every storey; otherwise one matrix a storey.
  const bool single = !array.empty() && array[0].is_array() && !array[0].as_array()->empty() &&
                      array[0].as_array()->get(0)->is_number();
  if (single) return std::vector<Eigen::Matrix3d>(std::max(storeys, 0), matrix_of(table, node, key));
  std::vector<Eigen::Matrix3d> matrices;
  for (std::size_t i = 0; i < array.size(); ++i) {
    matrices.push_back(matrix_of(table, array[i], fmt::format("{}[{}]", key, i + 1)));
  }
  return matrices;
}

void read_stiffness(TableReader& table, model::BuildingDefinition& b) {
  if (const toml::node* node = table.find("storey_stiffness")) {
    for (const char* other :
         {"columns", "column_grid", "E_kPa", "frame_factor", "target_period_s", "column_shear_capacity_kN",
          "column_shear_failure", "shear_capacity", "flexural_strength", "slab_thickness_m"}) {
      if (table.has(other)) {
        throw table.error(*node, table.key_path("storey_stiffness"),
                          fmt::format("give either storey_stiffness or columns with {}, not both", other));
      }
    }
    b.storey_stiffness = storey_matrices(table, *node, b.storeys);
    return;
  }
  b.columns = read_columns(table, b.storeys);
  b.E_kPa = table.number("E_kPa");
  const toml::node* factor = table.find("frame_factor");
  const toml::node* period = table.find("target_period_s");
  if (factor && period) {
    throw table.error(*period, table.key_path("target_period_s"),
                      "give either frame_factor or target_period_s, not both");
  }
  if (!factor && !period) {
    throw InputError(table.key_path("frame_factor"), "missing", "give frame_factor or target_period_s", table.file());
  }
  if (factor) b.frame_factor = table.number_of(*factor, table.key_path("frame_factor"));
  if (period) b.target_period_s = table.number_of(*period, table.key_path("target_period_s"));
  b.column_shear_capacity_kN = per_storey(table, "column_shear_capacity_kN", model::kColumnShearCapacity, b.storeys);
  b.slab_thickness_m = table.optional_number("slab_thickness_m");
  b.column_shear_failure = table.optional_string("column_shear_failure").value_or(b.column_shear_failure);
}

/// For read_keys(): no row of the table is required.
constexpr auto kNoneRequired = [](const auto&) { return false; };

/// Reads each row's key of `table` into its member of `owner`; an absent key leaves the member as
/// it is, unless `required(row)`. A per-storey key's single number is spread over `storeys`.
template <typename Owner, typename Required>
void read_keys(TableReader& table, Owner& owner, std::span<const KeySpec<Owner>> specs, const Required& required,
               int storeys = 0) {
  for (const KeySpec<Owner>& spec : specs) {
    std::visit(
        [&](auto Owner::*member) {
          auto& value = owner.*member;
          using T = std::decay_t<decltype(value)>;
          if constexpr (std::is_same_v<T, std::string>) {
            value = table.optional_string(spec.key).value_or(value);
          } else if constexpr (std::is_same_v<T, double>) {
            value = required(spec) ? table.number(spec.key) : table.number_or(spec.key, value);
          } else if constexpr (std::is_same_v<T, long>) {
            value = table.optional_integer(spec.key).value_or(value);
          } else if constexpr (std::is_same_v<T, bool>) {
            value = table.optional_boolean(spec.key).value_or(value);
          } else if constexpr (std::is_same_v<T, std::vector<double>>) {
            if (required(spec)) table.require(spec.key);
            value = per_storey(table, spec.key.data(), *spec.range, storeys);
          } else {
            value = table.optional_number(spec.key);
          }
        },
        spec.member);
  }
}

/// Refuses a row's key given while the table's selector `selector` (e.g. `law`) has a value the
/// row does not apply to (KeySpec::applies_to).
template <typename Owner>
void refuse_inapplicable(TableReader& table, std::span<const KeySpec<Owner>> specs, std::string_view selector,
                         const std::string& chosen) {
  for (const KeySpec<Owner>& spec : specs) {
    const toml::node* given = table.find(spec.key);
    if (given == nullptr || spec.applies_to.empty() ||
        std::find(spec.applies_to.begin(), spec.applies_to.end(), chosen) != spec.applies_to.end())
      continue;
    throw table.error(*given, table.key_path(spec.key),
                      fmt::format("applies to {} = {} only (the {} is {})", selector, or_list(spec.applies_to, true),
                                  selector, chosen));
  }
}

/// [building.hysteresis]: `law`, then its rows (model::hysteresis_specs()).
model::HystereticLaw read_hysteresis(TableReader& table, int storeys) {
  model::HystereticLaw law;
  const toml::node& kind = table.require("law");
  const std::string name = table.string_of(kind, table.key_path("law"));
  const std::span<const std::string_view> names = model::hysteretic_law_names();
  const auto found = std::find(names.begin(), names.end(), name);
  if (found == names.end()) {
    std::vector<std::string> quoted;
    for (std::string_view known : names.first(names.size() - 1)) quoted.push_back(fmt::format("\"{}\"", known));
    throw table.error(kind, table.key_path("law"),
                      fmt::format("expected {} or \"{}\"", fmt::join(quoted, ", "), names.back()));
  }
  law.kind = static_cast<model::HystereticLaw::Kind>(found - names.begin());
  refuse_inapplicable(table, model::hysteresis_specs(), "law", name);
  read_keys(table, law, model::hysteresis_specs(), kNoneRequired, storeys);
  table.finish();
  return law;
}

/// A table whose keys are all `specs`' rows ([building.limit_states], [building.shear_capacity]),
/// its required ones required.
template <typename Owner>
Owner read_table_of_keys(TableReader table, std::span<const analysis::KeySpec<Owner>> specs, int storeys = 0) {
  Owner owner;
  read_keys(
      table, owner, specs, [](const analysis::KeySpec<Owner>& spec) { return spec.required; }, storeys);
  table.finish();
  return owner;
}

model::BuildingDefinition read_building(TableReader table) {
  model::BuildingDefinition b;
  b.name = table.string("name");
  b.storeys = table.integer("storeys");
  b.storey_height_m = storey_heights(table, b.storeys);
  {
    const std::string key = table.key_path("slab");
    const toml::array& vertices = table.array_of(table.require("slab"), key);
    if (vertices.size() > model::kMaxSlabVertices) {
      throw table.error(
          vertices, key,
          fmt::format("{} vertices: a slab may have at most {}", vertices.size(), model::kMaxSlabVertices));
    }
    std::vector<Point2> points;
    for (std::size_t i = 0; i < vertices.size(); ++i) {
      points.push_back(table.point_of(vertices[i], fmt::format("{}[{}]", key, i + 1)));
    }
    b.slab = model::Polygon(std::move(points));
  }
  b.centre_of_mass = table.point_of(table.require("centre_of_mass"), table.key_path("centre_of_mass"));
  b.mass_t = per_floor_masses(table, b.storeys);
  b.polar_moment_tm2 = polar_moments(table, b);
  read_stiffness(table, b);
  if (auto damping = table.optional_subtable("damping")) {
    b.damping.ratio = damping->number_or("ratio", b.damping.ratio);
    if (const toml::node* modes = damping->find("modes")) {
      const std::string key = damping->key_path("modes");
      const toml::array& array = damping->array_of(*modes, key);
      if (array.size() != 2) throw damping->error(*modes, key, "expected two mode numbers");
      b.damping.modes = {damping->integer_of(array[0], key + "[1]"), damping->integer_of(array[1], key + "[2]")};
    }
    damping->finish();
  }
  if (auto hysteresis = table.optional_subtable("hysteresis")) b.hysteresis = read_hysteresis(*hysteresis, b.storeys);
  if (auto limits = table.optional_subtable("limit_states"))
    b.drift_limits = read_table_of_keys(*limits, analysis::drift_limit_specs());
  if (auto capacity = table.optional_subtable("shear_capacity"))
    b.shear_capacity = read_table_of_keys(*capacity, analysis::shear_capacity_specs());
  if (auto strength = table.optional_subtable("flexural_strength"))
    b.flexural_strength = read_table_of_keys(*strength, analysis::flexural_strength_specs(), b.storeys);
  if (const toml::node* p_delta = table.find("p_delta")) {
    if (!p_delta->is_boolean()) throw table.error(*p_delta, table.key_path("p_delta"), "expected true or false");
    b.p_delta = **p_delta->as_boolean();
  }
  table.finish();
  return b;
}

/// A record file named by `file` in `table`, resolved against the scene's folder; refused if missing.
std::filesystem::path read_record_file(TableReader& table, const std::filesystem::path& scene_dir) {
  const toml::node& file_node = table.require("file");
  const std::filesystem::path file = table.string_of(file_node, table.key_path("file"));
  std::filesystem::path resolved = (file.is_absolute() ? file : scene_dir / file).lexically_normal();
  std::error_code unreadable;  // e.g. a name too long for the system: refused like a missing file
  if (!std::filesystem::is_regular_file(resolved, unreadable)) {
    throw table.error(file_node, table.key_path("file"),
                      fmt::format("no such record file (looked for {})", resolved.string()));
  }
  return resolved;
}

/// `format` and `units`: required for H1; a pair's H2 takes H1's when it leaves them out.
void read_format_and_units(TableReader& table, excitation::RecordReadOptions& read, excitation::AccelUnits& units,
                           bool required) {
  if (required || table.has("format")) {
    const toml::node& format_node = table.require("format");
    const auto format = excitation::parse_record_format(table.string_of(format_node, table.key_path("format")));
    if (!format) throw table.error(format_node, table.key_path("format"), "expected peer-at2, columns or single");
    read.format = *format;
  }
  if (required || table.has("units")) {
    const toml::node& units_node = table.require("units");
    const auto parsed = excitation::parse_accel_units(table.string_of(units_node, table.key_path("units")));
    if (!parsed)
      throw table.error(units_node, table.key_path("units"), fmt::format("expected {}", excitation::kAccelUnitChoices));
    units = *parsed;
  }
}

/// dt_s (the spacing of a `single` file, else a re-spacing) and the columns.
void read_layout(TableReader& table, excitation::RecordReadOptions& read, std::optional<double>& dt_override_s) {
  const std::optional<double> dt = table.optional_number("dt_s");
  if (read.format == excitation::RecordFormat::single) {
    read.dt_s = dt;
  } else {
    dt_override_s = dt;
  }
  read.time_column = table.optional_integer("time_column").value_or(1);
  read.accel_column = table.optional_integer("accel_column");
}

/// [excitation.second]: H2 of a pair; what it leaves out is read as H1 is (excitation::second_like).
excitation::SecondComponentSpec read_second_component(TableReader table, const std::filesystem::path& scene_dir,
                                                      const excitation::ExcitationSpec& first) {
  excitation::SecondComponentSpec second = excitation::second_like(first, read_record_file(table, scene_dir));
  const excitation::RecordFormat h1_format = second.read.format;
  read_format_and_units(table, second.read, second.units, false);
  if (second.read.format != h1_format) {  // another layout: H1's spacing and columns mean nothing for it
    second.read = {.format = second.read.format};
    second.dt_override_s.reset();
  }
  const excitation::RecordReadOptions inherited = second.read;
  const std::optional<double> inherited_respacing = second.dt_override_s;
  read_layout(table, second.read, second.dt_override_s);
  if (!table.has("dt_s")) second.read.dt_s = inherited.dt_s, second.dt_override_s = inherited_respacing;
  if (!table.has("time_column")) second.read.time_column = inherited.time_column;
  table.finish();
  return second;
}

excitation::ExcitationSpec read_excitation(TableReader table, const std::filesystem::path& scene_dir) {
  excitation::ExcitationSpec spec;
  spec.file = read_record_file(table, scene_dir);
  read_format_and_units(table, spec.read, spec.units, true);
  read_layout(table, spec.read, spec.dt_override_s);
  read_keys(table, spec, excitation::excitation_specs(), kNoneRequired);
  if (const std::optional<std::string> sa = table.optional_string("scale_to_sa")) {
    spec.scale_to_sa = excitation::parse_sa_scaling(*sa, table.key_path("scale_to_sa"));
  }
  if (auto second = table.optional_subtable("second")) spec.second = read_second_component(*second, scene_dir, spec);
  table.finish();
  return spec;
}

analysis::SolverSettings read_solver(std::optional<TableReader> table) {
  analysis::SolverSettings solver;
  if (!table) return solver;
  // Unset keys stay unset: the method's defaults fill them (analysis::resolve), and a key set
  // for a method that does not use it is refused by Scene::validate().
  solver.method = table->optional_string("method").value_or(solver.method);
  for (const analysis::SettingSpec& spec : analysis::setting_specs()) {
    std::optional<analysis::SettingValue> value;
    switch (spec.member.index()) {  // the setting's type (SettingSpec::member)
      case 0: value = table->optional_integer(spec.key); break;
      case 1: value = table->optional_number(spec.key); break;
      default: value = table->optional_string(spec.key); break;
    }
    if (value) solver.set(spec.id, *value);
  }
  table->finish();
  return solver;
}

/// [output.floor_history]: building name = [floors]; names and ranges are Scene::validate's.
std::vector<std::pair<std::string, std::vector<int>>> read_floor_history(TableReader& table) {
  std::vector<std::pair<std::string, std::vector<int>>> floors;
  for (const std::string& name : table.unasked_keys()) {
    const std::string key = table.key_path(name);
    const toml::array& array = table.array_of(*table.find(name), key);
    std::vector<int>& listed = floors.emplace_back(name, std::vector<int>{}).second;
    for (std::size_t i = 0; i < array.size(); ++i) {
      listed.push_back(table.integer_of(array[i], fmt::format("{}[{}]", key, i + 1)));
    }
  }
  return floors;
}

analysis::OutputSettings read_output(std::optional<TableReader> table) {
  analysis::OutputSettings output;
  if (!table) return output;
  if (const toml::node* floors = table->find("history_floors")) {
    const std::string key = table->key_path("history_floors");
    const toml::array& array = table->array_of(*floors, key);
    for (std::size_t i = 0; i < array.size(); ++i) {
      output.history_floors.push_back(table->integer_of(array[i], fmt::format("{}[{}]", key, i + 1)));
    }
  }
  if (auto floors = table->optional_subtable("floor_history")) output.floor_history = read_floor_history(*floors);
  read_keys(*table, output, analysis::output_specs(), kNoneRequired);
  if (const toml::node* peaks = table->find("peaks")) {
    const std::string key = table->key_path("peaks");
    const toml::array& array = table->array_of(*peaks, key);
    output.peaks.clear();
    for (std::size_t i = 0; i < array.size(); ++i) {
      output.peaks.push_back(table->string_of(array[i], fmt::format("{}[{}]", key, i + 1)));
    }
  }
  table->finish();
  return output;
}

/// The two building names of a pair's key "NAME:NAME"; empty unless both are given.
std::optional<std::array<std::string, 2>> pair_names(std::string_view key) {
  const std::size_t colon = key.find(':');
  if (colon == std::string_view::npos || colon == 0 || colon + 1 == key.size()) return std::nullopt;
  return std::array{std::string(key.substr(0, colon)), std::string(key.substr(colon + 1))};
}

/// [contact.gaps] of a row ("NAME:NAME" = m), and no contact.gap_m there; neither for two buildings.
void read_pair_gaps(TableReader& contact, analysis::Scene& scene) {
  if (scene.is_row()) {
    if (const toml::node* gap = contact.find("gap_m")) {
      throw contact.error(*gap, contact.key_path("gap_m"),
                          fmt::format("is one gap, and the {} buildings of a row stand apart per neighbouring pair: "
                                      "the outlines give each pair's gap; state them in [contact.gaps] "
                                      "(\"{}:{}\" = ...) to have them checked",
                                      scene.buildings.size(), scene.buildings[0].name, scene.buildings[1].name));
    }
  }
  std::optional<TableReader> gaps = contact.optional_subtable("gaps");
  if (!gaps) return;
  if (!scene.is_row()) {
    throw InputError(contact.key_path("gaps"), "",
                     "is for rows of three or more buildings; two buildings take contact.gap_m", contact.file());
  }
  for (const std::string& key : gaps->unasked_keys()) {
    const double gap_m = gaps->number(key);
    const std::optional<std::array<std::string, 2>> names = pair_names(key);
    if (!names) {
      throw InputError(fmt::format("contact.gaps.\"{}\"", key), fmt::format("{}", gap_m),
                       "expected a key \"NAME:NAME\" naming two buildings", contact.file());
    }
    scene.contact.gaps.push_back({(*names)[0], (*names)[1], gap_m});
  }
  gaps->finish();
}

analysis::Scene read_document(const toml::table& document, const std::filesystem::path& path) {
  TableReader root(document, "", path.string());
  analysis::Scene scene;
  scene.file = path;
  scene.name = root.optional_string("name").value_or(path.stem().string());
  root.optional_string("description");

  const toml::node& buildings_node = root.require("building");
  const toml::array* buildings = buildings_node.as_array();
  if (!buildings || buildings->size() < 2 || !buildings->is_array_of_tables()) {
    throw root.error(buildings_node, "building",
                     "expected two or more [[building]] tables (two: a pair; more: a row, gaps per pair)");
  }
  scene.buildings.clear();
  for (std::size_t i = 0; i < buildings->size(); ++i) {
    scene.buildings.push_back(
        read_building(TableReader(*(*buildings)[i].as_table(), fmt::format("building[{}]", i + 1), path.string())));
  }
  scene.excitation = read_excitation(root.subtable("excitation"), path.parent_path());
  for (model::BuildingDefinition& b : scene.buildings) b.g_mps2 = scene.excitation.g_mps2;  // for P-Δ
  TableReader contact = root.subtable("contact");
  read_keys(contact, scene.contact, analysis::contact_setting_specs(), [&](const analysis::ContactSettingSpec& spec) {
    return spec.required && !(scene.is_row() && spec.key == "gap_m");
  });
  read_pair_gaps(contact, scene);
  contact.finish();
  scene.solver = read_solver(root.optional_subtable("solver"));
  scene.output = read_output(root.optional_subtable("output"));
  root.finish();
  return scene;
}

/// Parses TOML text after checking its encoding and making it ASCII (toml_text.hpp says why).
/// @throws InputError naming file, line, column.
toml::table parse_toml(std::string_view text, const std::string& file) {
  if (const auto bad = detail::find_invalid_utf8(text)) {
    throw InputError("", "", "is not valid UTF-8 text", fmt::format("{}:{}:{}", file, bad->line, bad->column));
  }
  const detail::AsciiToml ascii = detail::ascii_toml(text);
  if (const auto& at = ascii.stray_non_ascii) {
    throw InputError("", "",
                     "a non-ASCII character outside a string or comment (or escaped by a backslash) is not TOML",
                     fmt::format("{}:{}:{}", file, at->line, at->column));
  }
  try {
    return toml::parse(ascii.text, file);
  } catch (const toml::parse_error& error) {
    throw InputError("", "", std::string(error.description()),
                     fmt::format("{}:{}:{}", file, error.source().begin.line, error.source().begin.column));
  } catch (const detail::TomlCheckFailed& error) {
    throw InputError("", "", fmt::format("is not valid TOML (the parser's check '{}' failed)", error.what()), file);
  }
}

/// The options that set excitation keys, by key: only those the user gave.
std::map<std::string, std::string> record_option_names(const excitation::RecordChoice& choice) {
  const std::tuple<const char*, bool, const char*> options[] = {
      {"excitation.file", choice.file.has_value(), "--record"},
      {"excitation.format", choice.format.has_value(), "--record-format"},
      {"excitation.units", choice.units.has_value(), "--units"},
      {"excitation.dt_s", choice.dt_s.has_value(), "--record-dt"},
      {"excitation.accel_column", choice.accel_column.has_value(), "--record-column"},
      {"excitation.scale_factor", choice.scale_factor.has_value(), "--scale"},
      {"excitation.scale_to_pga_g", choice.pga_g.has_value(), "--pga-g"},
      {"excitation.scale_to_sa", choice.sa.has_value(), "--scale-to-sa"},
      {"excitation.direction_deg", choice.direction_deg.has_value(), "--direction-deg"},
      {"excitation.second.file", choice.second_file.has_value(), "--record2"},
      {"excitation.second.accel_column", choice.second_accel_column.has_value(), "--record2-column"}};
  std::map<std::string, std::string> names;
  for (const auto& [key, given, option] : options) {
    if (given) names[key] = option;
  }
  return names;
}

/// Applies the record options and reads the record they make, so that its errors arrive now,
/// naming the option that caused them (the record file's own errors keep its line and field).
void apply_record(analysis::Scene& scene, const excitation::RecordChoice& choice) {
  try {
    scene.excitation = excitation::with_record(scene.excitation, choice);
    excitation::load_ground_motion(analysis::resolved_excitation(scene));
  } catch (const InputError& error) {
    // A record the options chose as format 'single' without its spacing: say which option is
    // missing, in the scene's name (the key excitation.dt_s was never typed).
    if (error.key() == "excitation.dt_s" && error.value() == "missing" && (choice.format || choice.file)) {
      throw InputError("--record-dt", "missing",
                       fmt::format("the record {} is read as format 'single', which needs its sample spacing (s)",
                                   choice.file.value_or(scene.excitation.file).string()),
                       scene.file.string());
    }
    throw error.renamed(record_option_names(choice), scene.file.string());
  }
}

/// One `--gap`: "0.1" (two buildings) or "B1:B2=0.1". Returns the pair's names, in order, or
/// none for a plain gap.
std::optional<std::array<std::string, 2>> apply_gap_text(analysis::Scene& scene, const std::string& text) {
  const std::size_t equals = text.find('=');
  const std::string_view number =
      equals == std::string::npos ? std::string_view(text) : std::string_view(text).substr(equals + 1);
  double gap_m = 0.0;
  const auto [end, error] = std::from_chars(number.data(), number.data() + number.size(), gap_m);
  if (error != std::errc() || end != number.data() + number.size() || number.empty()) {
    throw InputError("--gap", text, "expected a gap in m, or NAME:NAME=m for a pair of a row (e.g. B1:B2=0.1)");
  }
  if (equals == std::string::npos) {
    scene.set_gap(gap_m);
    return std::nullopt;
  }
  std::optional<std::array<std::string, 2>> names = pair_names(std::string_view(text).substr(0, equals));
  if (!names) {
    throw InputError("--gap", text, "expected NAME:NAME=m, two building names and the pair's gap (e.g. B1:B2=0.1)");
  }
  scene.set_pair_gap((*names)[0], (*names)[1], gap_m);
  std::sort(names->begin(), names->end());
  return names;
}

/// Sets the [contact] keys given as options, then validates once: a key's refusal names the
/// option that set it (--restitution 0 with --contact-law jankowski is the restitution's fault,
/// whichever option comes first), a scene key's refusal names the key in the file and the
/// options given.
void apply_contact_options(analysis::Scene& scene,
                           const std::map<std::string, analysis::KeyValue, std::less<>>& options,
                           const std::filesystem::path& file) {
  std::map<std::string, std::string> option_of_key;  // "contact.restitution" -> "--restitution"
  std::set<std::string_view> applied;                // one option may serve two rows (--contact-stiffness)
  for (const analysis::ContactSettingSpec& spec : analysis::contact_setting_specs()) {
    if (spec.key == "gap_m") continue;  // --gap moves building 2 (gap_m and gaps, above), not only the key
    const auto given = options.find(spec.option);
    if (given == options.end()) continue;
    option_of_key["contact." + std::string(spec.key)] = given->first;
    if (!applied.insert(spec.option).second) continue;
    try {
      analysis::set_key(scene.contact, spec, "contact", given->second);
    } catch (const InputError& error) {
      throw InputError(given->first, error.value(), error.reason(), file.string());
    }
  }
  for (const auto& [option, value] : options) {
    if (!applied.contains(option)) throw InputError(option, "", "is not an option of a [contact] key", file.string());
  }
  if (applied.empty()) return;
  try {
    scene.validate();
  } catch (const InputError& error) {
    if (option_of_key.contains(error.key())) throw error.renamed(option_of_key, file.string());
    std::vector<std::string> given;  // a scene key that the options made wrong: both are named
    for (const auto& [option, value] : options) given.push_back(option);
    throw InputError(error.key(), error.value(), fmt::format("{} (with {})", error.reason(), fmt::join(given, ", ")),
                     file.string());
  }
}

}  // namespace

analysis::Scene parse_scene(std::string_view text, const std::filesystem::path& file, const SceneOverrides& overrides) {
  const toml::table document = parse_toml(text, file.string());
  analysis::Scene scene = read_document(document, file);
  // The file's own data is checked first so that an override is never blamed for it, and an
  // override's error names the option rather than the key it replaces.
  scene.validate();
  auto apply_option = [&](const char* option, auto&& apply) {
    try {
      apply();
      scene.validate();
    } catch (const InputError& error) {
      throw InputError(option, error.value(), error.reason(), file.string());
    }
  };
  if (overrides.gap_m) apply_option("--gap", [&] { scene.set_gap(*overrides.gap_m); });
  std::set<std::array<std::string, 2>> pairs_given;  // names sorted (B2:B1 is B1:B2); a plain gap: none
  for (const std::string& text : overrides.gaps) {
    try {
      const std::optional<std::array<std::string, 2>> pair = apply_gap_text(scene, text);
      if (!pairs_given.insert(pair.value_or(std::array<std::string, 2>{})).second) {
        throw InputError("--gap", text, "sets a pair's gap twice");
      }
      scene.validate();
    } catch (const InputError& error) {  // named by the option; a pair's as typed
      throw InputError("--gap", text.find('=') == std::string::npos ? error.value() : text, error.reason(),
                       file.string());
    }
  }
  apply_contact_options(scene, overrides.contact, file);
  if (!overrides.record.empty()) apply_record(scene, overrides.record);
  return scene;
}

analysis::Scene read_scene(const std::filesystem::path& file, const SceneOverrides& overrides) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error)) {
    throw InputError("", "", "no such scene file", file.string());
  }
  const auto size = std::filesystem::file_size(file, error);
  if (error || size > kMaxSceneBytes) {
    throw InputError("", fmt::format("{} bytes", size),
                     fmt::format("a scene file may hold at most {} bytes", kMaxSceneBytes), file.string());
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError("", "", "cannot open the scene file", file.string());
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (const std::size_t nul = text.find('\0'); nul != std::string::npos) {
    const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(nul), '\n');
    throw InputError(fmt::format("line {}", line), "", "holds a NUL byte: not a TOML text file", file.string());
  }
  return parse_scene(text, file, overrides);
}

}  // namespace pounding::io
