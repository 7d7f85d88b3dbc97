#pragma once
// Drift limit states: a building's largest peak storey drift ratio over a run against the drifts
// that mark its structural performance levels (immediate occupancy, life safety, collapse
// prevention), set per building in [building.limit_states] with defaults by structural type
// (FEMA 356 Table C1-3). docs/model.md §2b says what is measured and why.

#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pounding/key_spec.hpp"
#include "pounding/model/building.hpp"
#include "pounding/solvers/run_result.hpp"

namespace pounding::analysis {

/// One key of [building.limit_states], declared once (key_spec.hpp): the scene reader, the range
/// and choice checks, `pounding settings` and the docs' table come from its row.
using DriftLimitSpec = KeySpec<model::DriftLimits>;

/// Every [building.limit_states] key, in the order the docs list them.
std::span<const DriftLimitSpec> drift_limit_specs();

/// A structural type's indicative peak transient drift ratios at the three performance levels,
/// as FEMA 356 (2000) Table C1-3 lists them for the vertical elements.
struct StructuralType {
  std::string_view name;               // the scene's structural_type
  std::string_view description;        // as the table names it
  std::array<double, 3> drift_ratios;  // immediate occupancy, life safety, collapse prevention
};

/// Every structural type, in the order the docs list them; the first is the default.
std::span<const StructuralType> structural_types();

/// One key of [building.shear_capacity] (model::ShearCapacityFormula, ASCE 41-17
/// Eq. 10-3), declared once as DriftLimitSpec is.
using ShearCapacitySpec = KeySpec<model::ShearCapacityFormula>;

/// Every [building.shear_capacity] key, in the order the docs list them.
std::span<const ShearCapacitySpec> shear_capacity_specs();

/// @throws InputError(`shear_capacity.<key>`, value, reason) for a value out of range.
void validate_shear_capacity(const model::ShearCapacityFormula& formula);

/// One key of [building.flexural_strength] (model::FlexuralStrengthFormula), declared once as
/// DriftLimitSpec is.
using FlexuralStrengthSpec = KeySpec<model::FlexuralStrengthFormula>;

/// Every [building.flexural_strength] key, in the order the docs list them.
std::span<const FlexuralStrengthSpec> flexural_strength_specs();

/// Checks the keys' ranges, one ρ_l a storey, and every column's axial load against its balanced
/// load along x and y, where the formula stops holding (model::column_section_strength()).
/// @pre building.flexural_strength. @throws InputError(`flexural_strength.<key>`, value, reason).
void validate_flexural_strength(const model::BuildingDefinition& building);

/// The performance levels' short names, in order: "IO", "LS", "CP".
inline constexpr std::array<std::string_view, 3> kPerformanceLevels{"IO", "LS", "CP"};

/// The three limits of `limits`: each given one, else its structural type's.
/// @pre limits.structural_type is one of structural_types().
std::array<double, 3> resolved_drift_limits(const model::DriftLimits& limits);

/// Checks the keys' ranges and choices (drift_limit_specs()) and that the resolved limits rise
/// from IO to CP. @throws InputError(`limit_states.<key>`, value, reason).
void validate_drift_limits(const model::DriftLimits& limits);

/// The largest |peak drift ratio| of a building over its storeys, at the CM and the slab corners,
/// along x and y (FloorPeaks::drift_x ... corner_drift_y, whose maxima the run locates).
struct PeakStoreyDrift {
  double ratio = 0.0;  // |Δ|/H, ≥ 0
  double t_s = 0.0;
  int storey = 0;     // 1-based; 0: no drift peaks
  std::string where;  // "CM" or "corner 3"
  char axis = 'x';
};

/// @pre floors hold the drift peaks (OutputSelection::drift_peaks).
PeakStoreyDrift peak_storey_drift(const solvers::BuildingPeaks& peaks);

/// One performance level's verdict: the limit, whether the peak drift ratio passed it, and the
/// margin limit − peak (negative when exceeded).
struct LevelVerdict {
  std::string_view level;  // kPerformanceLevels
  double drift_ratio = 0.0;
  bool given = false;  // in the scene, not the structural type's
  bool exceeded = false;
  double margin = 0.0;
};

/// A building's drift limit states over a run, and (with output.contact_free_reference) over the
/// same run without contact.
struct DriftLimitState {
  int building = 0;  // 0-based in the scene
  std::string name;
  std::string structural_type;
  PeakStoreyDrift peak;
  std::array<LevelVerdict, 3> levels;
  std::optional<PeakStoreyDrift> peak_without_contact;
  std::optional<std::array<LevelVerdict, 3>> levels_without_contact;
};

/// A storey's residual drift: its drift ratio at the end of the run, which is the drift it keeps
/// (FEMA P-58's residual drift) once the building has come to rest there ([excitation]
/// free_vibration_s lets it).
struct StoreyResidualDrift {
  int storey = 0;           // 1-based
  double x = 0.0, y = 0.0;  // at the CM, signed
  double largest = 0.0;     // the largest |drift ratio| over the CM and the slab corners, x and y
  std::string where;        // where that is: "CM" or "corner 3"
  char axis = 'x';
  /// The largest |drift ratio rate| / ω₁ over the same points (ω₁ = 2π/T₁): the amplitude of a
  /// first-mode vibration still going on at the end. Far below `largest` once at rest.
  double oscillation = 0.0;
};

/// A damage state of residual drift, as FEMA P-58 (2012) defines the four: the residual storey
/// drift ratio that marks it and what it means for the building.
struct ResidualDamageState {
  std::string_view name;  // "DS1" ... "DS4"
  double drift_ratio;
  std::string_view meaning;
};

/// The four, in rising order.
std::span<const ResidualDamageState> residual_damage_states();

/// A building's residual drifts and whether it had come to rest.
struct BuildingResidualDrift {
  std::string name;
  double first_period_s = 0.0;
  std::vector<StoreyResidualDrift> storeys;  // every storey, bottom up
  StoreyResidualDrift largest;               // the storey with the largest `largest`
  double oscillation = 0.0;                  // the largest over storeys
  /// At rest: the oscillation at most a tenth of the largest residual drift ratio, or below
  /// kSettledOscillation (a drift ratio no damage state notices).
  bool settled = false;
  /// The highest residual_damage_states() entry its largest residual drift ratio reaches (0-based);
  /// empty below DS1.
  std::optional<std::size_t> damage_state;
};
inline constexpr double kSettledOscillation = 1e-4;

/// @pre peaks' floors hold the drifts at the end (FloorPeaks::end_drift); first_period_s > 0.
BuildingResidualDrift residual_drift(const solvers::BuildingPeaks& peaks, double first_period_s);

/// The limit states of every building whose definition has drift_limits, from `result` and the
/// optional contact-free run. @pre both hold drift peaks for every building.
std::vector<DriftLimitState> drift_limit_states(const std::vector<model::BuildingDefinition>& buildings,
                                                const solvers::RunResult& result,
                                                const std::optional<solvers::RunResult>& contact_free);

}  // namespace pounding::analysis
