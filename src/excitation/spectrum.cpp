#include "pounding/excitation/spectrum.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "pounding/input_error.hpp"

namespace pounding::excitation {

void SpectrumOptions::validate() const {
  if (!(damping_ratio >= 0.0 && damping_ratio < 1.0)) {
    throw InputError("damping_ratio", format_value(damping_ratio), "must lie in [0, 1) (an oscillating SDOF)");
  }
  if (periods_s.size() > static_cast<std::size_t>(kMaxSpectrumPeriods)) {
    throw InputError("periods_s", std::to_string(periods_s.size()) + " periods",
                     "must hold at most " + std::to_string(kMaxSpectrumPeriods));
  }
  for (std::size_t i = 0; i < periods_s.size(); ++i) {
    require_range("periods_s[" + std::to_string(i + 1) + "]", periods_s[i], {kMinPeriod_s, kMaxPeriod_s, "s"});
  }
}

std::vector<double> default_periods_s() {
  std::vector<double> periods;
  for (int i = 0; i <= 60; ++i) periods.push_back(std::pow(10.0, -2.0 + i / 20.0));
  return periods;
}

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
/// Substeps per undamped period: short enough that x has at most one turning point in a substep
/// and the cubic Hermite estimate of a peak inside it is within ~1e-4 of the amplitude.
constexpr double kSubstepsPerPeriod = 16.0;
/// A turning point is located exactly when its Hermite estimate comes this close (relative) to
/// the largest |x| found so far: well above the estimate's own error.
constexpr double kRefineMargin = 1e-3;

/// The SDOF x'' + 2ζωx' + ω²x = −a(t), a linear over a step, advanced by its closed form.
class Oscillator {
 public:
  Oscillator(double period_s, double damping_ratio)
      : omega_(kTwoPi / period_s),
        zeta_(damping_ratio),
        omega_d_(omega_ * std::sqrt(1.0 - damping_ratio * damping_ratio)) {}

  double omega() const { return omega_; }

  /// (x, v) after h (s) from (x0, v0), a going linearly from a0 to a1 (m/s²).
  std::array<double, 2> advance(double x0, double v0, double a0, double a1, double h) const {
    const double slope = (a1 - a0) / h;
    // Particular solution α + βt of the linear forcing; the rest is free vibration.
    const double w2 = omega_ * omega_;
    const double beta = -slope / w2;
    const double alpha = -a0 / w2 + 2.0 * zeta_ * slope / (w2 * omega_);
    const double y0 = x0 - alpha;
    const double dy0 = v0 - beta;
    const double decay = std::exp(-zeta_ * omega_ * h);
    const double c = std::cos(omega_d_ * h);
    const double s = std::sin(omega_d_ * h);
    const double x = alpha + beta * h + decay * (y0 * c + (dy0 + zeta_ * omega_ * y0) / omega_d_ * s);
    const double v = beta + decay * (dy0 * c - (w2 * y0 + zeta_ * omega_ * dy0) / omega_d_ * s);
    return {x, v};
  }

 private:
  double omega_, zeta_, omega_d_;
};

/// The response at the nodes of the record's samples, each interval cut into equal substeps of
/// at most period/kSubstepsPerPeriod; a_k is the forcing at node k (linear between nodes).
struct Trace {
  std::vector<double> t, x, v, a;
};

Trace trace_response(const AccelerationHistory& history, const Oscillator& oscillator, double period_s) {
  Trace trace;
  const double max_substep_s = period_s / kSubstepsPerPeriod;
  const std::size_t n = history.time_s.size();
  trace.t.push_back(history.time_s.front());
  trace.x.push_back(0.0);
  trace.v.push_back(0.0);
  trace.a.push_back(history.accel_mps2.front());
  // The same step length recurs (uniform records): the coefficients of the recurrence would be
  // cheaper, but the closed form keeps every step exact and this is not the hot path of a run.
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double t0 = history.time_s[i];
    const double dt = history.time_s[i + 1] - t0;
    const double a0 = history.accel_mps2[i];
    const double a1 = history.accel_mps2[i + 1];
    const int pieces = std::max(1, static_cast<int>(std::ceil(dt / max_substep_s)));
    const double h = dt / pieces;
    for (int k = 1; k <= pieces; ++k) {
      const double a_end = k == pieces ? a1 : a0 + (a1 - a0) * (static_cast<double>(k) / pieces);
      const auto [x, v] = oscillator.advance(trace.x.back(), trace.v.back(), trace.a.back(), a_end, h);
      trace.t.push_back(k == pieces ? history.time_s[i + 1] : t0 + k * h);
      trace.x.push_back(x);
      trace.v.push_back(v);
      trace.a.push_back(a_end);
    }
  }
  return trace;
}

/// The largest value of the cubic Hermite interpolant of (x0, v0), (x1, v1) over [0, h] at a
/// root of its derivative inside (0, h); |x0| when there is none.
double hermite_turning_value(double x0, double v0, double x1, double v1, double h) {
  // p(s) = x0 + v0 s + c2 s² + c3 s³ on [0, h].
  const double c2 = (3.0 * (x1 - x0) / h - 2.0 * v0 - v1) / h;
  const double c3 = (v0 + v1 - 2.0 * (x1 - x0) / h) / (h * h);
  auto p = [&](double s) { return x0 + s * (v0 + s * (c2 + s * c3)); };
  double best = std::abs(x0);
  // p'(s) = v0 + 2c2 s + 3c3 s².
  const double qa = 3.0 * c3, qb = 2.0 * c2, qc = v0;
  std::array<double, 2> roots{-1.0, -1.0};
  if (std::abs(qa) < 1e-300) {
    if (qb != 0.0) roots[0] = -qc / qb;
  } else {
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc >= 0.0) {
      const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
      roots = {q / qa, q != 0.0 ? qc / q : -1.0};
    }
  }
  for (double s : roots) {
    if (s > 0.0 && s < h) best = std::max(best, std::abs(p(s)));
  }
  return best;
}

/// A combination c1·x1 + c2·x2 of one or two traces on the same nodes.
struct Combination {
  const Trace* first;
  const Trace* second;  // null: the first alone
  double c1, c2;

  double x(std::size_t k) const { return c1 * first->x[k] + (second ? c2 * second->x[k] : 0.0); }
  double v(std::size_t k) const { return c1 * first->v[k] + (second ? c2 * second->v[k] : 0.0); }
  /// (x, v) of the combination τ into the substep that starts at node k.
  std::array<double, 2> inside(const Oscillator& oscillator, std::size_t k, double tau) const {
    auto one = [&](const Trace& trace) {
      const double h = trace.t[k + 1] - trace.t[k];
      const double a_tau = trace.a[k] + (trace.a[k + 1] - trace.a[k]) * (tau / h);
      return oscillator.advance(trace.x[k], trace.v[k], trace.a[k], a_tau, tau);
    };
    const auto a = one(*first);
    if (!second) return {c1 * a[0], c1 * a[1]};
    const auto b = one(*second);
    return {c1 * a[0] + c2 * b[0], c1 * a[1] + c2 * b[1]};
  }
};

struct Peak {
  double value = 0.0;
  double time_s = 0.0;
};

/// The time τ ∈ (0, h) where the combination's rate vanishes, by regula falsi (Illinois) on the
/// closed form; the rate changes sign over the substep.
double turning_time(const Combination& combination, const Oscillator& oscillator, std::size_t k, double h) {
  double lo = 0.0, hi = h;
  double f_lo = combination.v(k), f_hi = combination.v(k + 1);
  int side = 0;
  for (int iteration = 0; iteration < 200 && hi - lo > 4e-16 * h; ++iteration) {
    double tau = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    if (!(tau > lo && tau < hi)) tau = 0.5 * (lo + hi);
    const double f = combination.inside(oscillator, k, tau)[1];
    if (f == 0.0) return tau;
    if ((f < 0.0) == (f_lo < 0.0)) {
      lo = tau, f_lo = f;
      if (side == -1) f_hi *= 0.5;
      side = -1;
    } else {
      hi = tau, f_hi = f;
      if (side == 1) f_lo *= 0.5;
      side = 1;
    }
  }
  return 0.5 * (lo + hi);
}

/// The peak |combination| over the trace: the largest at the nodes, then every turning point
/// inside a substep whose Hermite estimate could exceed it, located on the closed form.
Peak peak_of(const Combination& combination, const Oscillator& oscillator) {
  const Trace& trace = *combination.first;
  Peak peak;
  for (std::size_t k = 0; k < trace.t.size(); ++k) {
    const double value = std::abs(combination.x(k));
    if (value > peak.value) peak = {value, trace.t[k]};
  }
  for (std::size_t k = 0; k + 1 < trace.t.size(); ++k) {
    const double v0 = combination.v(k), v1 = combination.v(k + 1);
    if (!((v0 < 0.0 && v1 > 0.0) || (v0 > 0.0 && v1 < 0.0))) continue;
    const double h = trace.t[k + 1] - trace.t[k];
    const double estimate = hermite_turning_value(combination.x(k), v0, combination.x(k + 1), v1, h);
    if (estimate < peak.value * (1.0 - kRefineMargin)) continue;
    const double tau = turning_time(combination, oscillator, k, h);
    const double value = std::abs(combination.inside(oscillator, k, tau)[0]);
    if (value > peak.value) peak = {value, trace.t[k] + tau};
  }
  return peak;
}

const std::vector<double>& periods_of(const SpectrumOptions& options, std::vector<double>& storage) {
  if (!options.periods_s.empty()) return options.periods_s;
  storage = default_periods_s();
  return storage;
}

double interpolate(const AccelerationHistory& history, double t) {
  const auto& times = history.time_s;
  if (t < times.front() || t > times.back()) return 0.0;
  const auto upper = std::lower_bound(times.begin(), times.end(), t);
  const std::size_t i = static_cast<std::size_t>(upper - times.begin());
  if (times[i] == t) return history.accel_mps2[i];
  const double w = (t - times[i - 1]) / (times[i] - times[i - 1]);
  return history.accel_mps2[i - 1] + w * (history.accel_mps2[i] - history.accel_mps2[i - 1]);
}

}  // namespace

std::vector<SpectrumOrdinate> response_spectrum(const AccelerationHistory& history, const SpectrumOptions& options) {
  options.validate();
  std::vector<double> storage;
  std::vector<SpectrumOrdinate> ordinates;
  for (double period_s : periods_of(options, storage)) {
    const Oscillator oscillator(period_s, options.damping_ratio);
    const Trace trace = trace_response(history, oscillator, period_s);
    const Peak peak = peak_of({&trace, nullptr, 1.0, 0.0}, oscillator);
    const double omega = oscillator.omega();
    ordinates.push_back({period_s, peak.value, omega * peak.value, omega * omega * peak.value, peak.time_s});
  }
  return ordinates;
}

std::pair<AccelerationHistory, AccelerationHistory> on_common_time_base(const AccelerationHistory& first,
                                                                        const AccelerationHistory& second) {
  std::vector<double> times;
  times.reserve(first.time_s.size() + second.time_s.size());
  std::merge(first.time_s.begin(), first.time_s.end(), second.time_s.begin(), second.time_s.end(),
             std::back_inserter(times));
  times.erase(std::unique(times.begin(), times.end()), times.end());
  AccelerationHistory a{times, {}}, b{times, {}};
  for (double t : times) {
    a.accel_mps2.push_back(interpolate(first, t));
    b.accel_mps2.push_back(interpolate(second, t));
  }
  return {std::move(a), std::move(b)};
}

std::vector<RotDOrdinate> rotd_spectrum(const AccelerationHistory& first, const AccelerationHistory& second,
                                        const SpectrumOptions& options, double angle_step_deg) {
  options.validate();
  if (!(angle_step_deg > 0.0 && angle_step_deg <= 90.0)) {
    throw InputError("angle_step_deg", format_value(angle_step_deg), "must lie in (0, 90] degrees");
  }
  const auto [a, b] = on_common_time_base(first, second);
  const int angles = static_cast<int>(std::ceil(180.0 / angle_step_deg - 1e-9));
  std::vector<double> storage;
  std::vector<RotDOrdinate> ordinates;
  for (double period_s : periods_of(options, storage)) {
    const Oscillator oscillator(period_s, options.damping_ratio);
    const Trace trace_a = trace_response(a, oscillator, period_s);
    const Trace trace_b = trace_response(b, oscillator, period_s);
    std::vector<double> peaks;
    RotDOrdinate ordinate{.period_s = period_s};
    for (int i = 0; i < angles; ++i) {
      const double theta_deg = i * angle_step_deg;
      const double theta = theta_deg * std::numbers::pi / 180.0;
      const double value = peak_of({&trace_a, &trace_b, std::cos(theta), std::sin(theta)}, oscillator).value;
      if (value > ordinate.rotd100_sd_m) ordinate.rotd100_sd_m = value, ordinate.rotd100_angle_deg = theta_deg;
      peaks.push_back(value);
    }
    std::sort(peaks.begin(), peaks.end());
    const std::size_t m = peaks.size();
    ordinate.rotd50_sd_m = m % 2 == 1 ? peaks[m / 2] : 0.5 * (peaks[m / 2 - 1] + peaks[m / 2]);
    const double w2 = oscillator.omega() * oscillator.omega();
    ordinate.rotd50_psa_mps2 = w2 * ordinate.rotd50_sd_m;
    ordinate.rotd100_psa_mps2 = w2 * ordinate.rotd100_sd_m;
    ordinates.push_back(ordinate);
  }
  return ordinates;
}

double scale_to_psa(const AccelerationHistory& history, double period_s, double damping_ratio, double target_psa_mps2) {
  if (!(target_psa_mps2 > 0.0) || !std::isfinite(target_psa_mps2)) {
    throw InputError("target_psa", format_value(target_psa_mps2), "must be positive (m/s²)");
  }
  const SpectrumOptions options{.periods_s = {period_s}, .damping_ratio = damping_ratio};
  const double psa = response_spectrum(history, options).front().psa_mps2;
  if (!(psa > 0.0)) {
    throw InputError("period_s", format_value(period_s), "the record's spectral acceleration there is zero");
  }
  return target_psa_mps2 / psa;
}

}  // namespace pounding::excitation
