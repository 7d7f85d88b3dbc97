// What both contact-law policies share (law_events.hpp): the hand-over of a contact round a corner.
#include "law_events.hpp"

#include <cmath>

namespace pounding::solvers {

bool EventContext::slides_along_face(std::size_t i, const dynamics::VectorXd& y, const contact::GapState& s) const {
  const contact::CornerLinks& links = cover.links();
  const int end = s.segment_param < 0.5 ? 0 : 1;
  const long next = links.next[i][end];
  // The corner is the next edge's other end; a twin there means that edge faces the vertex's slab.
  if (next == contact::kNoCandidate || links.twin[static_cast<std::size_t>(next)][1 - end] == contact::kNoCandidate)
    return false;
  const auto j = static_cast<std::size_t>(next);
  const contact::GapState along = system.gap(y, j);
  return std::abs(along.gap_m) <= options.contact_tolerance_m &&
         along.gap_rate_mps >= -system.gap_rate_round_off_mps(y, j);
}

std::optional<std::size_t> EventContext::successor(std::size_t i, const dynamics::VectorXd& y, bool compliant) const {
  const contact::GapState s = system.gap(y, i);
  const int end = s.segment_param < 0.5 ? 0 : 1;
  const contact::CornerLinks& links = cover.links();
  const double band_m = options.contact_tolerance_m;
  const double reach_m = 2.0 * (std::abs(s.gap_m) + band_m);
  for (const long candidate : {links.twin[i][end], links.next[i][end]}) {
    if (candidate == contact::kNoCandidate) continue;
    const auto j = static_cast<std::size_t>(candidate);
    if (!states.open(j)) continue;  // already in contact: it carries on by itself
    const contact::Candidate& c = system.candidates()[j];
    const contact::GapState t = system.gap(y, j);
    const double slack = reach_m / (c.edge_end_rest - c.edge_start_rest).norm() + contact::kOnSegmentTolerance;
    const bool touching = compliant ? t.gap_m < 0.0 : t.gap_m <= band_m;
    if (touching && t.segment_param >= -slack && t.segment_param <= 1.0 + slack) return j;
  }
  return std::nullopt;
}

}  // namespace pounding::solvers
