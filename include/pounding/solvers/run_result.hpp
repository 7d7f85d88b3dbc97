#pragma once
// What every solution path returns: events, peaks, history, energy audit, statistics and a
// status with a named reason. Units in the member names.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "pounding/model/polygon.hpp"

namespace pounding::solvers {

enum class RunStatus {
  completed,           // reached the end of the record
  solver_failure,      // the integrator gave up; detail names its flag
  event_limit,         // more events per simulated second than allowed: an unresolved accumulation
  step_limit,          // more internal steps than allowed
  unresolved_overlap,  // slabs not held sank into each other deeper than the contact tolerance; not trustworthy
  time_limit,          // the run's wall-time budget was used up
  interrupted,         // stopped by SIGINT/SIGTERM; the outputs hold everything up to end_s
  non_finite,          // the state or time became NaN or infinite: the solution diverged
  collapse,            // a yielding column's drift passed kCollapseDriftRatio of its storey: the building fell
};
/// A yielding column whose drift passes this fraction of its storey height ends the run with
/// RunStatus::collapse: the frame has failed (P-Δ beyond the hardening drives the drift away), and
/// the model's small rotations and straight columns no longer describe it.
inline constexpr double kCollapseDriftRatio = 0.1;
std::string_view to_string(RunStatus status);

/// Which contact an impact, touch, sustained contact or force sample is at, numbered as the
/// outputs number it (1-based). Slab to slab, the striking building's slab vertex meets the struck
/// building's slab edge; slab to column (level 0), the striking building's slab meets the struck
/// building's column, `edge` is the slab's edge that meets it and `vertex` is 0.
struct ContactIdentity {
  std::size_t candidate = 0;           // index into the candidate list
  int level = 0;                       // 1-based level (floors at a common elevation); 0 slab to column
  std::array<int, 2> buildings{1, 2};  // the pair (1-based, first < second)
  std::array<int, 2> floors{0, 0};     // buildings[k]'s floor at the level; slab to column: the slab's
                                       // floor and the column's storey
  double elevation_m = 0.0;            // the level's elevation (m); slab to column: the slab's
  int striking_building = 0;           // the building whose slab strikes (one of `buildings`)
  int struck_building = 0;             // the other one: its slab edge, or its column, is struck
  std::size_t vertex = 0;              // the striking vertex, in its slab's outline; 0 slab to column
  std::size_t edge = 0;                // slab to slab: the struck edge of the struck slab's outline;
                                       // slab to column: the striking slab's edge that meets the column
  int column = 0;                      // slab to column: the struck column, in its building's list; else 0
};

struct ImpactRecord : ContactIdentity {
  double t_s = 0.0;
  model::Point2 vertex_rest;             // the striking vertex at rest (m); slab to column: the column's point
  model::Point2 point;                   // contact point at impact (m)
  double approach_velocity_mps = 0.0;    // −ġ⁻ > 0
  double separation_velocity_mps = 0.0;  // ġ⁺ (= k·approach for a lone contact)
  double impulse_kNs = 0.0;              // compliant laws: ∫F dt over the contact
  double energy_lost_kJ = 0.0;           // of the whole slab pair, shared by its simultaneous contacts
  /// Compliant laws: onset (t_s) to release, and the largest force in between. 0 for the
  /// impulse law, whose impacts are instantaneous impulses with no finite force.
  double duration_s = 0.0;
  double peak_force_kN = 0.0;
  bool starts_hold = false;  // the pair was then held in sustained contact
  // Slab to column: the height ratio ξ up the struck column's storey, and the end shear and
  // largest moment the peak force causes in the fixed–fixed column (contact::column_demand).
  // Zero for slab to slab.
  double height_ratio = 0.0;
  double column_shear_kN = 0.0;
  double column_moment_kNm = 0.0;
  /// column_shear_kN over the column building's column_shear_capacity_kN; NaN when it gives none.
  double column_shear_ratio = std::numeric_limits<double>::quiet_NaN();
  /// Slab to column: the struck column's largest shear over the contact with its sway
  /// (docs/model.md §6b, "Sway and impact together"), along the plan axis of its capacity: the
  /// larger of |V_s + N₁ F n_a| and |V_s − N₂ F n_a|, V_s the column's sway shear; when it was
  /// largest, and V_s then (signed along +x or +y); over the capacity (NaN without one).
  double column_total_shear_kN = 0.0;
  double column_total_shear_t_s = 0.0;
  double column_sway_shear_kN = 0.0;
  double column_total_shear_ratio = std::numeric_limits<double>::quiet_NaN();
};

struct TouchRecord : ContactIdentity {  // contact with ġ ≥ 0: no impulse
  double t_s = 0.0;
  model::Point2 point;
  double gap_rate_mps = 0.0;
  double gap_m = 0.0;
};

struct SustainedContactRecord : ContactIdentity {
  double start_s = 0.0;
  double release_s = 0.0;
  std::string release_reason;  // "tensile force", "slid off the edge", "end of run", ...
  double max_force_kN = 0.0;
  double max_gap_drift_m = 0.0;  // max |g| while held
  double impulse_kNs = 0.0;      // impulse shares taken while held, when impacts struck its floor
};

/// A located contact's floor of `building` (1-based, one of the pair).
inline int floor_of(const ContactIdentity& r, int building) { return r.floors[building == r.buildings[0] ? 0 : 1]; }

struct Peak {
  double value = 0.0;  // max |x| (signed value at that instant)
  double t_s = 0.0;
  void update(double x, double t) {
    if (std::abs(x) > std::abs(value)) {
      value = x;
      t_s = t;
    }
  }
};

/// A struck column that reached its shear capacity under a slab's push (compliant slab-to-column
/// contact, docs/model.md §6b): its shear with its sway, the larger of |V_s + N₁ F n_a| and
/// |V_s − N₂ F n_a|, located where it reaches V_c (or found over it at the contact's onset).
struct StruckColumnFailure : ContactIdentity {  // the contact's identity, as its impact's
  double t_s = 0.0;
  std::string column_key;                             // the column's scene key (model::column_key)
  model::Point2 column_rest = model::Point2::Zero();  // its point at rest (m), the impact's vertex_rest
  int storey = 1;                                     // the column's storey (1-based)
  int axis = 0;                                       // 0: x, 1: y (the capacity's direction)
  double capacity_kN = 0.0;
  double shear_kN = 0.0;       // with its sway, at t_s (≥ capacity_kN)
  double sway_shear_kN = 0.0;  // V_s at t_s
  double force_kN = 0.0;       // the contact's force F at t_s
  /// |V_s| alone was at or over the capacity: an elastic column (checked only while pushed) whose
  /// sway had taken it over before the push began.
  bool sway_over_capacity = false;
  bool loses_stiffness = false;  // its spring along the axis went to the failed branch
};

/// One member-force quantity of a storey or a column (solvers/member_forces.hpp) and its peak.
struct MemberForce {
  enum class Kind { shear_x, shear_y, torque, moment_x, moment_y };  // kN, kN, kN·m, kN·m, kN·m
  int building = 0;                                                  // 0-based in the scene
  int storey = 1;                                                    // 1-based
  int column = -1;         // 0-based in its building's column list; -1: the storey's resultant
  std::string column_key;  // the column's scene key (model::column_key); empty for a storey
  Kind kind = Kind::shear_x;
  /// The largest |value| (with its sign) over the instants the recorder measures: every step's
  /// end, every event and every history sample (not located between them).
  Peak peak;
};

/// "Vx_kN", "Vy_kN", "T_kNm", "Mx_kNm", "My_kNm".
std::string_view member_force_name(MemberForce::Kind kind);

struct FloorPeaks {
  int floor = 0;
  Peak u_m, v_m, phi_rad;
  std::vector<Peak> vertex_dx_m;  // x-displacement of each contact vertex of the building
  /// Absolute acceleration of the CM, q̈ + r a_g (m/s², rad/s²), the solver's own rhs with every
  /// contact force in it. The impulse law's impacts add Dirac parts that this smooth part leaves
  /// out (their impulses are in the impacts).
  Peak ax_abs_mps2, ay_abs_mps2, phi_ddot_radps2;
  /// Drift ratio of the storey below this floor: displacement of floor j minus floor j − 1 (the
  /// ground for j = 1) over the storey height, along x and y, at the CM ...
  Peak drift_x, drift_y;
  /// ... and at each slab corner, in outline order.
  std::vector<Peak> corner_drift_x, corner_drift_y;
  /// The same drift ratios at the end of the run, and their rates (1/s): slot 2k + axis (axis 0
  /// x, 1 y) holds the CM's for k = 0 and corner k's for k ≥ 1. Empty without drift peaks.
  std::vector<double> end_drift, end_drift_rate_per_s;
};

/// The corner drift peak of largest magnitude over the slab's corners and both axes.
struct WorstCornerDrift {
  std::size_t corner = 0;  // 1-based, in the slab outline
  char axis = 'x';
  Peak peak;
};
inline WorstCornerDrift worst_corner_drift(const FloorPeaks& floor) {
  WorstCornerDrift worst;
  for (std::size_t k = 0; k < floor.corner_drift_x.size(); ++k) {
    for (const auto& [axis, peak] :
         {std::pair{'x', floor.corner_drift_x[k]}, std::pair{'y', floor.corner_drift_y[k]}}) {
      if (worst.corner == 0 || std::abs(peak.value) > std::abs(worst.peak.value)) worst = {k + 1, axis, peak};
    }
  }
  return worst;
}

struct BuildingPeaks {
  std::string name;
  std::vector<int> contact_vertices;                 // their 1-based numbers in the slab outline, ascending
  std::vector<model::Point2> contact_vertices_rest;  // the same vertices at rest; vertex_dx_m follows this order
  std::vector<FloorPeaks> floors;                    // every floor of the building
};

struct EnergyAudit {                        // relative motion, kJ, integrated along the run
  double input_kJ = 0.0;                    // ∫ −q̇ᵀ M r a_g dt
  double kinetic_kJ = 0.0;                  // at the end
  double strain_kJ = 0.0;                   // at the end
  double damping_kJ = 0.0;                  // ∫ q̇ᵀ C q̇ dt
  double impact_loss_kJ = 0.0;              // Σ over impacts
  double constraint_work_kJ = 0.0;          // ∫ λ ġ dt during holds (ideally 0)
  double algorithmic_dissipation_kJ = 0.0;  // HHT: energy its update removes (numerical damping); 0 elsewhere
  double hysteretic_kJ = 0.0;               // dissipated by the yielding columns; 0 when every column stays elastic
  double residual_kJ() const {
    return input_kJ + constraint_work_kJ - kinetic_kJ - strain_kJ - damping_kJ - impact_loss_kJ -
           algorithmic_dissipation_kJ - hysteretic_kJ;
  }
};

/// One yielding column spring over a run (dynamics::YieldingSprings, same order).
struct SpringResult {
  double peak_drift_m = 0.0;  // largest |drift| at the step ends and events (exact once yielded)
  double first_yield_t_s = std::numeric_limits<double>::quiet_NaN();  // NaN: never yielded
  int yield_count = 0;                                                // yielding phases
  double hysteretic_kJ = 0.0;                                         // energy it dissipated
  double final_drift_m = 0.0;                                         // drift at the end of the run
  double final_slip_m = 0.0;  // its plastic part's slip at the end (the drift at zero force, α = 0)
  /// Its largest |force| (kN) at the step ends and events (exact at a yielding phase's end).
  double peak_force_kN = 0.0;
  /// When |force| first reached the column's shear capacity (located as an event); NaN: never, or
  /// no capacity given.
  double shear_failure_t_s = std::numeric_limits<double>::quiet_NaN();
  /// When a degrading (IMK) spring's law failed (a β past 1, its energy spent, the ultimate
  /// drift, no residual strength) and it lost its force; NaN: never, or not degrading.
  double degrading_failure_t_s = std::numeric_limits<double>::quiet_NaN();
};

/// "Inside means inside" (docs/model.md §5a), for a vertex `gap_m` (< 0) behind its edge's line
/// whose distance to the other slab's nearest edge is `depth_m` when it lies inside that slab (0
/// outside): whether that edge is the nearest one, so that the vertex is inside across it (a vertex
/// measurably nearer another edge came in across that one, or is at a corner).
inline bool inside_across_edge(double gap_m, double depth_m) {
  return depth_m > 0.0 && depth_m >= -gap_m * (1.0 - 1e-6);
}

/// The gap to note as that vertex's overlap: the gap itself within the touch band `band_m` (the
/// vertex is at the slab's outline, whichever edge is nearer) or inside across this edge; the
/// depth when inside but nearer another edge; none (NaN) outside. `depth_inside_m()` is asked
/// only beyond the band.
template <class Depth>
double noted_overlap_m(double gap_m, double band_m, const Depth& depth_inside_m) {
  if (gap_m >= -band_m) return gap_m;
  const double depth_m = depth_inside_m();
  if (!(depth_m > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return inside_across_edge(gap_m, depth_m) ? gap_m : -depth_m;
}

struct SolverStatistics {
  long steps = 0;
  long rhs_evaluations = 0;
  long root_evaluations = 0;
  long jacobian_evaluations = 0;
  long error_test_failures = 0;
  long restarts = 0;               // re-initialisations after events
  long events = 0;                 // root returns handled (impacts, touches, releases, ...)
  long interpolant_events = 0;     // contacts found inside a step from the interpolant (grazing)
  long yield_events = 0;           // yielding columns' branch changes (yield, unload); not in `events`
  long off_segment_crossings = 0;  // roots on an edge's extension: not contacts, ignored
  /// Corners (docs/model.md §5a): the corner candidates, how many of them were ever armed (a live
  /// root function), and the contacts handed round a corner to another candidate.
  long corner_candidates = 0;
  long corner_candidates_armed = 0;
  long corner_handovers = 0;
  long iterative_lcp_solves = 0;      // impact and hold problems solved by Gauss–Seidel (docs/model.md §6)
  double largest_lcp_residual = 0.0;  // their largest residual (contact::LcpSolution::residual)
  void note_lcp(bool exact, double residual) {
    if (exact) return;
    ++iterative_lcp_solves;
    largest_lcp_residual = std::max(largest_lcp_residual, residual);
  }
  long halvings = 0;             // HHT: step halvings on overlap
  double smallest_step_s = 0.0;  // HHT: the smallest step taken
  long unresolved_contacts = 0;  // HHT: times a pair sank deeper than the tolerance at an accepted step end
  /// The deepest overlap −g (m, ≥ 0) of a pair not held in sustained contact, seen at a step end,
  /// an event or a located minimum; when, and which candidate (−1: none overlapped).
  double max_interpenetration_m = 0.0;
  double max_interpenetration_t_s = 0.0;
  long max_interpenetration_candidate = -1;
  void note_overlap(double gap_m, double t_s, std::size_t candidate) {
    if (-gap_m > max_interpenetration_m) {
      max_interpenetration_m = -gap_m;
      max_interpenetration_t_s = t_s;
      max_interpenetration_candidate = static_cast<long>(candidate);
    }
  }
  double wall_time_s = 0.0;
};

/// The normal force of one contact at a history sample (contacts_history.csv): a compliant law's
/// force, or for the impulse law the force λ holding a sustained contact. Contacts without force
/// at that instant have no sample.
struct ContactForceSample : ContactIdentity {
  double t_s = 0.0;
  double gap_m = 0.0;         // signed gap g (< 0: overlap)
  double gap_rate_mps = 0.0;  // ġ
  double force_kN = 0.0;      // > 0 pushes the slabs apart
};

/// Sampled time history: one row per sample, columns named in `columns` (units in the name).
struct History {
  double interval_s = 0.0;  // regular sampling interval; event rows fall between
  std::vector<int> levels;  // the levels written, in column order (each: building 1's floor, then 2's)
  std::vector<std::string> columns;
  std::vector<double> time_s;
  std::vector<Eigen::VectorXd> rows;
  std::vector<ContactForceSample> contact_forces;  // at the same instants, in time order
};

/// What a run records besides its impacts, touches, sustained contacts, statistics and energy
/// audit (always recorded). A part left out is neither computed nor written.
struct OutputSelection {
  bool history = true;             // history rows and contact-force samples (History)
  bool displacement_peaks = true;  // FloorPeaks' u_m, v_m, phi_rad and vertex_dx_m
  bool acceleration_peaks = true;  // ax_abs_mps2, ay_abs_mps2, phi_ddot_radps2
  bool drift_peaks = true;         // drift_x, drift_y and the corner drifts
  bool member_forces = false;      // storey and column forces (MemberForce), in the history too
  bool any_peaks() const { return displacement_peaks || acceleration_peaks || drift_peaks; }
};

struct RunResult {
  RunStatus status = RunStatus::completed;
  std::string status_detail;
  std::string method;
  double start_s = 0.0;
  double end_s = 0.0;  // where the run stopped
  std::vector<ImpactRecord> impacts;
  std::vector<TouchRecord> touches;
  std::vector<SustainedContactRecord> sustained_contacts;
  OutputSelection outputs;  // what was recorded; the peaks of groups left out stay 0
  std::vector<BuildingPeaks> peaks;
  EnergyAudit energy;
  SolverStatistics statistics;
  History history;
  std::vector<SpringResult> springs;       // empty unless some building's columns yield
  std::vector<MemberForce> member_forces;  // empty unless outputs.member_forces
  /// Whether some struck column's shear with its sway was watched against its capacity, and
  /// those that reached it, in order of time.
  bool struck_columns_watched = false;
  std::vector<StruckColumnFailure> struck_column_failures;
};

}  // namespace pounding::solvers
