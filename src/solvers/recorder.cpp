#include "pounding/solvers/recorder.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

#include "pounding/solvers/floor_impacts.hpp"
#include "pounding/solvers/history_schema.hpp"
#include "pounding/solvers/root_finding.hpp"

namespace pounding::solvers {

RecordedDynamics free_dynamics(const dynamics::CoupledSystem& system) {
  return {.derivative = [&system](double t, const dynamics::VectorXd& y,
                                  Eigen::Ref<dynamics::VectorXd> y_dot) { system.rhs(t, y, y_dot); },
          .contact_forces = {},
          .free_motion = {}};
}

namespace {

std::vector<contact::Level> chosen_levels(const dynamics::CoupledSystem& system, const std::vector<int>& levels) {
  if (levels.empty()) return system.levels();
  std::vector<contact::Level> chosen;
  for (int level : levels) chosen.push_back(system.levels().at(static_cast<std::size_t>(level - 1)));
  return chosen;
}

/// Every slab `slabs` selects, {building, floor}, in column order.
std::vector<std::array<int, 2>> chosen_slabs(const dynamics::CoupledSystem& system, const HistorySlabs& slabs) {
  std::vector<std::array<int, 2>> chosen;
  const auto add = [&](const std::array<int, 2>& slab) {
    if (std::find(chosen.begin(), chosen.end(), slab) == chosen.end()) chosen.push_back(slab);
  };
  for (const contact::Level& level : chosen_levels(system, slabs.levels)) {
    for (int side = 0; side < 2; ++side) add({level.pair[side], level.floors[side]});  // a row's slab once
  }
  for (const std::array<int, 2>& slab : slabs.other_floors) add(slab);
  return chosen;
}

}  // namespace

std::vector<std::string> history_columns(const dynamics::CoupledSystem& system, const HistorySlabs& slabs,
                                         bool member_forces) {
  std::vector<std::string> columns{"t_s"};
  std::vector<std::vector<int>> numbers;
  for (int b = 0; b < system.building_count(); ++b) {
    std::vector<model::Point2> vertices = contact_vertices(system.candidates(), b);
    numbers.push_back(outline_numbers(system.building(b).definition.slab, vertices));
  }
  for (const std::array<int, 2>& slab : chosen_slabs(system, slabs)) {
    const int b = slab[0];  // not a structured binding: the lambda below captures it (clang < 16 cannot)
    const std::string prefix = fmt::format("B{}_f{}_", b + 1, slab[1]);
    const std::size_t corners = system.building(b).definition.slab.size();
    for_each_slab_column(numbers[b].size(), corners, [&](const HistoryQuantity& quantity, std::size_t k) {
      const bool vertex = quantity.per == HistoryQuantity::Per::contact_vertex;
      columns.push_back(prefix + quantity.column(vertex ? numbers[b][k] : static_cast<int>(k) + 1));
    });
  }
  if (member_forces) {
    for (std::string& name : MemberForces(system).column_names()) columns.push_back(std::move(name));
  }
  return columns;
}

Recorder::Recorder(const dynamics::CoupledSystem& system, RecordedDynamics dynamics, const HistorySlabs& slabs,
                   double history_interval_s, const OutputSelection& outputs, RunSink* sink)
    : system_(system),
      kinematics_(system, std::move(dynamics)),
      outputs_(outputs),
      peaks_(kinematics_, outputs),
      history_slabs_(chosen_slabs(system, slabs)),
      interval_s_(history_interval_s),
      energy_(system),
      sink_(sink) {
  next_sample_s_ = system.ground_motion().start_s();
  if (outputs_.member_forces) {
    member_forces_.emplace(system);
    member_peaks_ = member_forces_->quantities();
    member_values_.resize(static_cast<Eigen::Index>(member_peaks_.size()));
  }
  if (outputs_.history) {
    for (const contact::Level& level : chosen_levels(system, slabs.levels)) history_.levels.push_back(level.index);
    history_.interval_s = interval_s_;
    history_.columns = history_columns(system, slabs, outputs_.member_forces);
    row_.resize(static_cast<Eigen::Index>(history_.columns.size()) - 1);
  }
}

void Recorder::append_row(const Instant& at) {
  const double t = *at.t_s;
  const dynamics::VectorXd& y = at.y;
  Eigen::Index c = 0;
  for (const auto& [b, floor] : history_slabs_) {
    const int i = system_.floor_index(b, floor);
    const SlabSample slab{.q = &y[i],
                          .accel = &at.accel[i],
                          .drift = &at.drifts.value[static_cast<Eigen::Index>(kinematics_.drift_index(b, floor, 0))],
                          .contact_vertices = kinematics_.contact_vertices(b),
                          .centre = system_.building(b).definition.centre_of_mass};
    for_each_slab_column(kinematics_.contact_vertices(b).size(), system_.building(b).definition.slab.size(),
                         [&](const HistoryQuantity& quantity, std::size_t k) { row_[c++] = quantity.value(slab, k); });
  }
  if (member_forces_) row_.tail(member_values_.size()) = member_values_;
  std::vector<ContactForceSample> forces;
  if (kinematics_.dynamics().contact_forces) {
    for (const ContactForce& f : kinematics_.dynamics().contact_forces(t, y)) {
      const contact::GapState gap = system_.gap(y, f.candidate);
      ContactForceSample& sample =
          forces.emplace_back(ContactForceSample{contact_identity(system_.candidates()[f.candidate], f.candidate)});
      sample.t_s = t;
      sample.gap_m = gap.gap_m;
      sample.gap_rate_mps = gap.gap_rate_mps;
      sample.force_kN = f.force_kN;
    }
  }
  if (sink_ != nullptr) {
    sink_->history_row(t, row_);
    for (const ContactForceSample& f : forces) sink_->contact_force(f);
  } else {
    history_.time_s.push_back(t);
    history_.rows.push_back(row_);
    history_.contact_forces.insert(history_.contact_forces.end(), forces.begin(), forces.end());
  }
  last_row_t_s_ = t;
}

void Recorder::sample(double t, const dynamics::VectorXd& y) {
  if (!started_ && sink_ != nullptr) {
    // Columns at the first sample, not at construction: by then the run has passed its checks.
    sink_->history_columns(history_.columns);
  }
  started_ = true;
  const bool row = outputs_.history && last_row_t_s_ != t;
  kinematics_.measure(t, y, row || outputs_.acceleration_peaks, row || outputs_.drift_peaks, last_);
  peaks_.update(last_);
  measure_member_forces(t, y);
  if (row) append_row(last_);
}

void Recorder::measure_member_forces(double t, const dynamics::VectorXd& y) {
  if (!member_forces_) return;
  member_forces_->measure(y, spring_states_, member_values_);
  for (std::size_t i = 0; i < member_peaks_.size(); ++i)
    member_peaks_[i].peak.update(member_values_[static_cast<Eigen::Index>(i)], t);
}

void Recorder::advance(double t_a, double t_b, const dynamics::VectorXd& y_b,
                       const std::function<dynamics::VectorXd(double)>& at,
                       const std::function<double(double, const dynamics::VectorXd&)>& constraint_power,
                       const std::optional<StretchEnergy>& closed_form, const ComponentsAt& components_at) {
  if (!(t_b > t_a)) return;
  if (sink_ != nullptr) sink_->progress(t_b, system_.ground_motion().end_s(), impacts_streamed_);
  energy_.add_stretch(t_a, t_b, at, constraint_power, closed_form);
  // The stretch starts where the last instant recorded left off: the previous step's end or an
  // event's state after the event, with the dynamics that go on from there. Swapped out before the
  // samples inside the stretch take the place of the latest instant.
  const bool peaks = outputs_.any_peaks();
  if (peaks) {
    std::swap(start_, last_);
    if (start_.t_s != t_a) kinematics_.measure(t_a, at(t_a), outputs_.acceleration_peaks, outputs_.drift_peaks, start_);
  }
  // The peaks see the sample instants whether or not rows are written, so they do not depend on
  // the history (on HHT's Hermite interpolant a sample can beat the located turning points).
  if (outputs_.history || peaks) {
    while (next_sample_s_ <= t_b) {
      if (next_sample_s_ > t_a) sample(next_sample_s_, at(next_sample_s_));
      next_sample_s_ =
          system_.ground_motion().start_s() +
          interval_s_ * std::round((next_sample_s_ - system_.ground_motion().start_s()) / interval_s_ + 1.0);
    }
  }
  if (!peaks) {
    measure_member_forces(t_b, y_b);
    return;
  }
  // Turning points are found from the rates at the piece ends, so a piece must be too short for
  // a rate to change sign twice unseen (peak_step_s_).
  const double length_s = t_b - t_a;
  const int pieces = peak_step_s_ > 0.0 ? std::max(1, static_cast<int>(std::ceil(length_s / peak_step_s_))) : 1;
  for (int k = 1; k <= pieces; ++k) {
    const double s_a = t_a + length_s * (k - 1) / pieces;
    const double s_b = k == pieces ? t_b : t_a + length_s * k / pieces;
    if (k > 1) std::swap(start_, last_);
    kinematics_.measure(s_b, k == pieces ? y_b : at(s_b), outputs_.acceleration_peaks, outputs_.drift_peaks, last_);
    peaks_.locate(s_a, s_b, start_, last_, at, components_at);
    peaks_.update(last_);
    measure_member_forces(*last_.t_s, last_.y);
  }
}

void Recorder::stream_new_impacts(const std::vector<ImpactRecord>& impacts) {
  if (sink_ == nullptr) return;
  for (; impacts_streamed_ < impacts.size(); ++impacts_streamed_) sink_->impact(impacts[impacts_streamed_]);
}

void Recorder::finish(const dynamics::VectorXd& final_state, RunResult& result, const dynamics::SpringStates* springs) {
  stream_new_impacts(result.impacts);
  result.energy = energy_.close(final_state, springs);
  result.outputs = outputs_;
  result.peaks = peaks_.take();
  if (outputs_.drift_peaks) record_end_drifts(final_state, result.peaks);
  result.history = std::move(history_);
  result.member_forces = std::move(member_peaks_);
}

void Recorder::record_end_drifts(const dynamics::VectorXd& final_state, std::vector<BuildingPeaks>& peaks) const {
  Drifts end;
  kinematics_.storey_drifts(final_state, end);
  for (std::size_t b = 0; b < peaks.size(); ++b) {
    const int building = static_cast<int>(b);
    const std::size_t slots = kinematics_.drift_slots(building);
    for (FloorPeaks& floor : peaks[b].floors) {
      const std::size_t first = kinematics_.drift_index(building, floor.floor, 0);
      floor.end_drift.assign(end.value.data() + first, end.value.data() + first + slots);
      floor.end_drift_rate_per_s.assign(end.rate.data() + first, end.rate.data() + first + slots);
    }
  }
}

}  // namespace pounding::solvers
