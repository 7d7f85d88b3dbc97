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

void ContactStates::rearm(const std::vector<contact::GapState>& gaps) {
  for (std::size_t i = 0; i < modes_.size(); ++i) {
    if (modes_[i] == ContactMode::masked && gaps[i].gap_m > reopen_at_m_[i]) modes_[i] = ContactMode::armed;
  }
  watch_arrivals(gaps);
}

void ContactStates::watch_arrivals(const std::vector<contact::GapState>& gaps) {
  // Masked as it passed beside the edge, the vertex has come onto it: from here on its gap is a
  // depth into the other slab, watched by a root as a contact's is.
  for (std::size_t i = 0; i < modes_.size(); ++i) {
    if (modes_[i] == ContactMode::masked && !has_floor(i) && gaps[i].on_segment()) {
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

WitnessLayout::Crossed WitnessLayout::crossed(const std::vector<int>& flags) const {
  Crossed crossed;
  for (std::size_t i = 0; i < count_; ++i) {
    if (flagged(flags, Witness::gap, i)) crossed.gap.push_back(i);
    if (flagged(flags, Witness::force, i)) crossed.force.push_back(i);
    if (flagged(flags, Witness::edge, i)) crossed.edge.push_back(i);
  }
  for (std::size_t j = 0; j < springs_; ++j)
    crossed.springs = crossed.springs || flags[static_cast<std::size_t>(at_spring(j))] != 0;
  return crossed;
}

}  // namespace pounding::solvers
