#pragma once
// The event-driven solution: an ODE integrator (behind the Integrator seam) advances the smooth
// motion, its root finder stops at each contact, the impact module resets the velocities, and
// the integrator restarts there. docs/guide/event-handling.md gives the rules and their reasons.
//
// The loop, phase by phase (src/solvers/event_driven.cpp):
//  1. Start. Contacts that exist at rest (|g| within the touch band, on the edge) are an event
//     at t0: integrators report no root at their initial time.
//  2. Phase begins (at t0 and after every event). The next record sample becomes the stop time;
//     every gap is evaluated; pairs masked beside an edge whose vertex is now on it get a floor
//     root (ContactStates); the step bound is set (EventStepBound).
//  3. Step. The integrator advances to a root, a stop time or its own step end.
//  4. Missed contacts. Unless the step bound proved every gap open over the step, the step is
//     scanned on the interpolant (scan_missed_contacts): a dip below zero or a re-closure inside
//     the step is an event at its first crossing, the step is cut there (the recorder advances
//     to it) and the loop goes to 6.
//  5. Record. The recorder integrates history, peaks and energy over the step; compliant
//     contacts integrate their force, impulse and work.
//  6. Event (a root, or a missed contact). The crossed witnesses (WitnessLayout) are decoded.
//     impulse law: holds that slid off their edge or whose force turned tensile are released;
//       each level with a closing pair on its edge is solved as one complementarity problem over
//       all its closed contacts (floor_impacts), slow separations held, the rest masked; then
//       every hold is settled again together (an impulse on one floor changes the force that
//       holds the next).
//     compliant laws: a closing pair starts a contact, the law's switch releases or re-engages
//       it, an opening gap or a slide off the edge ends it.
//     Then the integrator restarts at the event with the new velocities: back to 2.
//  7. After a step without event: overlaps of pairs not held are noted, masked pairs whose gap
//     reopened are armed again, holds' peak force and drift are updated, the step bound is
//     re-evaluated; at a record sample the next becomes the stop time. Back to 3 until the
//     record ends, the budget, the step or the event limit stops the run.
//  8. End. A completed run whose pairs sank deeper than the touch band becomes
//     unresolved_overlap; holds and compliant contacts still open are closed as "end of run".

#include <array>
#include <functional>
#include <memory>
#include <string>

#include "pounding/contact/compliant_law.hpp"
#include "pounding/dynamics/coupled_system.hpp"
#include "pounding/solvers/integrator.hpp"
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

using IntegratorFactory =
    std::function<std::unique_ptr<Integrator>(OdeFunctions& functions, double t0, const Eigen::VectorXd& y0)>;

/// Runs the coupled system from rest over the whole ground motion. Never throws for a numerical
/// failure: the result's status says what happened. @throws InputError for invalid options.
RunResult run_event_driven(const dynamics::CoupledSystem& system, const EventOptions& options,
                           const IntegratorFactory& make_integrator, const std::string& method);

}  // namespace pounding::solvers
