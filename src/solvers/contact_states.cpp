#include "pounding/solvers/contact_states.hpp"

#include <algorithm>

namespace pounding::solvers {

ContactStates::ContactStates(std::size_t count, double overlap_allowance_m)
    : overlap_allowance_m_(overlap_allowance_m),
      modes_(count, ContactMode::armed),
      reopen_at_m_(count, 0.0),
      mask_floor_m_(count, -kNoFloor) {}

double ContactStates::gap_witness(std::size_t i, double gap_m) const {
  if (modes_[i] == ContactMode::armed) return gap_m;
  if (modes_[i] == ContactMode::masked && has_floor(i)) return gap_m - mask_floor_m_[i];
  return 1.0;
}

void ContactStates::leave_lists(std::size_t i) {
  if (const auto at = std::find(held_.begin(), held_.end(), i); at != held_.end()) held_.erase(at);
  if (const auto at = std::find(acting_.begin(), acting_.end(), i); at != acting_.end()) acting_.erase(at);
}

void ContactStates::mask(std::size_t i, double reopen_m, double gap_m) {
  leave_lists(i);
  modes_[i] = ContactMode::masked;
  reopen_at_m_[i] = reopen_m;
  mask_floor_m_[i] = std::min(gap_m, 0.0) - overlap_allowance_m_;
}

void ContactStates::mask_beside_edge(std::size_t i, double reopen_m) {
  leave_lists(i);
  modes_[i] = ContactMode::masked;
  reopen_at_m_[i] = reopen_m;
  mask_floor_m_[i] = -kNoFloor;
}

void ContactStates::rearm(const std::vector<contact::GapState>& gaps, const Arrived& arrived) {
  for (std::size_t i = 0; i < modes_.size(); ++i) {
    if (modes_[i] == ContactMode::masked && gaps[i].gap_m > reopen_at_m_[i]) modes_[i] = ContactMode::armed;
  }
  watch_arrivals(gaps, arrived);
}

void ContactStates::watch_arrivals(const std::vector<contact::GapState>& gaps, const Arrived& arrived) {
  // Masked as it passed beside the edge, the vertex has come onto it: from here on its gap is a
  // depth into the other slab, watched by a root as a contact's is.
  for (std::size_t i = 0; i < modes_.size(); ++i) {
    if (modes_[i] == ContactMode::masked && !has_floor(i) && gaps[i].on_segment() && arrived(i)) {
      mask_floor_m_[i] = std::min(gaps[i].gap_m, 0.0) - overlap_allowance_m_;
    }
  }
}

bool ContactStates::hold(std::size_t i) {
  if (modes_[i] == ContactMode::held) return false;
  modes_[i] = ContactMode::held;
  held_.push_back(i);
  return true;
}

bool ContactStates::release_hold(std::size_t i, double reopen_m, double gap_m) {
  if (modes_[i] != ContactMode::held) return false;
  mask(i, reopen_m, gap_m);
  return true;
}

void ContactStates::start_acting(std::size_t i) {
  modes_[i] = ContactMode::compliant;
  acting_.push_back(i);
}

void ContactStates::stop_acting(std::size_t i) {
  leave_lists(i);
  modes_[i] = ContactMode::released;
}

CornerCover::CornerCover(const std::vector<contact::Candidate>& candidates, contact::CornerLinks links,
                         double touch_band_m)
    : candidates_(candidates),
      links_(std::move(links)),
      touch_band_m_(touch_band_m),
      covered_(candidates.size(), false),
      live_(candidates.size(), true),
      ever_live_(candidates.size(), false) {
  for (const contact::Candidate& c : candidates) corner_count_ += c.corner;
}

void CornerCover::cover_group(long group) {
  if (group == contact::kNoCandidate) return;
  for (std::size_t j : links_.members[static_cast<std::size_t>(group)]) covered_[j] = true;
}

void CornerCover::update(const std::vector<contact::GapState>& gaps, const ContactStates& states) {
  std::fill(covered_.begin(), covered_.end(), false);
  for (std::size_t i = 0; i < candidates_.size(); ++i) {
    if (states.open(i)) continue;
    cover_group(static_cast<long>(links_.group[i]));
    // A corner of the struck slab at this contact's point: the same contact seen from the corner.
    const double reach_m = 2.0 * (std::max(-gaps[i].gap_m, 0.0) + touch_band_m_);
    for (long group : links_.edge_end_group[i]) {
      if (group == contact::kNoCandidate) continue;
      const std::size_t first = links_.members[static_cast<std::size_t>(group)].front();
      if ((gaps[first].contact_point - gaps[i].contact_point).norm() <= reach_m) cover_group(group);
    }
  }
  for (std::size_t i = 0; i < candidates_.size(); ++i) {
    if (!states.open(i)) covered_[i] = false;  // a contact in progress is its own
    // A corner candidate can close only from in front of its edge, over it.
    const bool can_close = gaps[i].on_segment() && gaps[i].gap_m >= -touch_band_m_;
    live_[i] = states.open(i) && !covered_[i] && (!candidates_[i].corner || can_close);
    if (live_[i] && candidates_[i].corner) ever_live_[i] = true;
  }
}

WitnessLayout::Crossed WitnessLayout::crossed(const std::vector<int>& flags) const {
  Crossed crossed;
  for (std::size_t i = 0; i < count_; ++i) {
    if (flagged(flags, Witness::gap, i)) crossed.gap.push_back(i);
    if (flagged(flags, Witness::force, i)) crossed.force.push_back(i);
    if (flagged(flags, Witness::edge, i)) crossed.edge.push_back(i);
    if (has_struck_columns() && flagged(flags, Witness::column, i)) crossed.column.push_back(i);
  }
  return crossed;  // the springs' witnesses: YieldStates::switch_branches finds those that crossed
}

}  // namespace pounding::solvers
