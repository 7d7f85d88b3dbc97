#pragma once
// The event-driven solution: an ODE integrator (behind the Integrator seam) advances the smooth
// motion, its root finder stops at each contact and at each yielding column's branch change, the
// contact law's policy applies the event, and the integrator restarts there. The loop is the
// Simulator's (simulator.hpp); this system's part in each phase is below, and
// docs/guide/event-handling.md gives the rules and their reasons.
//
//  1. start: contacts that exist at rest (|g| within the touch band, on the edge) are an event at
//     t0; a column started beyond its yield drift yields at once. The prepared integrator: one
//     that steps across record samples (the deviation form) has its energy split and its peaks
//     located at the samples.
//  2. begin_phase: every gap is evaluated; pairs masked beside an edge whose vertex is now on it
//     get a floor root (ContactStates); covered and live candidates are updated (CornerCover);
//     the step bound is set (EventStepBound).
//  3. step: the root functions are the witnesses (WitnessLayout): each live candidate's gap, a
//     hold's force and its point's distance to the edge's ends, a compliant contact's overlap
//     and switch, and each yielding column spring's distance to its next branch change.
//  4. examine_step: unless the step bound proved every gap open over the step, the step is
//     scanned on the interpolant (scan_missed_contacts): a dip below zero, a re-closure or a
//     dormant corner candidate closing inside the step is an event at its first crossing;
//     grazes become touches.
//  5. record: the recorder integrates history, peaks and energy over the step; compliant
//     contacts integrate their force, impulse and work.
//  6. on_event: the crossed witnesses are decoded (with armed pairs that a rounding took through
//     zero closing).
//     impulse law: holds that slid off their edge are handed round the corner or released,
//       holds whose force turned tensile released; each group of levels with a closing pair on
//       its edge is one complementarity problem over all its closed contacts (floor_impacts), slow
//       separations held (their closing keeping the impact's other contacts at their rebound),
//       the rest masked; then every hold is settled again together.
//     compliant laws: a closing pair starts a contact, the law's switch releases or re-engages
//       it, an opening gap ends it, a slide off the edge hands it round the corner or ends it.
//     Then the yielding columns whose witness crossed switch branch (a column's drift rate may
//     have turned with the impulse); more than max_events_per_s contact events, or switches of
//     one column, within a simulated second end the run with event_limit (chattering), a drift
//     beyond kCollapseDriftRatio of a storey with collapse. The integrator always restarts.
//  7. after_step: overlaps of open pairs are noted, a collapse is checked, masked pairs whose gap
//     reopened are armed again, covered and live candidates updated, holds' peak force and drift
//     updated, the step bound re-evaluated.
//  8. end: a completed run whose pairs sank deeper than the touch band becomes
//     unresolved_overlap (naming the vertex, edge, time and reason); holds and compliant
//     contacts still open are closed as "end of run"; yielding results and the energy audit.

#include <string>

#include "pounding/dynamics/coupled_system.hpp"
#include "pounding/solvers/event_options.hpp"
#include "pounding/solvers/integrator.hpp"
#include "pounding/solvers/run_result.hpp"

namespace pounding::solvers {

/// Runs the coupled system from rest over the whole ground motion. Never throws for a numerical
/// failure: the result's status says what happened. @throws InputError for invalid options.
RunResult run_event_driven(const dynamics::CoupledSystem& system, const EventOptions& options,
                           const IntegratorFactory& make_integrator, const std::string& method);

}  // namespace pounding::solvers
