#pragma once
// Runs a scene: assembles the model, finds the contact candidates, builds the coupled system and
// integrates it with the scene's solver settings.

#include <optional>
#include <span>
#include <vector>

#include "pounding/key_spec.hpp"
#include "pounding/analysis/limit_states.hpp"
#include "pounding/analysis/scene.hpp"
#include "pounding/contact/candidates.hpp"
#include "pounding/dynamics/coupled_system.hpp"
#include "pounding/solvers/run_sink.hpp"
#include "pounding/solvers/hht.hpp"
#include "pounding/solvers/run_result.hpp"

namespace pounding::analysis {

/// The candidates the scene's geometry allows (docs/model.md §4), on every level (Scene::levels()):
/// the facing ones (slab to slab, then slab to column, pair by pair), then the corner ones.
std::vector<contact::Candidate> scene_candidates(const Scene& scene);

/// scene.excitation with a spectral scaling at a building's first period (excitation.scale_to_sa
/// "…@B1", "…@B2", "…@T1": the longer of the two) given that period from the scene's buildings.
/// @throws InputError for a building that cannot be assembled.
excitation::ExcitationSpec resolved_excitation(const Scene& scene);

/// The scene's ground motion: its record (or pair) read and processed (resolved_excitation()).
/// @throws InputError naming the record's file and line and the scene's file and keys.
excitation::GroundMotion scene_ground_motion(const Scene& scene);

/// The coupled system of a scene (assembles both buildings, loads the record); without contact
/// candidates if `contact` is false (the buildings then move as if they never met).
/// @throws InputError for bad buildings or a bad record.
dynamics::CoupledSystem build_system(const Scene& scene, bool contact = true);

/// The HHT-α options that `used` (method hht), scene.contact and scene.output describe.
solvers::HhtOptions hht_options(const Scene& scene, const UsedSettings& used);

/// What one run may cost (docs/guide/limits.md): checked against an estimate before the run
/// starts, and enforced while it runs (the run then ends with status step_limit or time_limit).
/// Each limit is a row of limit_specs(); the defaults are these initialisers.
struct RunLimits {
  long max_steps = 10'000'000;      // integrator steps (hht: trial steps, halvings included)
  double max_wall_time_s = 3600.0;  // wall-clock time of the run (s)
  double max_history_values = 2e7;  // history.csv values (rows × columns): 2e7 ≈ 450 MB on disk (≈ 23 B a
                                    // value), 160 MB in memory when the caller keeps the history (no sink)
  /// @throws InputError naming the limit (limits.max_steps, ...) and its range (limit_specs()).
  void validate() const;
};

/// One run limit, declared once (key_spec.hpp): `run`'s options, Python run()'s keywords,
/// validate(), `pounding settings` and docs/guide/limits.md's table come from its row.
using LimitSpec = KeySpec<RunLimits>;

/// Every run limit, in the order the docs list them.
std::span<const LimitSpec> limit_specs();

/// What a run of the scene needs at least, from the scene alone (no integration).
struct WorkEstimate {
  int dof = 0;                // both buildings
  double duration_s = 0.0;    // simulated time
  double history_rows = 0.0;  // regular samples (event rows come on top); 0 without history
  double history_columns = 0.0;
  double min_steps = 0.0;  // hht: duration/Δt; event-driven: duration over the largest step allowed
  double history_values() const { return history_rows * history_columns; }
};

WorkEstimate estimate_work(const Scene& scene, const dynamics::CoupledSystem& system);

/// @throws InputError naming the limit (limits.max_steps, limits.max_history_values), the
///   estimate and the limit, when the estimate exceeds it.
void check_work(const WorkEstimate& estimate, const RunLimits& limits);

/// A run together with what it was run on, for writers and printers.
/// Something about a completed run that its numbers alone do not say. `code` is stable (for
/// scripts); `message` says what and what to do.
struct RunWarning {
  std::string code;  // record_undersampled, implausible_floor_mass, slab_misses_columns, building_alone
  std::string message;
};

/// What excitation.scale_to_sa asked and what it did.
struct SpectralScaling {
  std::string asked;      // as written ("0.5g@T1", "asce7(SDS=1,SD1=0.6)@0.2-2T1")
  double target_g = 0.0;  // at a period; 0 for a range
  double period_s = 0.0;  // at a period: where (a building's T1 resolved); for a range: its reference
  std::optional<excitation::DesignSpectrum> design = std::nullopt;  // over a range: the target
  double from_s = 0.0, to_s = 0.0;                                  // over a range: its periods (s)
  double damping_ratio = 0.05;
  bool rotd100 = false;        // a pair: its RotD100; else the one component's PSA
  double record_factor = 0.0;  // what the record's values were multiplied by (its own units)
};

struct RunReport {
  std::string scene;
  double gap_m = 0.0;
  double restitution = 0.0;
  SolverSettings solver;  // as given
  UsedSettings used;      // as run (real order, Newton solver, tolerances per component)
  double hold_velocity_mps = 0.0;
  std::vector<contact::Level> levels;
  std::vector<contact::Candidate> candidates;
  solvers::RunResult result;
  std::string contact_law = "impulse";  // contact_laws.hpp
  double contact_stiffness = 0.0;       // used by compliant laws, in the law's unit; 0 for impulse
  /// The law's damping from the restitution (contact_damping() in contact_laws.hpp); 0 for impulse.
  double contact_damping = 0.0;
  double g_mps2 = 9.81;  // the scene's gravity: accelerations are also reported in g
  std::vector<RunWarning> warnings = {};
  /// With output.contact_free_reference: the same run with no contact candidates (its peaks and
  /// springs; no history).
  std::optional<solvers::RunResult> contact_free = std::nullopt;
  /// The yielding column springs (result.springs in the same order); empty if all stay elastic.
  std::vector<dynamics::YieldingSpring> springs = {};
  /// The drift limit states of the buildings with [building.limit_states] (limit_states.hpp).
  std::vector<DriftLimitState> limit_states = {};
  /// Every building's residual drift (limit_states.hpp), when the run completed, the drift peaks
  /// are kept and the scene has yielding columns, limit states or a quiet tail (an elastic
  /// building keeps none: without them its drift at the end is vibration); else empty.
  std::vector<BuildingResidualDrift> residual_drifts = {};
  double free_vibration_s = 0.0;  // the quiet tail after the record (excitation.free_vibration_s)
  std::optional<SpectralScaling> spectral_scaling = std::nullopt;  // with excitation.scale_to_sa
  /// A row: its neighbouring pairs (Scene::pairs) and building names; empty for two buildings,
  /// whose outputs name no pair.
  std::vector<BuildingPair> pairs = {};
  std::vector<std::string> building_names = {};
};

/// One storey of a building whose columns yield, over a run: its springs' largest ductility in x
/// and y (peak |drift| / yield drift), the first yield (NaN: none), how many springs yielded and
/// the energy they dissipated.
struct StoreyYielding {
  int building = 0;  // 0 or 1
  int storey = 1;
  std::array<double, 2> peak_ductility{0.0, 0.0};
  double first_yield_t_s = 0.0;
  int springs_yielded = 0;
  int springs = 0;
  double hysteretic_kJ = 0.0;
  /// The largest peak |force| of its columns along x and y (kN; SpringResult::peak_force_kN).
  std::array<double, 2> peak_column_force_kN{0.0, 0.0};
  /// With column shear capacities (column_shear_capacity_kN, [building.shear_capacity]): how many of its springs
  /// have one, how many reached it, the first instant one did (NaN: none), and the largest peak
  /// force over capacity, with that spring's column, direction, peak force and capacity (kN).
  int springs_with_capacity = 0;
  int shear_failures = 0;
  double first_shear_failure_t_s = 0.0;
  double largest_demand_capacity_ratio = 0.0;
  std::string critical_column;
  char critical_direction = 'x';
  double critical_peak_force_kN = 0.0;
  double critical_capacity_kN = 0.0;
  /// With degrading (IMK) columns: how many of its springs degrade, how many of them failed
  /// (lost their force, SpringResult::degrading_failure_t_s) and the first instant one did (NaN: none).
  int degrading_springs = 0;
  int degrading_failures = 0;
  double first_degrading_failure_t_s = 0.0;
};
/// Below this a contact-free drift ratio or ductility is round-off (y drift under pure x
/// shaking): the pounding-induced ratio to it is not reported.
inline constexpr double kDemandFloor = 1e-9;

/// Per storey, in the springs' order (building, then storey). @pre results match springs.
std::vector<StoreyYielding> storey_yielding(const std::vector<dynamics::YieldingSpring>& springs,
                                            const std::vector<solvers::SpringResult>& results);

/// Integrates the scene with scene.solver (its method's factory in the registry, methods.hpp) and
/// scene.output, within `limits`.
/// With a `sink` (must outlive the call) the history rows and impacts go to it as they come and
/// the report's history keeps its columns only; without, the whole history is in the report.
/// @throws InputError for invalid settings (a given setting the method does not use among them,
///   a contact law the method does not run)
///   or a run whose estimate exceeds the limits; numerical
///   trouble, an exhausted budget or an interrupt come back in the status.
/// What a valid scene may still have got wrong: a floor whose mass per slab area lies outside
/// 0.1–10 t/m² (floors weigh about 0.5–2 t/m²; 1000 times that is kilograms given as tonnes),
/// once per building. A rigid-wall stand-in (a huge mass on purpose) is flagged too; its message
/// says so. `pounding check` prints them and every run's report carries them.
std::vector<RunWarning> scene_warnings(const Scene& scene);

RunReport run_scene(const Scene& scene, const RunLimits& limits = {}, solvers::RunSink* sink = nullptr);

}  // namespace pounding::analysis
