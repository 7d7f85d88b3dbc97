#pragma once
// The scan for contacts inside a step that no root function stopped at. A root function sees a
// crossing only where it changes sign between the step's ends, so the event-driven run examines
// every step that ends without a root on the step's interpolant:
//  - an armed pair whose gap falls at the start and rises at the end, both ends open, has its
//    minimum inside: below zero it is a contact (at the first crossing), within the touch band a
//    graze (a touch, no impulse);
//  - a masked pair sinking at the end (g < 0, ġ < 0) closed again after it was handled: a contact
//    at the last crossing of zero, or at the step end when it never rose above zero;
//  - a dormant corner candidate (no root function: CornerCover) closed on its edge at the end: a
//    contact at the last crossing of zero on the edge.
// A pair masked as it passed beside its edge, or a dormant one, that comes onto the edge already
// behind it is a contact at the step end only if its vertex is inside the other slab. Covered
// candidates are not examined: a contact in progress holds their point.
// Gaps in m, rates in m/s, times in s.

#include <cstddef>
#include <optional>
#include <vector>

#include "pounding/contact/gap.hpp"
#include "pounding/solvers/contact_states.hpp"

namespace pounding::solvers {

/// The step's interpolant, seen through one candidate's gap at a time.
class StepGaps {
 public:
  virtual ~StepGaps() = default;
  /// Candidate i's gap at t_s inside the step.
  virtual contact::GapState at(std::size_t i, double t_s) = 0;
  /// The round-off (m/s) of candidate i's gap rate in the state of the last at(i, ·).
  virtual double rate_round_off_mps(std::size_t i) = 0;
  /// How deep candidate i's vertex lies inside the struck slab (m, 0 outside) in the state of the
  /// last at(i, ·) (CoupledSystem::depth_inside_m).
  virtual double depth_inside_m(std::size_t i) = 0;
};

struct MissedContact {
  double t_s = 0.0;
  std::size_t candidate = 0;
};

struct Graze {  // a minimum within the touch band: a touch to report, no event
  double t_s = 0.0;
  std::size_t candidate = 0;
  contact::GapState gap;
};

struct ScanTolerances {
  double contact_tolerance_m = 1e-8;  // EventOptions::contact_tolerance_m
  double overlap_allowance_m = 1e-9;  // EventOptions::overlap_allowance_m
};

/// The earliest missed contact in the step (t_start, t_end], if any; grazes of armed pairs are
/// appended to `grazes` in candidate order. `start`, `end`: every candidate's gap at the step's
/// ends; `cover`: which candidates were live over the step and which are covered (null: every
/// candidate live, none covered). @pre t_start < t_end, start.size() == end.size() == states.size().
std::optional<MissedContact> scan_missed_contacts(const ContactStates& states, StepGaps& path, double t_start,
                                                  double t_end, const std::vector<contact::GapState>& start,
                                                  const std::vector<contact::GapState>& end,
                                                  const ScanTolerances& tolerances, std::vector<Graze>& grazes,
                                                  const CornerCover* cover = nullptr);

}  // namespace pounding::solvers
