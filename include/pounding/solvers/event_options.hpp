#pragma once
// The event-driven run's settings (run_event_driven, event_driven.hpp): the contact law, the
// event loop's tolerances and limits, and what it records. Units in the names (m, s, m/s, kN).

#include <Eigen/Core>
#include <array>
#include <vector>

#include "pounding/contact/compliant_law.hpp"
#include "pounding/solvers/run_budget.hpp"
#include "pounding/solvers/run_result.hpp"
#include "pounding/solvers/run_sink.hpp"

namespace pounding::solvers {

struct EventOptions {
  double restitution = 0.5;  // Newton k ∈ [0, 1]
  /// impulse: velocity jumps and held contacts. kelvin, hertzdamp, jankowski: a force while the
  /// slabs overlap, its damping set by `restitution` (contact/compliant_law.hpp); no holds.
  contact::ContactLaw law = contact::ContactLaw::impulse;
  /// The compliant law's stiffness, > 0: kelvin's k (kN/m), hertzdamp's k_h or jankowski's β
  /// (kN/m^1.5). Unused by impulse.
  double contact_stiffness = 0.0;
  /// A candidate counts as in contact at an event when |g| ≤ this (m): contacts this close at the
  /// same instant are solved together as simultaneous.
  double contact_tolerance_m = 1e-8;
  /// A contact that just took an impulse is masked until its gap re-opens beyond this (m); far
  /// below the height of the shortest flight that is not held (hold_height_m). A released
  /// sustained contact opens only cubically (its force, so g̈, starts at zero) and is masked until
  /// its gap exceeds contact_tolerance_m instead, so solver noise is not taken for a new contact.
  double reopen_gap_m = 1e-10;
  /// The deepest overlap (m) a masked contact may reach before its own root function stops the
  /// integrator: a masked pair's root is g − (min(g at masking, 0) − this), so a re-closure is
  /// never stepped over whatever the step size; the crossing of g = 0 is then located on the
  /// step's interpolant.
  double overlap_allowance_m = 1e-9;
  /// Sticking threshold: after an impact, a pair that separates slower than this (m/s) while
  /// pressed together (free g̈ < 0) is held in sustained contact. With k < 1 the bounce speeds
  /// fall geometrically; this cuts the accumulation off after the bounce that drops below it.
  double hold_velocity_mps = 1e-3;
  /// A pair whose next flight would rise less than this (m), v⁺²/(2|g̈|), is held as well,
  /// whatever hold_velocity_mps says: such a bounce is below what the integrators resolve at
  /// their default tolerances, and chasing it only accumulates round-off (and energy).
  double hold_height_m = 1e-8;
  /// A run with more events than this within one simulated second stops with event_limit.
  double max_events_per_s = 2000;
  long max_steps = 10'000'000;
  RunBudget budget;  // wall time; a run also stops when interrupted
  /// Largest step (s). 0: automatic, the shortest damped period among the modes that move some
  /// candidate's gap by more than overlap_allowance_m with their present amplitude, divided by
  /// steps_per_period (GapModeBound), re-evaluated after every step and event. So no gap rate
  /// can change sign twice inside a step and every minimum of a gap inside a step is examined
  /// (see the interpolant check in the loop), while a stiff storey whose mode is overdamped or
  /// barely moves sets no bound.
  double max_step_s = 0.0;
  double steps_per_period = 4.0;
  /// > 0: the integrator keeps only the modes below this frequency (Hz) and takes the rest as
  /// quasi-static (the exact path's truncation, ExactSettings::modes_cutoff_hz), so the automatic
  /// step bound counts those modes only. 0: every mode.
  double modes_cutoff_hz = 0.0;
  /// With the automatic bound and the impulse law: in free flight, a step may also reach as far
  /// as every gap provably stays above contact_tolerance_m (GapClearance, from the modal
  /// amplitudes), up to the next record sample, so a step far from contact spans a whole record
  /// interval and no gap can cross, dip below zero or touch unseen inside it. For integrators
  /// whose energy_between is a closed form (the exact path's): the recorder's Gauss quadrature
  /// of the energy integrals needs short steps.
  bool clearance_steps = false;
  Eigen::VectorXd initial_state;    // (q, q̇) at the record's start; empty: at rest
  OutputSelection outputs;          // what the run records besides impacts and energy; default: all
  std::vector<int> history_floors;  // levels (1-based) to write; empty: every level
  /// Other slabs to write as well, {building (0 or 1), floor (1-based)}: any floor of either
  /// building, after the levels' slabs (Recorder).
  std::vector<std::array<int, 2>> history_other_floors;
  double history_interval_s = 0.01;
  /// Receives the history rows and impacts as they come (the history then holds no rows); null:
  /// the whole history is kept in the result. Must outlive the run.
  RunSink* sink = nullptr;

  /// @pre restitution ∈ [0, 1] (user input is checked by the scene's contact validator).
  /// @throws InputError for restitution 0 with the jankowski law (its damping is infinite).
  /// @throws InputError naming any other field.
  void validate() const;
};

}  // namespace pounding::solvers
