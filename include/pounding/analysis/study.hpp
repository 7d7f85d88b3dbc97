#pragma once
// The work–precision study: every solution path over a ladder of settings, each run measured
// against the exact path (the ground truth of the linear model) and timed.

#include <string>
#include <vector>

#include "pounding/analysis/contact_laws.hpp"
#include "pounding/analysis/scene.hpp"
#include "pounding/solvers/run_result.hpp"

namespace pounding::analysis {

struct StudyOptions {
  int repeat = 3;                // timed runs per case (median)
  bool quick = false;            // each method's quick ladder (MethodInfo::quick_ladder), not its full one
  double match_window_s = 0.05;  // impacts further apart are not a match
  /// Wall time (s) a run of the contact-stiffness ladder may take; it then stops with status
  /// time_limit (explicit methods pay for stiff contacts in steps).
  double stiffness_run_limit_s = 120.0;
  /// @throws InputError naming the field.
  void validate() const;
};

/// How one run compares with the reference.
struct RunErrors {
  std::size_t matched = 0, missing = 0, extra = 0;  // impacts: in both, only in the reference, only here
  double impact_time_s = 0.0;                       // max |Δt| over matched impacts faster than 1 cm/s
  double impact_time_all_s = 0.0;                   // max |Δt| over all matched impacts
  /// max |Δt| over matched impacts before the reference's first sustained contact: there the
  /// exact path is exact to round-off, so this ranks methods below the reference's hold error.
  double impact_time_before_hold_s = 0.0;
  double impulse_relative = 0.0;                                       // max |ΔI|/I_ref over matched impacts > 1 cm/s
  double history_u_m = 0.0, history_v_m = 0.0, history_phi_rad = 0.0;  // max over contact floors
  double peak_u_m = 0.0, peak_v_m = 0.0, peak_phi_rad = 0.0;           // max over all floors
};

/// Impacts matched in time order by contact (same candidate: level, vertex and edge), each to the
/// nearest unused one within `window_s`;
/// histories compared at the samples both runs share (the regular grid).
RunErrors compare_runs(const solvers::RunResult& reference, const solvers::RunResult& run, double window_s);

struct StudyRow {
  std::string method;   // the series' label (StudySeries::label): cvode-bdf, ..., hht-halving, ...
  std::string setting;  // the method's ladder setting: "rtol" or "dt_s"
  double value = 0.0;
  std::string status;
  double run_time_s = 0.0;  // median wall time of the solver over the repeats
  long steps = 0, rhs_evaluations = 0, restarts = 0;
  std::size_t impacts = 0;
  RunErrors errors;
  /// The error is within the reference's own error estimate: the run is as accurate as the
  /// reference can tell, and its error figure is really the reference's.
  bool impact_time_at_reference = false, history_u_at_reference = false;
};

/// One run of the contact-stiffness ladder: a compliant law at one stiffness on one method, at the
/// scene's settings for that method.
struct StiffnessRow {
  std::string law;
  std::string method;
  double stiffness = 0.0;      // in the law's unit (stiffness_unit)
  std::string stiffness_unit;  // "kN/m" or "kN/m^1.5"
  std::string status;
  double run_time_s = 0.0;  // median wall time of the solver over the repeats
  long steps = 0, rhs_evaluations = 0, jacobian_evaluations = 0;
  std::size_t impacts = 0;
  double peak_force_kN = 0.0;  // the largest contact force of the run
};

/// One rung of the truncation ladder: the exact path keeping each building's modes below a
/// cut-off (solver.modes_cutoff_hz), the rest as their static response, against the full one.
struct TruncationRow {
  double cutoff_hz = 0.0;  // 0: every mode (the full exact path, timed like the others)
  int modes_kept = 0;      // of both buildings together
  int modes_total = 0;
  std::string status;
  double run_time_s = 0.0;  // median wall time of the solver over the repeats
  long steps = 0;
  std::size_t impacts = 0;
  RunErrors errors;  // against the reference (the full exact path)
};

/// The truncation ladder's cut-offs (Hz): 2, 5, 10 and 15, then 0 (every mode). The paper scene's
/// modes span 0.9 to 15.7 Hz, so these keep from 6 to 49 of its 51.
std::vector<double> truncation_ladder();

/// The ladder's stiffnesses for a compliant law, in its unit: its default times 0.1, 1, 10, 100
/// and 1000 (quick: 1 and 100, kelvin only); empty for the impulse law.
std::vector<double> stiffness_ladder(const ContactLawInfo& law, bool quick);

struct StudyResult {
  std::string scene;
  double gap_m = 0.0;
  std::string reference_method;  // study_reference(): "exact", or cvode-bdf at a tight rtol
  solvers::RunResult reference;  // the run of reference_method
  double reference_run_time_s = 0.0;
  /// The reference against itself with its held stretches 100 times looser (hold_rtol × 100), or
  /// for yielding columns at 10 times its rtol: an upper estimate of the reference's own error.
  RunErrors reference_error;
  std::vector<StudyRow> rows;
  std::vector<StiffnessRow> stiffness_rows;  // every compliant law's ladder on each of its methods
  /// The exact path truncated at each cut-off of truncation_ladder() that keeps a mode of both
  /// buildings (others are left out), against the reference.
  std::vector<TruncationRow> truncation_rows;
  /// A SIGINT/SIGTERM (solvers::request_interrupt) ended the study: the rows run so far, the
  /// last of them (and the reference, if it was still running) with status interrupted.
  bool interrupted = false;
};

/// The reference of a scene the exact path cannot run (columns that yield, a compliant contact
/// law): cvode-bdf at this rtol (atol rtol/100 m), its own error estimated by the same at 10
/// times the rtol.
inline constexpr double kCvodeReferenceRtol = 1e-12;

/// True when a building's columns yield.
bool yields(const Scene& scene);
/// True when the exact path runs the scene: elastic columns and a contact law it takes.
bool exact_runs(const Scene& scene);
/// The study's reference for `scene`: "exact", or "cvode-bdf rtol 1e-12" where exact_runs() is false.
std::string study_reference(const Scene& scene);

/// Runs every series of every method of the registry over its ladder against the reference
/// method (the exact path, with the scene's settings for it), then every compliant law over its
/// stiffness ladder on each method that runs it (what each method pays as contacts stiffen), then
/// the reference truncated at each cut-off of truncation_ladder() (what leaving modes out costs).
/// For a scene the exact path cannot run, the reference is study_reference()'s and only the
/// methods that run the scene (yielding columns, its contact law) have rows; the truncation ladder
/// (the exact path's) is left out, and for yielding columns the stiffness ladder too (its runs are
/// elastic in what they measure).
/// `progress` and `stiffness_progress` are called with each finished row (for printing as it
/// goes). After an interrupt request no further run starts. @throws InputError as
/// require_study_scene.

/// A row is refused (it needs a compliant law, and the study measures against the exact path,
/// which runs the impulse law only). @throws InputError naming the buildings.
void require_study_scene(const Scene& scene);

StudyResult run_study(const Scene& scene, const StudyOptions& options,
                      const std::function<void(const StudyRow&)>& progress = {},
                      const std::function<void(const StiffnessRow&)>& stiffness_progress = {});

}  // namespace pounding::analysis
