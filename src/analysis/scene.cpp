#include "pounding/analysis/scene.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "pounding/analysis/contact_laws.hpp"
#include "pounding/input_error.hpp"

namespace pounding::analysis {
namespace {

constexpr double kGapTolerance_m = 1e-6;

// Physical ranges (docs/scene-format.md lists each next to its key).
constexpr Range kGap{0.0, 10.0, "m"};                      // seismic joints are centimetres to a metre
constexpr Range kCandidateMargin{0.0, 10.0, "m", true};
constexpr Range kHoldVelocity{0.0, 0.1, "m/s", true};      // pounding approaches at 0.1 to 1 m/s
// Floors this far apart still meet face on: up to a slab's thickness. validate_levels() also
// keeps it below half of every storey, so a floor meets at most one floor of the other building.
constexpr Range kLevelTolerance{0.0, 0.5, "m", true};
constexpr Range kHistoryInterval{1e-4, 10.0, "s"};
// From a soft pad (1 kN/m) to far stiffer than concrete (1e12 kN/m: contact periods of
// microseconds for floor masses of tonnes, below which no integrator resolves the contact).
constexpr Range kContactStiffness{1.0, 1e12, "kN/m"};
// The Hertz laws' k δ^(1/2) at 1 mm of overlap spans the same 1 to 1e12 kN/m within a factor 30.
constexpr Range kHertzStiffness{1.0, 1e13, "kN/m^1.5"};

void validate_gap(const std::string& key, double gap_m) { require_range(key, gap_m, kGap); }

std::string building_key(std::size_t index) { return fmt::format("building[{}]", index + 1); }

void validate_contact(const ContactSettings& contact) {
  validate_gap("contact.gap_m", contact.gap_m);
  if (!(contact.restitution >= 0.0 && contact.restitution <= 1.0)) {
    throw InputError("contact.restitution", format_value(contact.restitution), "must lie in [0, 1]");
  }
  require_range("contact.candidate_margin_m", contact.candidate_margin_m, kCandidateMargin);
  require_range("contact.hold_velocity_mps", contact.hold_velocity_mps, kHoldVelocity);
  require_range("contact.level_tolerance_m", contact.level_tolerance_m, kLevelTolerance);
  const ContactLawInfo& law = contact_law_info(contact.law);
  auto check_stiffness = [&](std::string_view key, const std::optional<double>& value, const Range& range) {
    if (!value) return;
    const std::string name = "contact." + std::string(key);
    if (law.stiffness_key != key) {
      throw InputError(name, format_value(*value),
                       law.stiffness_key.empty()
                           ? fmt::format("does not apply to law {} (it uses no stiffness)", law.name)
                           : fmt::format("does not apply to law {}: its stiffness is {} ({})", law.name,
                                         law.stiffness_key, law.stiffness_unit));
    }
    require_range(name, *value, range);
  };
  check_stiffness("stiffness_kN_per_m", contact.stiffness_kN_per_m, kContactStiffness);
  check_stiffness("stiffness_kN_per_m1_5", contact.stiffness_kN_per_m1_5, kHertzStiffness);
  if (law.law == contact::ContactLaw::jankowski && contact.restitution == 0.0) {
    throw InputError("contact.restitution", "0",
                     "must be positive for law jankowski: its damping ratio 9 sqrt(5) (1 - e^2) / (2e (e (9 pi - 16) "
                     "+ 16)) is infinite at e = 0 (use kelvin or hertzdamp for a plastic contact)");
  }
}

void validate_levels(const Scene& scene) {
  // Below half a storey height a floor can meet at most one floor of the other building.
  const double tolerance = scene.contact.level_tolerance_m;
  for (std::size_t b = 0; b < 2; ++b) {
    const std::vector<double>& heights = scene.buildings[b].storey_height_m;
    for (std::size_t s = 0; s < heights.size(); ++s) {
      if (!(tolerance < heights[s] / 2.0)) {
        throw InputError("contact.level_tolerance_m", format_value(tolerance),
                         fmt::format("must be below half of every storey height ({}.storey_height_m[{}] is {} m)",
                                     building_key(b), s + 1, heights[s]));
      }
    }
  }
  if (!scene.levels().empty()) return;
  const auto elevations = [&](std::size_t b) { return model::floor_elevations(scene.buildings[b]); };
  throw InputError(building_key(1) + ".storey_height_m", fmt::format("[{}]", fmt::join(scene.buildings[1].storey_height_m, ", ")),
                   fmt::format("no floor of building 2 stands at the elevation of a floor of building 1 "
                               "(building 1's floors at {} m, building 2's at {} m, matched within "
                               "contact.level_tolerance_m = {} m): their slabs could only strike columns, and "
                               "slab-to-column impacts are outside this model",
                               fmt::join(elevations(0), ", "), fmt::join(elevations(1), ", "), tolerance));
}

void validate_output(const OutputSettings& output, std::size_t levels) {
  std::set<int> seen;
  for (std::size_t i = 0; i < output.history_floors.size(); ++i) {
    const int level = output.history_floors[i];
    const std::string key = fmt::format("output.history_floors[{}]", i + 1);
    if (level < 1 || static_cast<std::size_t>(level) > levels) {
      throw InputError(key, std::to_string(level),
                       fmt::format("lists levels (floor pairs at a common elevation, as `pounding check` "
                                   "prints them), numbered 1..{}", levels));
    }
    if (!seen.insert(level).second) throw InputError(key, std::to_string(level), "is listed twice");
  }
  require_range("output.history_interval_s", output.history_interval_s, kHistoryInterval);
  for (std::size_t i = 0; i < output.peaks.size(); ++i) {
    const std::string key = fmt::format("output.peaks[{}]", i + 1), value = fmt::format("\"{}\"", output.peaks[i]);
    if (std::find(kPeakGroups.begin(), kPeakGroups.end(), output.peaks[i]) == kPeakGroups.end()) {
      throw InputError(key, value, fmt::format("expected one of {} (or an empty list for no peaks)", fmt::join(kPeakGroups, ", ")));
    }
    if (std::find(output.peaks.begin(), output.peaks.begin() + static_cast<std::ptrdiff_t>(i), output.peaks[i]) !=
        output.peaks.begin() + static_cast<std::ptrdiff_t>(i)) {
      throw InputError(key, value, "is listed twice");
    }
  }
}

void validate_pair(const Scene& scene) {
  const model::Polygon& left = scene.buildings[0].slab;
  const model::Polygon& right = scene.buildings[1].slab;
  if (model::interiors_overlap(left, right)) {
    throw InputError(building_key(1) + ".slab", "", "overlaps the slab of building 1 at rest");
  }
  const std::optional<double> clearance = model::horizontal_clearance(left, right);
  if (!clearance || *clearance < 0.0) {
    throw InputError(building_key(1) + ".slab", "",
                     "building 2 must stand on the +x side of building 1, facing it over a "
                     "common range of y");
  }
  if (std::abs(*clearance - scene.contact.gap_m) > kGapTolerance_m) {
    throw InputError("contact.gap_m", format_value(scene.contact.gap_m),
                     fmt::format("disagrees with the slab outlines, whose clear distance along x "
                                 "is {} m", *clearance));
  }
}

}  // namespace

solvers::OutputSelection OutputSettings::selection() const {
  auto asked = [&](std::string_view group) { return std::find(peaks.begin(), peaks.end(), group) != peaks.end(); };
  return {.history = history,
          .displacement_peaks = asked(kPeakGroups[0]),
          .acceleration_peaks = asked(kPeakGroups[1]),
          .drift_peaks = asked(kPeakGroups[2])};
}

double ContactSettings::used_stiffness() const {
  const ContactLawInfo& info = contact_law_info(law);
  const std::optional<double>& given = info.stiffness_key == "stiffness_kN_per_m1_5" ? stiffness_kN_per_m1_5 : stiffness_kN_per_m;
  return given.value_or(info.default_stiffness);
}

void ContactSettings::set_stiffness(double value) {
  (contact_law_info(law).stiffness_key == "stiffness_kN_per_m1_5" ? stiffness_kN_per_m1_5 : stiffness_kN_per_m) = value;
}

void Scene::set_gap(double gap_m) {
  validate_gap("contact.gap_m", gap_m);
  const model::Point2 shift(gap_m - contact.gap_m, 0.0);
  model::BuildingDefinition& right = buildings[1];
  right.slab = right.slab.translated(shift);
  right.centre_of_mass += shift;
  for (model::Column& column : right.columns) column.position_m += shift;
  contact.gap_m = gap_m;
}

std::vector<contact::Level> Scene::levels() const {
  return contact::common_levels({model::floor_elevations(buildings[0]), model::floor_elevations(buildings[1])},
                                contact.level_tolerance_m);
}

void Scene::validate() const {
  if (name.empty()) throw InputError("name", "\"\"", "must not be empty", file.string());
  for (std::size_t i = 0; i < buildings.size(); ++i) {
    try {
      buildings[i].validate();
    } catch (const InputError& error) {
      throw error.in_context(file.string(), building_key(i));
    }
  }
  try {
    excitation.validate();
    validate_contact(contact);
    validate_levels(*this);
    solver.validate();
    validate_output(output, levels().size());
    validate_pair(*this);
  } catch (const InputError& error) {
    throw error.in_context(file.string());
  }
}

}  // namespace pounding::analysis
