#include "pounding/solvers/event_step_bound.hpp"

#include <algorithm>
#include <cmath>

#include "pounding/solvers/event_options.hpp"

namespace pounding::solvers {

EventStepBound::EventStepBound(const dynamics::CoupledSystem& system, const EventOptions& options)
    : system_(system), options_(options) {
  if (options.max_step_s == 0.0) {
    mode_bound_.emplace(system, options.overlap_allowance_m, options.steps_per_period, options.modes_cutoff_hz);
  }
}

double EventStepBound::enable_clearance() {
  clearance_.emplace(system_);
  watched_.resize(system_.candidates().size());
  return clearance_->shortest_damped_period_s();
}

double EventStepBound::max_step_s(double t, const Eigen::VectorXd& y, const std::vector<contact::GapState>& gaps,
                                  const ContactStates& states, const CornerCover& cover,
                                  const GapAcceleration& gap_acceleration) {
  double bound = mode_bound_ ? mode_bound_->max_step_s(y) : options_.max_step_s;
  open_until_s_ = -std::numeric_limits<double>::infinity();
  if (clearance_ && states.free_motion()) bound = std::max(bound, clear_step_s(t, y, states, cover));
  for (std::size_t i = 0; i < states.size(); ++i) {
    if (!states.is(i, ContactMode::masked)) continue;
    const contact::GapState& s = gaps[i];
    const double height = s.gap_m - states.mask_floor_m(i);
    if (!s.on_segment() || !(height > 0.0) || std::isinf(height)) continue;
    const double accel = gap_acceleration(i);
    if (accel >= 0.0) continue;
    const double rate = s.gap_rate_mps;
    const double reclose = (rate + std::sqrt(rate * rate - 2.0 * height * accel)) / (-accel);
    bound = std::min(bound, reclose / 4.0);
  }
  return bound;
}

double EventStepBound::clear_step_s(double t, const Eigen::VectorXd& y, const ContactStates& states,
                                    const CornerCover& cover) {
  // Steps end at record samples, so the window ends at the next one and each component is one
  // straight piece over it: its largest |a_c| is at an end.
  const excitation::GroundMotion& motion = system_.ground_motion();
  const std::optional<double> next = motion.next_sample_after(t);
  if (!next) return 0.0;
  const double horizon_s = *next - t;
  Eigen::Vector2d peak_accel_mps2 = Eigen::Vector2d::Zero();
  for (int c = 0; c < motion.component_count(); ++c) {
    peak_accel_mps2[c] = std::max(std::abs(motion.accel_at(t, c)), std::abs(motion.accel_at(*next, c)));
  }
  // A dormant corner candidate is left out: its vertex reaches its (side) edge only across the
  // line of the other slab's facing edge, whose gap the bound holds open (docs/model.md §5a).
  for (std::size_t i = 0; i < states.size(); ++i) {
    watched_[i] = states.open(i) && (!system_.candidates()[i].corner || cover.live(i));
  }
  // Above contact_tolerance_m throughout, a gap can neither close nor touch inside the step.
  const double open_s = clearance_->open_time_s(y, watched_, options_.contact_tolerance_m, horizon_s, peak_accel_mps2);
  open_until_s_ = t + open_s;
  // Open up to the stop time: a bound past it lets the stop time end the step (t + horizon may
  // round below it).
  return open_s >= horizon_s ? 2.0 * horizon_s : open_s;
}

}  // namespace pounding::solvers
