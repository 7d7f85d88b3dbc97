#include "pounding/solvers/yield_states.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace pounding::solvers {

using dynamics::SpringBranch;

YieldStates::YieldStates(const dynamics::YieldingSprings& springs, double max_switches_per_s,
                         bool locate_shear_failures)
    : springs_(springs),
      states_(springs.size()),
      results_(springs.size()),
      phase_start_slip_m_(springs.size(), 0.0),
      max_switches_per_s_(max_switches_per_s),
      locate_shear_failures_(locate_shear_failures),
      recent_switches_s_(springs.size()) {
  laws_.resize(springs.size());
  for (std::size_t j = 0; j < springs.size(); ++j) {
    if (!springs[j].imk) continue;
    laws_[j].emplace(*springs[j].imk);
    take_line(j);
  }
}

void YieldStates::take_line(std::size_t j) {
  const dynamics::ImkPeakOriented& law = *laws_[j];
  const auto moves = [&] {
    return states_[j].branch == SpringBranch::failed ||
           (states_[j].branch == SpringBranch::line &&
            states_[j].line.slope_kN_per_m != springs_[j].stiffness_kN_per_m);
  };
  if (moves()) --yielding_;
  states_[j] = law.failed() ? dynamics::SpringState{.branch = SpringBranch::failed}
                            : dynamics::SpringState{.branch = SpringBranch::line, .line = law.line()};
  if (moves()) ++yielding_;
}

bool YieldStates::advance_degrading(std::size_t j, double t, const Eigen::VectorXd& y, double rate_mps,
                                    double accel_mps2) {
  const double heading = rate_mps != 0.0 ? rate_mps : accel_mps2;
  if (heading == 0.0) return false;
  dynamics::ImkPeakOriented& law = *laws_[j];
  const int before = law.branch();
  if (!law.advance(springs_.drift(y.head(springs_.dof()), j), heading > 0.0 ? 1 : -1)) return false;
  SpringResult& result = results_[j];
  const auto on_backbone = [](int branch) { return branch % 10 >= 5; };  // post-yield, post-capping, residual
  if (!on_backbone(before) && on_backbone(law.branch())) {               // a yielding phase begins
    if (result.yield_count == 0) result.first_yield_t_s = t;
    ++result.yield_count;
  }
  if (law.failed()) result.degrading_failure_t_s = t;
  take_line(j);
  return true;
}

void YieldStates::count_switch(std::size_t j, double t) {
  std::deque<double>& recent = recent_switches_s_[j];
  recent.push_back(t);
  while (recent.front() < t - 1.0) recent.pop_front();
  if (!chattering_ && static_cast<double>(recent.size()) > max_switches_per_s_) chattering_ = j;
}

double YieldStates::witness(const Eigen::Ref<const Eigen::VectorXd>& y, std::size_t j) const {
  const double own = branch_witness(y, j);
  return watches_capacity(j) ? std::min(own, capacity_witness(y, j)) : own;
}

bool YieldStates::watches_capacity(std::size_t j) const {
  return locate_shear_failures_ && springs_[j].shear_capacity_kN > 0.0 && std::isnan(results_[j].shear_failure_t_s);
}

double YieldStates::capacity_witness(const Eigen::Ref<const Eigen::VectorXd>& y, std::size_t j) const {
  // In metres, as the elastic branch's witness: on a branch the force is linear in the drift.
  return (springs_[j].shear_capacity_kN - std::abs(springs_.force_kN(y, states_, j))) / springs_[j].stiffness_kN_per_m;
}

double YieldStates::branch_witness(const Eigen::Ref<const Eigen::VectorXd>& y, std::size_t j) const {
  if (!springs_[j].bouc_wen) return springs_.witness(y, states_, j);
  // A smooth spring has no branches: its one event is its first yield, |d| reaching d_y.
  if (results_[j].yield_count > 0) return 1.0;
  return springs_[j].yield_drift_m - std::abs(springs_.drift(y.head(springs_.dof()), j));
}

int YieldStates::switch_branches(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& y_dot) {
  const int n = springs_.dof();
  int switched = 0;
  for (std::size_t j = 0; j < springs_.size(); ++j) {
    if (watches_capacity(j) && capacity_witness(y, j) <= 0.0) {
      if (springs_[j].loses_stiffness) {
        lose_stiffness(j, t, y);
        ++switched;
        continue;
      }
      results_[j].shear_failure_t_s = t;
    }
    if (states_[j].branch == SpringBranch::failed || branch_witness(y, j) > 0.0) continue;
    dynamics::SpringState& state = states_[j];
    SpringResult& result = results_[j];
    const double rate_mps = springs_.drift(y.segment(n, n), j), accel_mps2 = springs_.drift(y_dot.segment(n, n), j);
    if (laws_[j]) {
      if (!advance_degrading(j, t, y, rate_mps, accel_mps2)) continue;
      count_switch(j, t);
      ++switched;
      continue;
    }
    const double offset_m = springs_.drift(y.head(n), j) - (springs_[j].bouc_wen ? 0.0 : state.slip_m);
    if (springs_[j].bouc_wen || state.branch == SpringBranch::elastic) {
      const double outwards = offset_m >= 0.0 ? 1.0 : -1.0;
      const bool leaving = outwards * rate_mps > 0.0 || (outwards * rate_mps == 0.0 && outwards * accel_mps2 > 0.0);
      if (!leaving) continue;  // on the yield drift but turning back: stays elastic
      if (result.yield_count == 0) result.first_yield_t_s = t;
      ++result.yield_count;
      if (!springs_[j].bouc_wen) {
        state.branch = outwards > 0.0 ? SpringBranch::yielding_up : SpringBranch::yielding_down;
        phase_start_slip_m_[j] = state.slip_m;
        ++yielding_;
      }
    } else {
      const double sign = state.branch == SpringBranch::yielding_up ? 1.0 : -1.0;
      if (sign * rate_mps == 0.0 && sign * accel_mps2 > 0.0) continue;  // the rate touches zero and grows again
      end_yielding(j, springs_.slip(y, states_, j));
    }
    count_switch(j, t);
    ++switched;
  }
  return switched;
}

void YieldStates::end_yielding(std::size_t j, double slip_m) {
  const dynamics::YieldingSpring& spring = springs_[j];
  results_[j].hysteretic_kJ +=
      spring.plastic_stiffness() * spring.yield_drift_m * std::abs(slip_m - phase_start_slip_m_[j]);
  states_[j] = {.branch = SpringBranch::elastic, .slip_m = slip_m};
  --yielding_;
}

void YieldStates::lose_stiffness(std::size_t j, double t, const Eigen::VectorXd& y) {
  results_[j].shear_failure_t_s = t;
  fail(j, y);
  count_switch(j, t);
}

void YieldStates::fail(std::size_t j, const Eigen::VectorXd& y) {
  const dynamics::YieldingSpring& spring = springs_[j];
  // Its force at the failure (V_c) is its peak: observe() sees it only after, at zero.
  results_[j].peak_force_kN = std::max(results_[j].peak_force_kN, std::abs(springs_.force_kN(y, states_, j)));
  if (laws_[j]) {  // a degrading spring: its law fails (all its work is dissipated)
    laws_[j]->fail_at(springs_.drift(y.head(springs_.dof()), j));
    take_line(j);
    return;
  }
  if (states_[j].branch != SpringBranch::elastic) end_yielding(j, springs_.slip(y, states_, j));
  const double d = springs_.drift(y.head(springs_.dof()), j), elastic_part = d - states_[j].slip_m;
  results_[j].hysteretic_kJ += 0.5 * spring.hardening_ratio * spring.stiffness_kN_per_m * d * d +
                               0.5 * spring.plastic_stiffness() * elastic_part * elastic_part;
  states_[j] = {.branch = SpringBranch::failed, .slip_m = 0.0};
  ++failed_;
}

std::optional<std::size_t> YieldStates::observe(const Eigen::VectorXd& y) {
  std::optional<std::size_t> collapsed;
  for (std::size_t j = 0; j < springs_.size(); ++j) {
    const double signed_drift_m = springs_.drift(y.head(springs_.dof()), j), drift_m = std::abs(signed_drift_m);
    results_[j].peak_drift_m = std::max(results_[j].peak_drift_m, drift_m);
    const double force_kN = springs_[j].force_kN(signed_drift_m, springs_.slip(y, states_, j));
    results_[j].peak_force_kN = std::max(results_[j].peak_force_kN, std::abs(force_kN));
    if (!collapsed && drift_m > kCollapseDriftRatio * springs_[j].storey_height_m) collapsed = j;
  }
  return collapsed;
}

std::optional<YieldingStop> YieldStates::stop(double t, const Eigen::VectorXd& y,
                                              const std::vector<std::string>& building_names) {
  auto where = [&](std::size_t j) {
    const dynamics::YieldingSpring& s = springs_[j];
    return fmt::format("{} storey {}, {} {}", building_names.at(static_cast<std::size_t>(s.building)), s.storey,
                       s.column, s.direction == 0 ? "x" : "y");
  };
  if (const std::optional<std::size_t> j = observe(y)) {
    return YieldingStop{RunStatus::collapse,
                        fmt::format("{}: drift beyond {:g} % of the {:g} m storey at t = {} s (the frame has failed; "
                                    "the model's small rotations no longer hold)",
                                    where(*j), 100.0 * kCollapseDriftRatio, springs_[*j].storey_height_m, t)};
  }
  if (chattering_) {
    return YieldingStop{
        RunStatus::event_limit,
        fmt::format("{}: more than {} yields and unloadings within one simulated second before t = {} s",
                    where(*chattering_), max_switches_per_s_, t)};
  }
  return std::nullopt;
}

std::vector<SpringResult> YieldStates::finish(const Eigen::VectorXd& y, const std::vector<double>& smooth_dissipated_kJ,
                                              double& hysteretic_kJ) {
  (void)observe(y);  // the run has ended: a collapse at its last state is the caller's to report
  hysteretic_kJ = 0.0;
  for (std::size_t j = 0; j < springs_.size(); ++j) {
    if (springs_[j].bouc_wen) {
      results_[j].hysteretic_kJ = smooth_dissipated_kJ.at(j);
    } else if (laws_[j]) {
      results_[j].hysteretic_kJ = laws_[j]->dissipated_kJ(springs_.drift(y.head(springs_.dof()), j));
    } else if (states_[j].branch == SpringBranch::yielding_up || states_[j].branch == SpringBranch::yielding_down) {
      end_yielding(j, springs_.slip(y, states_, j));
    }
    results_[j].final_drift_m = springs_.drift(y.head(springs_.dof()), j);
    results_[j].final_slip_m = springs_.slip(y, states_, j);
    hysteretic_kJ += results_[j].hysteretic_kJ;
  }
  return std::move(results_);
}

}  // namespace pounding::solvers
