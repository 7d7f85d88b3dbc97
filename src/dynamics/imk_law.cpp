#include "pounding/dynamics/imk_law.hpp"

#include <algorithm>
#include <cmath>

namespace pounding::dynamics {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// The longest chain at one drift: a reversal, an unloading of zero length, a new excursion and the
// reload on through 4 → 5 → 6 → 7 (seven changes).
constexpr int kMaxChangesAtOneDrift = 16;

int side_of(int branch) { return branch >= 12 ? -1 : 1; }

}  // namespace

ImkPeakOriented::ImkPeakOriented(const ImkParameters& parameters)
    : parameters_(parameters),
      unloading_stiffness_(parameters.stiffness_kN_per_m),
      reload_slope_(parameters.stiffness_kN_per_m) {
  const double k = parameters.stiffness_kN_per_m;
  for (int sign : {1, -1}) {
    const ImkSide& p = sign > 0 ? parameters.positive : parameters.negative;
    const double yield_drift = p.yield_force_kN / k, cap_force = p.cap_ratio * p.yield_force_kN;
    const double post_cap_slope = -cap_force / p.post_cap_drift_m, residual = p.residual_ratio * p.yield_force_kN;
    Backbone& s = side(sign);
    s.yield_drift_m = sign * yield_drift;
    s.yield_force_kN = sign * p.yield_force_kN;
    s.cap_drift_m = sign * (yield_drift + p.plastic_drift_m);
    s.cap_force_kN = sign * cap_force;
    s.plastic_slope = (cap_force - p.yield_force_kN) / p.plastic_drift_m;
    s.post_cap_slope = post_cap_slope;
    s.residual_force_kN = sign * residual;
    s.residual_drift_m = (s.residual_force_kN - s.cap_force_kN) / post_cap_slope + s.cap_drift_m;
    s.local_drift_m = s.global_drift_m = s.yield_drift_m;
    s.local_force_kN = s.global_force_kN = s.yield_force_kN;
    s.ultimate_drift_m = sign * p.ultimate_drift_m;
    s.rate = p.deterioration_rate;
  }
  enter(0, 0.0);
}

double ImkPeakOriented::backbone_force(const Backbone& s, double drift_m, double stiffness) {
  const double sign = s.yield_force_kN > 0.0 ? 1.0 : -1.0;
  double force = 0.0;
  if (sign * drift_m < sign * s.yield_drift_m) {
    force = stiffness * drift_m;
  } else if (sign * drift_m < sign * s.cap_drift_m) {
    force = s.yield_force_kN + s.plastic_slope * (drift_m - s.yield_drift_m);
  } else {
    force = s.cap_force_kN + s.post_cap_slope * (drift_m - s.cap_drift_m);
  }
  return sign * force < sign * s.residual_force_kN ? s.residual_force_kN : force;
}

void ImkPeakOriented::enter(int branch, double drift_m) {
  branch_ = branch;
  entry_drift_m_ = drift_m;
  const double k = parameters_.stiffness_kN_per_m;
  LineBranch line;
  const Backbone& s = side_of(branch) > 0 ? positive_ : negative_;
  switch (branch % 10) {
    case 0:  // elastic, about the origin
      line.slope_kN_per_m = k;
      line.lower_m = negative_.yield_drift_m;
      line.upper_m = positive_.yield_drift_m;
      break;
    case 1: {  // unloading from the reversal (line_'s anchor, set by reverse())
      line.force_kN = line_.force_kN;
      line.drift_m = line_.drift_m;
      line.slope_kN_per_m = unloading_stiffness_;
      const double zero_force_m = line.drift_m - line.force_kN / unloading_stiffness_;
      line.lower_m = line.force_kN > 0.0 ? zero_force_m : line.drift_m;
      line.upper_m = line.force_kN > 0.0 ? line.drift_m : zero_force_m;
      break;
    }
    case 2: line = {.force_kN = pinch_force_kN_, .drift_m = pinch_drift_m_, .slope_kN_per_m = reload_slope_}; break;
    case 3: line = {.force_kN = s.local_force_kN, .drift_m = s.local_drift_m, .slope_kN_per_m = reload_slope_}; break;
    case 4: line = {.force_kN = s.global_force_kN, .drift_m = s.global_drift_m, .slope_kN_per_m = reload_slope_}; break;
    case 5: line = {.force_kN = s.cap_force_kN, .drift_m = s.cap_drift_m, .slope_kN_per_m = s.plastic_slope}; break;
    case 6: line = {.force_kN = s.cap_force_kN, .drift_m = s.cap_drift_m, .slope_kN_per_m = s.post_cap_slope}; break;
    case 7: line = {.force_kN = s.residual_force_kN, .drift_m = drift_m, .slope_kN_per_m = 0.0}; break;
  }
  if (branch % 10 >= 2) {  // a loading branch: it ends at its target ahead, or where the motion turns
    const double target_m = branch % 10 == 2   ? pinch_drift_m_
                            : branch % 10 == 3 ? s.local_drift_m
                            : branch % 10 == 4 ? s.global_drift_m
                            : branch % 10 == 5 ? s.cap_drift_m
                            : branch % 10 == 6 ? s.residual_drift_m
                                               : side_of(branch) * kInfinity;
    line.reversal_sign = side_of(branch);
    line.lower_m = side_of(branch) > 0 ? -kInfinity : target_m;
    line.upper_m = side_of(branch) > 0 ? target_m : kInfinity;
  }
  line.unloading_stiffness_kN_per_m = unloading_stiffness_;
  line.upper_m = std::min(line.upper_m, positive_.ultimate_drift_m);
  line.lower_m = std::max(line.lower_m, negative_.ultimate_drift_m);
  line_ = line;
}

void ImkPeakOriented::close_segment(double drift_m) {
  work_kJ_ = work_kJ(drift_m);
  entry_drift_m_ = drift_m;
}

double ImkPeakOriented::work_kJ(double drift_m) const {
  if (failed_) return work_kJ_;
  return work_kJ_ + 0.5 * (line_.force_at(entry_drift_m_) + line_.force_at(drift_m)) * (drift_m - entry_drift_m_);
}

double ImkPeakOriented::dissipated_kJ(double drift_m) const {
  if (failed_) return work_kJ_;
  if (branch_ == 0) return 0.0;  // never yielded: all its work is stored (exactly, not to round-off)
  const double force = line_.force_at(drift_m);
  return work_kJ(drift_m) - 0.5 * force * force / unloading_stiffness_;
}

double ImkPeakOriented::beta(ImkMode mode, double numerator_kJ, double spent_kJ) {
  const double lamda_m = parameters_.lamda_m[mode];
  if (lamda_m == 0.0) return 0.0;  // the mode is off
  const double left_kJ = lamda_m * parameters_.positive.yield_force_kN - spent_kJ;
  if (left_kJ <= 0.0) {  // the energy the mode allows is spent
    failing_ = true;
    return 1.0;
  }
  const double b = std::pow(std::max(0.0, numerator_kJ / left_kJ), parameters_.exponent[mode]);
  if (b >= 1.0) failing_ = true;  // (OpenSees: > 1) at 1 a stiffness would fall to zero
  return std::min(b, 1.0);
}

void ImkPeakOriented::fail(double drift_m) {
  close_segment(drift_m);
  failed_ = true;
  line_ = LineBranch{.unloading_stiffness_kN_per_m = unloading_stiffness_};
}

void ImkPeakOriented::reverse(double drift_m) {
  const double force = line_.force_at(drift_m);
  close_segment(drift_m);
  Backbone& s = force > 0.0 ? positive_ : negative_;
  const double sign = force > 0.0 ? 1.0 : -1.0;
  s.local_drift_m = drift_m;
  s.local_force_kN = force;
  if (sign * drift_m > sign * s.global_drift_m) {
    s.global_drift_m = drift_m;
    s.global_force_kN = force;
  }
  // Stiffness deterioration: the excursion's work less what unloading will return.
  const double recoverable_kJ = 0.5 * force * force / unloading_stiffness_;
  const double beta_k = beta(kStiffness, work_kJ_ - excursion_start_kJ_ - recoverable_kJ, work_kJ_ - recoverable_kJ);
  unloading_stiffness_ *= 1.0 - beta_k;
  // Unloading would return ½F²/K_u: more than the spring ever received, and the law would make
  // energy. Its energy is spent (this program's rule; OpenSees lets the work go negative).
  if (!(unloading_stiffness_ > 0.0) || 0.5 * force * force > work_kJ_ * unloading_stiffness_) failing_ = true;
  line_.force_kN = force;
  line_.drift_m = drift_m;
  if (failing_) return fail(drift_m);
  enter(1, drift_m);
}

void ImkPeakOriented::deteriorate_backbone(Backbone& s, const std::array<double, 4>& b) {
  const double k = parameters_.stiffness_kN_per_m;
  double cap_intercept_kN = s.cap_force_kN - s.post_cap_slope * s.cap_drift_m;
  s.yield_force_kN *= 1.0 - b[kStrength] * s.rate;
  s.plastic_slope *= 1.0 - b[kStrength] * s.rate;
  cap_intercept_kN *= 1.0 - b[kPostCap] * s.rate;
  s.global_drift_m *= 1.0 + b[kAccelerated] * s.rate;
  s.yield_drift_m = s.yield_force_kN / k;
  const double yield_intercept_kN = s.yield_force_kN - s.plastic_slope * s.yield_drift_m;
  s.cap_drift_m = s.plastic_slope <= s.post_cap_slope
                      ? 0.0
                      : (cap_intercept_kN - yield_intercept_kN) / (s.plastic_slope - s.post_cap_slope);
  s.cap_force_kN = yield_intercept_kN + s.plastic_slope * s.cap_drift_m;
  s.global_force_kN = backbone_force(s, s.global_drift_m, k);
  s.residual_drift_m = (s.residual_force_kN - s.cap_force_kN + s.post_cap_slope * s.cap_drift_m) / s.post_cap_slope;
}

void ImkPeakOriented::new_excursion(double drift_m, int direction) {
  close_segment(drift_m);
  const double excursion_kJ = std::max(0.0, work_kJ_ - excursion_start_kJ_);
  std::array<double, 4> b{};
  for (ImkMode mode : {kStrength, kPostCap, kAccelerated}) b[mode] = beta(mode, excursion_kJ, work_kJ_);
  excursion_start_kJ_ = work_kJ_;
  deteriorate_backbone(side(direction), b);
  if (failing_ || positive_.global_force_kN == 0.0 || negative_.global_force_kN == 0.0) return fail(drift_m);
  reload(drift_m, direction);
}

void ImkPeakOriented::reload(double drift_m, int direction) {
  const double k = parameters_.stiffness_kN_per_m, sign = direction;
  const double zero_force_m = drift_m - line_.force_at(drift_m) / line_.slope_kN_per_m;  // u0
  Backbone& s = side(direction);
  double global_slope = s.global_force_kN / (s.global_drift_m - zero_force_m);
  if (!(global_slope > 0.0 && global_slope <= k)) {
    // Reloading to the global peak would be stiffer than K_e or point backwards: reload at K_e to
    // where that line meets the backbone, the new global peak (this program's rule).
    const auto meets = [&](double force_kN, double anchor_m, double slope) {
      return (force_kN - slope * anchor_m + k * zero_force_m) / (k - slope);
    };
    double at_m = meets(s.cap_force_kN, s.cap_drift_m, s.plastic_slope);
    if (sign * at_m > sign * s.cap_drift_m) at_m = meets(s.cap_force_kN, s.cap_drift_m, s.post_cap_slope);
    if (sign * at_m > sign * s.residual_drift_m) at_m = meets(s.residual_force_kN, 0.0, 0.0);
    s.global_drift_m = at_m;
    s.global_force_kN = k * (at_m - zero_force_m);
    global_slope = k;
  }
  if (parameters_.pinching) {
    // The pinching point: κ_D back from the global peak's plastic drift, at κ_F of the force the
    // line to the global peak has there.
    const double plastic_m = s.global_drift_m - s.global_force_kN / unloading_stiffness_;
    pinch_drift_m_ = (1.0 - parameters_.pinching->kappa_d) * plastic_m;
    pinch_force_kN_ = parameters_.pinching->kappa_f * s.global_force_kN * (pinch_drift_m_ - zero_force_m) /
                      (s.global_drift_m - zero_force_m);
    if (sign * zero_force_m < sign * pinch_drift_m_) {
      reload_slope_ = pinch_force_kN_ / (pinch_drift_m_ - zero_force_m);
      return enter(direction > 0 ? 2 : 12, drift_m);
    }
  }
  const double local_slope = s.local_force_kN / (s.local_drift_m - zero_force_m);
  const bool to_local = sign * zero_force_m < sign * s.local_drift_m &&
                        sign * s.local_force_kN < sign * s.global_force_kN && local_slope > global_slope &&
                        local_slope <= k;
  reload_slope_ = to_local ? local_slope : global_slope;
  const int branch = to_local ? 3 : 4;
  enter(direction > 0 ? branch : branch + 10, drift_m);
}

bool ImkPeakOriented::pinches_before_global(const Backbone& s, int direction) const {
  if (!parameters_.pinching) return false;
  const double sign = direction;
  const double global_slope = (s.global_force_kN - s.local_force_kN) / (s.global_drift_m - s.local_drift_m);
  const double pinch_slope = (pinch_force_kN_ - s.local_force_kN) / (pinch_drift_m_ - s.local_drift_m);
  return sign * s.local_drift_m < sign * pinch_drift_m_ && sign * s.local_force_kN < sign * pinch_force_kN_ &&
         sign * pinch_drift_m_ < sign * s.global_drift_m && sign * pinch_force_kN_ < sign * s.global_force_kN &&
         pinch_slope < global_slope;
}

bool ImkPeakOriented::advance(double drift_m, int direction) {
  bool changed = false;
  for (int change = 0; change < kMaxChangesAtOneDrift && !failed_; ++change) {
    failing_ = false;
    if (line_.reversal_sign != 0 && direction == -line_.reversal_sign) {
      reverse(drift_m);
      changed = true;
      continue;
    }
    const bool at_upper = direction > 0 && drift_m >= line_.upper_m;
    const bool at_lower = direction < 0 && drift_m <= line_.lower_m;
    if (!at_upper && !at_lower) break;
    changed = true;
    if ((at_upper && drift_m >= positive_.ultimate_drift_m) || (at_lower && drift_m <= negative_.ultimate_drift_m)) {
      fail(drift_m);
      break;
    }
    close_segment(drift_m);
    pass_end(drift_m, direction);
  }
  return changed;
}

void ImkPeakOriented::pass_end(double drift_m, int direction) {
  const Backbone& s = side(direction);
  const auto slope = [](double d0, double f0, double d1, double f1) { return (f1 - f0) / (d1 - d0); };
  const bool global_beyond_local = direction * s.global_drift_m > direction * s.local_drift_m;
  const int mirror = direction > 0 ? 0 : 10;
  switch (branch_ % 10) {
    case 0: return enter(5 + mirror, drift_m);
    case 1:
      if (direction * line_.force_kN <= 0.0) return new_excursion(drift_m, direction);  // zero force
      // Back at the reversal point: on to the global peak (through the pinching point, IMKPinching).
      if (global_beyond_local && pinches_before_global(s, direction)) {
        reload_slope_ = slope(s.local_drift_m, s.local_force_kN, pinch_drift_m_, pinch_force_kN_);
        return enter(2 + mirror, drift_m);
      }
      if (global_beyond_local)
        reload_slope_ = slope(s.local_drift_m, s.local_force_kN, s.global_drift_m, s.global_force_kN);
      return enter((global_beyond_local ? 4 : 5) + mirror, drift_m);
    case 2: {  // past the pinching point: on to the local peak if it lies ahead and steeper, else the global
      const double to_global = slope(pinch_drift_m_, pinch_force_kN_, s.global_drift_m, s.global_force_kN);
      const double to_local = slope(pinch_drift_m_, pinch_force_kN_, s.local_drift_m, s.local_force_kN);
      const bool local = direction * pinch_drift_m_ < direction * s.local_drift_m &&
                         direction * pinch_force_kN_ < direction * s.local_force_kN &&
                         direction * s.local_force_kN < direction * s.global_force_kN && to_local > to_global;
      reload_slope_ = local ? to_local : to_global;
      return enter(branch_ + (local ? 1 : 2), drift_m);
    }
    case 3:
      if (global_beyond_local)
        reload_slope_ = slope(s.local_drift_m, s.local_force_kN, s.global_drift_m, s.global_force_kN);
      return enter(branch_ + (global_beyond_local ? 1 : 2), drift_m);
    case 4:
    case 5: return enter(branch_ + 1, drift_m);
    case 6:
      enter(branch_ + 1, drift_m);
      if (direction * s.residual_force_kN <= 0.0) fail(drift_m);  // no residual strength
      return;
  }
}

}  // namespace pounding::dynamics
