#pragma once
// The clear gap that prevents every contact, from one contact-free run. While no pair touches,
// the motion does not depend on the gap, so each vertex–edge pair's gap is g(t; G) =
// g(t; G₀) + (G − G₀) b(t), with b = ∂g/∂G (the struck edge's normal along x, signed so that
// widening the gap opens it). The pair touches at t for the "touch gap" G(t) = G₀ − g(t; G₀)/b(t);
// the needed gap is the largest touch gap over time and over every pair whose vertex lies on the
// edge in the geometry of that touch gap (GapState::on_segment there, not at the scene's gap).
// Beside it: the code rules ABS, SRSS and DDC from each building's peak displacement towards
// the other. Units: m, s, rad.

#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "pounding/analysis/scene.hpp"
#include "pounding/contact/candidates.hpp"
#include "pounding/dynamics/coupled_system.hpp"
#include "pounding/solvers/run_budget.hpp"

namespace pounding::analysis {

/// The three code rules for one level (m): ABS δ₁ + δ₂, SRSS √(δ₁² + δ₂²), DDC √(δ₁² + δ₂² − 2ρδ₁δ₂).
struct GapRules {
  double abs_m = 0.0;
  double srss_m = 0.0;
  double ddc_m = 0.0;
};

/// @pre δ ≥ 0, ρ ∈ [−1, 1].
GapRules gap_rules(double delta1_m, double delta2_m, double rho);

/// CQC correlation coefficient of two modes (Der Kiureghian 1981), in (0, 1], 1 for equal modes.
/// @pre periods and damping ratios positive.
double cqc_correlation(double period1_s, double damping1, double period2_s, double damping2);

/// One elevation where the facades can touch: a level (slab against slab), or a slab facing the
/// other building's columns between two of its floors (`column`; level.index 0, level.floors the
/// slab's floor and the struck storey, level.elevation_m the slab's).
struct LevelGap {
  contact::Level level;
  bool column = false;
  int slab_building = 0;      // column: the slab's building (0 or 1)
  int storey = 0;             // column: the other building's struck storey
  double height_ratio = 0.0;  // column: where up that storey
  double needed_gap_m = 0.0;  // largest touch gap of the level's pairs; ≤ 0 if they never close
  double t_s = 0.0;           // when
  long candidate = -1;        // index into NeededGap::candidates of the governing pair (−1: none)
  /// δ of building 1 and 2: the peak displacement (m, ≥ 0) of the facing edge's vertices towards
  /// the other building (+x for building 1, −x for building 2), rotation included, and when; at
  /// a slab facing columns, the slab's edge vertices and the column points (their cubic between
  /// the column's floors).
  std::array<double, 2> peak_towards_m{0.0, 0.0};
  std::array<double, 2> peak_t_s{0.0, 0.0};
  GapRules rules;
};

/// The first translational mode along x (the direction of the gap) of one building.
struct GapMode {
  int mode = 1;  // 1-based, longest period first
  double period_s = 0.0;
  double damping_ratio = 0.0;  // Rayleigh ratio at that mode
};

/// What design practice would estimate for yielding buildings: the code rules from the elastic
/// contact-free analysis, each building's peak displacement amplified by a factor (ASCE 7's
/// C_d/I_e, EC8's q), against the needed gap of the yielding ones.
struct AmplifiedElastic {
  double factor = 1.0;
  double elastic_needed_gap_m = 0.0;  // of the same scene with every column elastic, unamplified
  GapRules rules;                     // from factor × the elastic peaks, largest over the levels
  /// The elastic run's status: when it did not complete, the rules cover the record up to its end.
  solvers::RunStatus status = solvers::RunStatus::completed;
};

/// The needed gap at one angle of incidence (the scene's direction_deg: H1's direction).
struct AngleGap {
  double angle_deg = 0.0;
  double needed_gap_m = 0.0;
};

/// The needed gap over every angle of incidence (all_angles_gap()).
struct AllAngles {
  /// "superposition": elastic buildings, the envelope from two contact-free runs (0° and 90°:
  /// every other angle's motion is cos θ times the first plus sin θ times the second); "sweep":
  /// yielding buildings (no superposition), the envelope from one run per angle.
  std::string method;
  double step_deg = 1.0;          // the envelope's angle step
  double record_angle_deg = 0.0;  // the scene's own direction_deg (the needed gap there is NeededGap's)
  /// The needed gap per angle over [0°, 360°): superposition evaluates the touch gaps exactly at
  /// the combined states, sampled every sample_interval_s (a peak between samples may be missed
  /// by O(interval²)); sweep: each angle's own run.
  std::vector<AngleGap> envelope;
  double sample_interval_s = 0.0;  // superposition only
  AngleGap estimate;               // the envelope's largest
  /// Where the needed gap is largest, refined by golden-section search with full contact-free
  /// runs (each exact at its angle, rotation included) within one envelope step of the estimate,
  /// to refine_tolerance_deg; that run's governing level, time and pair (index into the candidates).
  AngleGap worst;
  double refine_tolerance_deg = 0.01;
  int worst_level = 0;
  double worst_t_s = 0.0;
  long worst_candidate = -1;
  int runs = 0;  // contact-free runs it took
  /// completed, or the first run's status that did not complete (the figures are then lower bounds),
  /// and which run that was and why: "the run with the record along 125 deg: solver_failure (...)".
  /// A run that failed gives no needed gap at its angle (NaN in the envelope); the others count.
  solvers::RunStatus status = solvers::RunStatus::completed;
  std::string status_detail;
};

struct NeededGap {
  double scene_gap_m = 0.0;
  double needed_gap_m = 0.0;  // the largest over the levels
  double t_s = 0.0;
  int level = 0;        // 1-based level of the governing pair (0: none, or a slab facing columns)
  long entry = -1;      // index into `levels` of the governing pair's entry (−1: no pair ever closes)
  long candidate = -1;  // index into `candidates`
  std::vector<contact::Candidate> candidates;  // the scene's (its gap and candidate margin)
  std::vector<bool> counted;                   // per candidate: false if widening the gap does not open it (b ≤ 0.1)
  std::vector<LevelGap> levels;
  std::array<GapMode, 2> modes;
  double rho = 0.0;       // CQC coefficient of the two modes
  GapRules rules;         // each rule's largest value over the levels
  long extrema = 0;       // touch-gap maxima located (root returns on the pairs' rates)
  bool yielding = false;  // some building's columns yield: the contact-free run is nonlinear
  long yield_events = 0;  // the yielding columns' branch changes in the contact-free run
  std::optional<AmplifiedElastic> amplified_elastic;  // add_amplified_elastic()
  std::optional<AllAngles> all_angles;                // add_all_angles()
  long steps = 0;
  /// completed, or interrupted / time_limit when the run stopped at end_s: everything above then
  /// covers the record only up to end_s (the needed gap is a lower bound).
  solvers::RunStatus status = solvers::RunStatus::completed;
  std::string status_detail;
  double end_s = 0.0;
  double wall_time_s = 0.0;
  /// Touch gap (m) of each level's governing pair, sampled every history_interval_s; one column
  /// per level (NaN where the vertex is off the edge), times in history_t_s.
  std::vector<double> history_t_s;
  std::vector<std::vector<double>> history_touch_gap_m;
};

struct NeededGapOptions {
  bool adams = false;  // CVODE Adams instead of BDF
  double rtol = std::get<double>(spec(Setting::rtol).default_value);
  double atol = std::get<double>(spec(Setting::atol).default_value);  // m, rad and their rates
  double history_interval_s = 0.01;
  solvers::RunBudget budget{};  // wall time; a SIGINT/SIGTERM (solvers::request_interrupt) also stops it
  /// rtol and atol in the ranges of [solver]'s (methods.hpp). @throws InputError naming the field.
  void validate() const;
};

/// One contact-free run of `system` with CVODE from rest over its ground motion, stopping at
/// every maximum of every pair's touch gap and of every facing vertex's displacement towards the
/// other building (root functions, located on CVODE's dense output to its root tolerance). The
/// needed gap is as accurate as that run. `scene_gap_m`: the clear gap the candidates' rest
/// geometry has. @throws InputError for bad options; std::runtime_error if CVODE fails.
NeededGap needed_gap(const dynamics::CoupledSystem& system, double scene_gap_m, const NeededGapOptions& options);

/// The same for a scene, with its solver's rtol/atol (Adams when its method is cvode-adams).
/// @throws InputError for a bad scene or record (as build_system does), or a bad budget.
NeededGap needed_gap(const Scene& scene, const solvers::RunBudget& budget = {});

/// Sets gap.all_angles: the needed gap over every angle of incidence of the scene's record (or
/// pair), the angle where it is largest and that angle's full result (AllAngles).
/// @throws InputError for a bad scene or budget (as needed_gap).
void add_all_angles(const Scene& scene, NeededGap& gap, const solvers::RunBudget& budget = {});

/// The amplification factor's range (add_amplified_elastic).
inline constexpr Range kAmplificationFactor{0.0, 20.0, "", true};

/// Runs `scene` with every column elastic, contact-free, and sets gap.amplified_elastic from its
/// peaks times `factor`. @throws InputError (key "amplification") for a factor outside
/// kAmplificationFactor or a scene whose columns do not yield (then the rules above are elastic
/// already).
void add_amplified_elastic(const Scene& scene, double factor, NeededGap& gap, const solvers::RunBudget& budget = {});

/// A code rule against the needed gap: unconservative when it asks for less.
struct RuleVerdict {
  const char* rule = "";  // "ABS", "SRSS", "DDC"
  double value_m = 0.0;   // the rule's largest value over the levels
  double margin_m = 0.0;  // value − needed gap: negative = unconservative by that much
  bool unconservative() const { return margin_m < 0.0; }
};
std::vector<RuleVerdict> rule_verdicts(const NeededGap& gap);
/// The same for any rules against a needed gap (e.g. AmplifiedElastic::rules).
std::vector<RuleVerdict> rule_verdicts(const GapRules& rules, double needed_gap_m);

/// What a gap short of the needed one costs: one full event-driven run at that gap.
struct SeverityPoint {
  double gap_m = 0.0;
  std::string status;  // the run's status ("completed", ...)
  long impacts = 0;
  double max_impulse_kNs = 0.0;
  double max_approach_mps = 0.0;
  double energy_lost_kJ = 0.0;  // Σ over impacts
  double wall_time_s = 0.0;
};

/// Runs `scene` (its own solver settings) at the gaps k·needed_gap_m/count, k = 0 … count − 1,
/// `threads` at a time (0: every core); `progress` is called after each run (from any thread,
/// one call at a time). @throws InputError (key `count`, `needed_gap_m`) if count < 2 or
/// needed_gap_m is not positive.
std::vector<SeverityPoint> severity_curve(const Scene& scene, double needed_gap_m, int count, unsigned threads = 0,
                                          const std::function<void(const SeverityPoint&)>& progress = {});

}  // namespace pounding::analysis
