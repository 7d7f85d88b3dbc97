#include "pounding/analysis/limit_states.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "pounding/input_error.hpp"

namespace pounding::analysis {

namespace {

/// A drift ratio limit: above 0 (a limit of 0 is exceeded by any motion), at most 20 % (beyond
/// 10 % the run ends as a collapse; a higher limit would never be reached).
constexpr Range kDriftLimitRange{0.0, 0.2, "", true};

constexpr std::array<StructuralType, 8> kStructuralTypes{{
    {"concrete-frame", "concrete frames", {0.01, 0.02, 0.04}},
    {"concrete-wall", "concrete walls", {0.005, 0.01, 0.02}},
    {"steel-moment-frame", "steel moment frames", {0.007, 0.025, 0.05}},
    {"steel-braced-frame", "braced steel frames", {0.005, 0.015, 0.02}},
    {"masonry-infill", "unreinforced masonry infill walls", {0.001, 0.005, 0.006}},
    {"unreinforced-masonry", "unreinforced masonry (noninfill) walls", {0.003, 0.006, 0.01}},
    {"reinforced-masonry", "reinforced masonry walls", {0.002, 0.006, 0.015}},
    {"wood-stud", "wood stud walls", {0.01, 0.02, 0.03}},
}};

std::vector<std::string_view> type_names() {
  std::vector<std::string_view> names;
  for (const StructuralType& type : kStructuralTypes) names.push_back(type.name);
  return names;
}

const std::vector<DriftLimitSpec> kSpecs = {
    {.key = "structural_type",
     .member = &model::DriftLimits::structural_type,
     .choices = type_names(),
     .description = "the structural system, whose drift limits are the defaults",
     .details = "FEMA 356 Table C1-3's indicative peak transient drifts (`pounding settings` lists them)"},
    {.key = "immediate_occupancy",
     .member = &model::DriftLimits::immediate_occupancy,
     .range = kDriftLimitRange,
     .description = "peak storey drift ratio at the immediate occupancy level (IO)",
     .details = "unset: the structural type's"},
    {.key = "life_safety",
     .member = &model::DriftLimits::life_safety,
     .range = kDriftLimitRange,
     .description = "peak storey drift ratio at the life safety level (LS)",
     .details = "unset: the structural type's"},
    {.key = "collapse_prevention",
     .member = &model::DriftLimits::collapse_prevention,
     .range = kDriftLimitRange,
     .description = "peak storey drift ratio at the collapse prevention level (CP)",
     .details = "unset: the structural type's"},
};

const std::vector<ShearCapacitySpec> kShearCapacitySpecs = {
    {.key = "concrete_strength_MPa",
     .member = &model::ShearCapacityFormula::concrete_strength_MPa,
     .required = true,
     .range = Range{10.0, 120.0, "MPa"},
     .description = "f'c: the concrete's compressive strength (MPa)"},
    {.key = "transverse_yield_strength_MPa",
     .member = &model::ShearCapacityFormula::transverse_yield_strength_MPa,
     .required = true,
     .range = Range{200.0, 1000.0, "MPa"},
     .description = "f_yt: the ties' yield strength (MPa)"},
    {.key = "transverse_area_mm2",
     .member = &model::ShearCapacityFormula::transverse_area_mm2,
     .required = true,
     .range = Range{0.0, 1e4, "mm2"},
     .description = "A_v: the area of one set of ties' legs across the shear plane (mm²), along x and along y alike",
     .details = "0: no ties (the concrete alone)"},
    {.key = "transverse_spacing_mm",
     .member = &model::ShearCapacityFormula::transverse_spacing_mm,
     .required = true,
     .range = Range{0.0, 1000.0, "mm", true},
     .description = "s: the ties' spacing along the column (mm)",
     .details = "ties at s ≥ d do not count (α = 0), at s ≤ 0.75 d fully"},
    {.key = "axial_load_kN",
     .member = &model::ShearCapacityFormula::axial_load_kN,
     .range = Range{0.0, 1e6, "kN"},
     .description = "N: each column's axial compression (kN)",
     .details = "unset: the storey's gravity share, g times the floor masses it carries over its number of columns"},
    {.key = "effective_depth_ratio",
     .member = &model::ShearCapacityFormula::effective_depth_ratio,
     .range = Range{0.5, 1.0, ""},
     .description = "d over the section's depth along the sway",
     .details = "ASCE 41-17 allows 0.8"},
    {.key = "ductility_factor",
     .member = &model::ShearCapacityFormula::ductility_factor,
     .range = Range{0.7, 1.0, ""},
     .description = "k_nl: 1 for a displacement ductility demand up to 2, 0.7 from 6 on (linear between)",
     .details = "fixed for the run, not updated with the demand"},
};

const std::vector<FlexuralStrengthSpec> kFlexuralStrengthSpecs = {
    {.key = "longitudinal_ratio",
     .member = &model::FlexuralStrengthFormula::longitudinal_ratio,
     .required = true,
     .range = Range{0.001, 0.08, ""},
     .description = "rho_l: the area of all longitudinal bars over b h",
     .details = "a list gives each storey its own, storey 1 first; half of the bars in each face across the sway"},
    {.key = "steel_yield_strength_MPa",
     .member = &model::FlexuralStrengthFormula::steel_yield_strength_MPa,
     .required = true,
     .range = Range{200.0, 1000.0, "MPa"},
     .description = "f_y: the longitudinal bars' yield strength (MPa)"},
    {.key = "concrete_strength_MPa",
     .member = &model::FlexuralStrengthFormula::concrete_strength_MPa,
     .required = true,
     .range = Range{10.0, 120.0, "MPa"},
     .description = "f'c: the concrete's compressive strength (MPa)"},
    {.key = "axial_load_kN",
     .member = &model::FlexuralStrengthFormula::axial_load_kN,
     .range = Range{0.0, 1e6, "kN"},
     .description = "N: each column's axial compression (kN)",
     .details = "unset: the storey's gravity share, g times the floor masses it carries over its number of columns; "
                "at most the balanced load N_b"},
    {.key = "cover_ratio",
     .member = &model::FlexuralStrengthFormula::cover_ratio,
     .range = Range{0.02, 0.3, ""},
     .description = "d'/D: the bars' centroid from the face over the section's depth along the sway"},
};

const StructuralType& structural_type(std::string_view name) {
  const auto* type = std::find_if(kStructuralTypes.begin(), kStructuralTypes.end(),
                                  [&](const StructuralType& t) { return t.name == name; });
  return type == kStructuralTypes.end() ? kStructuralTypes.front() : *type;
}

std::array<const std::optional<double>*, 3> given_limits(const model::DriftLimits& limits) {
  return {&limits.immediate_occupancy, &limits.life_safety, &limits.collapse_prevention};
}

std::array<LevelVerdict, 3> verdicts(const model::DriftLimits& limits, double peak_ratio) {
  const std::array<double, 3> resolved = resolved_drift_limits(limits);
  const auto given = given_limits(limits);
  std::array<LevelVerdict, 3> levels;
  for (std::size_t i = 0; i < levels.size(); ++i) {
    levels[i] = {.level = kPerformanceLevels[i],
                 .drift_ratio = resolved[i],
                 .given = given[i]->has_value(),
                 .exceeded = peak_ratio > resolved[i],
                 .margin = resolved[i] - peak_ratio};
  }
  return levels;
}

void consider(PeakStoreyDrift& worst, const solvers::Peak& peak, int storey, std::string where, char axis) {
  if (worst.storey != 0 && !(std::abs(peak.value) > worst.ratio)) return;
  worst = {.ratio = std::abs(peak.value), .t_s = peak.t_s, .storey = storey, .where = std::move(where), .axis = axis};
}

}  // namespace

std::span<const DriftLimitSpec> drift_limit_specs() { return kSpecs; }

std::span<const StructuralType> structural_types() { return kStructuralTypes; }

std::span<const ShearCapacitySpec> shear_capacity_specs() { return kShearCapacitySpecs; }

std::span<const ResidualDamageState> residual_damage_states() {
  static constexpr std::array<ResidualDamageState, 4> kStates{{
      {"DS1", 0.002, "no structural realignment needed for stability; nonstructural and mechanical repairs"},
      {"DS2", 0.005, "realignment of the structural frame and related structural repairs needed"},
      {"DS3", 0.01,
       "major structural realignment needed to restore the margin against lateral instability; "
       "may not be economically or practically feasible"},
      {"DS4", 0.02, "in danger of collapse from aftershocks"},
  }};
  return kStates;
}

void validate_shear_capacity(const model::ShearCapacityFormula& formula) {
  validate_keys<model::ShearCapacityFormula>(formula, kShearCapacitySpecs, "shear_capacity");
}

std::span<const FlexuralStrengthSpec> flexural_strength_specs() { return kFlexuralStrengthSpecs; }

void validate_flexural_strength(const model::BuildingDefinition& building) {
  const model::FlexuralStrengthFormula& formula = building.flexural_strength.value();
  validate_keys<model::FlexuralStrengthFormula>(formula, kFlexuralStrengthSpecs, "flexural_strength");
  if (formula.longitudinal_ratio.size() != static_cast<std::size_t>(building.storeys)) {
    throw InputError("flexural_strength.longitudinal_ratio",
                     fmt::format("{} values", formula.longitudinal_ratio.size()),
                     fmt::format("needs one value per storey ({})", building.storeys));
  }
  for (int storey = 1; storey <= building.storeys; ++storey) {
    for (std::size_t c = 0; c < building.columns.size(); ++c) {
      if (!building.columns[c].yield_force_kN.empty()) continue;  // its own strength, not its section's
      for (int direction = 0; direction < 2; ++direction) {
        const model::SectionStrength strength = model::column_section_strength(building, storey, c, direction);
        if (strength.axial_load_kN <= strength.balanced_axial_load_kN) continue;
        throw InputError(
            "flexural_strength.axial_load_kN", fmt::format("{:.5g} kN", strength.axial_load_kN),
            fmt::format("is above the balanced load N_b = {:.5g} kN of {} in storey {} along {} ({}): the "
                        "section's formula assumes the tension bars yield, which they do not beyond N_b; give the "
                        "column's yield_force_kN instead",
                        strength.balanced_axial_load_kN, model::column_key(building, c), storey,
                        direction == 0 ? "x" : "y",
                        formula.axial_load_kN ? "N given" : "N the storey's gravity share"));
      }
    }
  }
}

std::array<double, 3> resolved_drift_limits(const model::DriftLimits& limits) {
  std::array<double, 3> resolved = structural_type(limits.structural_type).drift_ratios;
  const auto given = given_limits(limits);
  for (std::size_t i = 0; i < resolved.size(); ++i) resolved[i] = given[i]->value_or(resolved[i]);
  return resolved;
}

void validate_drift_limits(const model::DriftLimits& limits) {
  validate_keys<model::DriftLimits>(limits, kSpecs, "limit_states");
  const std::array<double, 3> resolved = resolved_drift_limits(limits);
  for (std::size_t i = 1; i < resolved.size(); ++i) {
    if (resolved[i] > resolved[i - 1]) continue;
    const std::string_view key = kSpecs[i + 1].key;
    throw InputError(
        fmt::format("limit_states.{}", key), fmt::format("{:g}", resolved[i]),
        fmt::format(
            "must exceed the {} limit ({:g}{}): the levels rise from immediate occupancy to "
            "collapse prevention",
            kPerformanceLevels[i - 1], resolved[i - 1],
            given_limits(limits)[i - 1]->has_value() ? "" : fmt::format(", the {} default", limits.structural_type)));
  }
}

PeakStoreyDrift peak_storey_drift(const solvers::BuildingPeaks& peaks) {
  PeakStoreyDrift worst;
  for (const solvers::FloorPeaks& floor : peaks.floors) {
    consider(worst, floor.drift_x, floor.floor, "CM", 'x');
    consider(worst, floor.drift_y, floor.floor, "CM", 'y');
    for (std::size_t k = 0; k < floor.corner_drift_x.size(); ++k) {
      consider(worst, floor.corner_drift_x[k], floor.floor, fmt::format("corner {}", k + 1), 'x');
      consider(worst, floor.corner_drift_y[k], floor.floor, fmt::format("corner {}", k + 1), 'y');
    }
  }
  return worst;
}

BuildingResidualDrift residual_drift(const solvers::BuildingPeaks& peaks, double first_period_s) {
  const double omega_radps = 2.0 * std::numbers::pi / first_period_s;
  BuildingResidualDrift building{.name = peaks.name, .first_period_s = first_period_s};
  for (const solvers::FloorPeaks& floor : peaks.floors) {
    StoreyResidualDrift storey{.storey = floor.floor, .x = floor.end_drift.at(0), .y = floor.end_drift.at(1)};
    for (std::size_t slot = 0; slot < floor.end_drift.size(); ++slot) {
      const double ratio = std::abs(floor.end_drift[slot]);
      storey.oscillation = std::max(storey.oscillation, std::abs(floor.end_drift_rate_per_s[slot]) / omega_radps);
      if (!storey.where.empty() && !(ratio > storey.largest)) continue;
      storey.largest = ratio;
      storey.where = slot < 2 ? "CM" : fmt::format("corner {}", slot / 2);
      storey.axis = slot % 2 == 0 ? 'x' : 'y';
    }
    if (building.storeys.empty() || storey.largest > building.largest.largest) building.largest = storey;
    building.oscillation = std::max(building.oscillation, storey.oscillation);
    building.storeys.push_back(std::move(storey));
  }
  building.settled = building.oscillation <= std::max(0.1 * building.largest.largest, kSettledOscillation);
  for (std::size_t k = 0; k < residual_damage_states().size(); ++k) {
    if (building.largest.largest >= residual_damage_states()[k].drift_ratio) building.damage_state = k;
  }
  return building;
}

std::vector<DriftLimitState> drift_limit_states(const std::vector<model::BuildingDefinition>& buildings,
                                                const solvers::RunResult& result,
                                                const std::optional<solvers::RunResult>& contact_free) {
  std::vector<DriftLimitState> states;
  for (std::size_t b = 0; b < buildings.size(); ++b) {
    if (!buildings[b].drift_limits) continue;
    const model::DriftLimits& limits = *buildings[b].drift_limits;
    DriftLimitState state{.building = static_cast<int>(b),
                          .name = buildings[b].name,
                          .structural_type = limits.structural_type,
                          .peak = peak_storey_drift(result.peaks.at(b))};
    state.levels = verdicts(limits, state.peak.ratio);
    if (contact_free) {
      state.peak_without_contact = peak_storey_drift(contact_free->peaks.at(b));
      state.levels_without_contact = verdicts(limits, state.peak_without_contact->ratio);
    }
    states.push_back(std::move(state));
  }
  return states;
}

}  // namespace pounding::analysis
