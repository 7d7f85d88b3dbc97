#include "pounding/solvers/yield_states.hpp"

#include <cmath>

namespace pounding::solvers {

using dynamics::SpringBranch;

YieldStates::YieldStates(const dynamics::YieldingSprings& springs, double max_switches_per_s)
    : springs_(springs),
      states_(springs.size()),
      results_(springs.size()),
      phase_start_slip_m_(springs.size(), 0.0),
      max_switches_per_s_(max_switches_per_s),
      recent_switches_s_(springs.size()) {}

void YieldStates::count_switch(std::size_t j, double t) {
  std::deque<double>& recent = recent_switches_s_[j];
  recent.push_back(t);
  while (recent.front() < t - 1.0) recent.pop_front();
  if (!chattering_ && static_cast<double>(recent.size()) > max_switches_per_s_) chattering_ = j;
}

int YieldStates::switch_branches(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& y_dot) {
  const Eigen::Index n = y.size() / 2;
  int switched = 0;
  for (std::size_t j = 0; j < springs_.size(); ++j) {
    if (witness(y, j) > 0.0) continue;
    dynamics::SpringState& state = states_[j];
    const double rate_mps = springs_.drift(y.tail(n), j), accel_mps2 = springs_.drift(y_dot.tail(n), j);
    if (state.branch == SpringBranch::elastic) {
      const double outwards = springs_.drift(y.head(n), j) - state.slip_m >= 0.0 ? 1.0 : -1.0;
      const bool leaving = outwards * rate_mps > 0.0 || (outwards * rate_mps == 0.0 && outwards * accel_mps2 > 0.0);
      if (!leaving) continue;  // on the yield drift but turning back: stays elastic
      state.branch = outwards > 0.0 ? SpringBranch::yielding_up : SpringBranch::yielding_down;
      phase_start_slip_m_[j] = state.slip_m;
      SpringResult& result = results_[j];
      if (result.yield_count == 0) result.first_yield_t_s = t;
      ++result.yield_count;
      ++yielding_;
    } else {
      const double sign = state.branch == SpringBranch::yielding_up ? 1.0 : -1.0;
      if (sign * rate_mps == 0.0 && sign * accel_mps2 > 0.0) continue;  // the rate touches zero and grows again
      end_yielding(j, springs_.slip(y.head(n), states_, j));
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

std::optional<std::size_t> YieldStates::observe(const Eigen::VectorXd& y) {
  const Eigen::Index n = y.size() / 2;
  std::optional<std::size_t> collapsed;
  for (std::size_t j = 0; j < springs_.size(); ++j) {
    const double drift_m = std::abs(springs_.drift(y.head(n), j));
    results_[j].peak_drift_m = std::max(results_[j].peak_drift_m, drift_m);
    if (!collapsed && drift_m > kCollapseDriftRatio * springs_[j].storey_height_m) collapsed = j;
  }
  return collapsed;
}

std::vector<SpringResult> YieldStates::finish(const Eigen::VectorXd& y, double& hysteretic_kJ) {
  const Eigen::Index n = y.size() / 2;
  (void)observe(y);  // the run has ended: a collapse at its last state is the caller's to report
  hysteretic_kJ = 0.0;
  for (std::size_t j = 0; j < springs_.size(); ++j) {
    if (states_[j].branch != SpringBranch::elastic) end_yielding(j, springs_.slip(y.head(n), states_, j));
    results_[j].final_drift_m = springs_.drift(y.head(n), j);
    results_[j].final_slip_m = states_[j].slip_m;
    hysteretic_kJ += results_[j].hysteretic_kJ;
  }
  return std::move(results_);
}

}  // namespace pounding::solvers
