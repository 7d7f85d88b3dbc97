#include "pounding/solvers/modal_propagator.hpp"

#include <cmath>

namespace pounding::solvers {
namespace {

/// Balanced ‖Fτ‖ above which the closed form is used (for ζ ≤ 2): below it the series is both
/// more accurate and, with few terms, as cheap.
constexpr double kClosedFormSize = 0.25;

/// e^X, φ₁(X) e₂ τ and φ₂(X) e₂ τ² with X = Fτ by their series, for ‖X‖ = `size` ≤ 1 in the
/// balanced norm ωτ(1 + 2ζ): summed until the next term is below 2⁻⁵⁶ of the sum (at most 19).
OscillatorStep taylor_step(double omega, double zeta, double tau, double size) {
  Eigen::Matrix2d x;
  x << 0.0, tau, -omega * omega * tau, -2.0 * zeta * omega * tau;
  OscillatorStep step;
  Eigen::Matrix2d term = Eigen::Matrix2d::Identity();  // Xʲ/j!
  step.free = term;
  Eigen::Vector2d column = term.col(1);  // Xʲ e₂ / j!
  step.start = column;
  step.slope = column / 2.0;
  double remainder = 1.0;  // sizeʲ/j!, the balanced norm of the next term
  for (int j = 1; remainder > 0x1p-56; ++j) {
    remainder *= size / double(j + 1);
    term = term * x / double(j);
    column = term.col(1);
    step.free += term;
    step.start += column / double(j + 1);
    step.slope += column / double((j + 1) * (j + 2));
  }
  step.start *= tau;
  step.slope *= tau * tau;
  return step;
}

/// The closed form: free response through the particular solutions η_p = p₀/ω² (constant load)
/// and η_p = (τ − 2ζ/ω)/ω² (unit load rate). Used for ωτ(1 + 2ζ) > kClosedFormSize and ζ ≤ 2,
/// where their cancellation against e^{Fτ} costs at most a factor ((1 + 2ζ)/kClosedFormSize)²
/// of round-off (measured against a long-double matrix exponential: below 1e-13 relative).
OscillatorStep closed_step(double omega, double zeta, double tau) {
  const double decay_rate = zeta * omega;
  double damped_cos = 0.0, damped_sin_over = 0.0;  // e^{−ζωτ} c and e^{−ζωτ} S of the free response
  if (zeta < 1.0) {
    const double omega_d = omega * std::sqrt(1.0 - zeta * zeta);
    const double decay = std::exp(-decay_rate * tau);
    damped_cos = decay * std::cos(omega_d * tau);
    damped_sin_over = decay * std::sin(omega_d * tau) / omega_d;
  } else {
    const double mu = omega * std::sqrt(zeta * zeta - 1.0);
    const double x = mu * tau;
    if (x <= 1.0) {  // near critical: sinh(x)/x has no cancellation and cosh cannot overflow
      const double decay = std::exp(-decay_rate * tau);
      damped_cos = decay * std::cosh(x);
      damped_sin_over = decay * tau * (x == 0.0 ? 1.0 : std::sinh(x) / x);
    } else {  // as two real exponentials, so e^{−ζωτ} cosh(μτ) cannot overflow into 0·∞
      const double slow = std::exp((mu - decay_rate) * tau), fast = std::exp(-(mu + decay_rate) * tau);
      damped_cos = 0.5 * (slow + fast);
      damped_sin_over = (slow - fast) / (2.0 * mu);
    }
  }
  OscillatorStep step;
  step.free << damped_cos + decay_rate * damped_sin_over, damped_sin_over,  //
      -omega * omega * damped_sin_over, damped_cos - decay_rate * damped_sin_over;
  const double w2 = omega * omega;
  const Eigen::Vector2d constant(1.0 / w2, 0.0);
  step.start = constant - step.free * constant;
  const Eigen::Vector2d ramp_start(-2.0 * zeta / (w2 * omega), 1.0 / w2);
  step.slope = Eigen::Vector2d(ramp_start[0] + tau / w2, ramp_start[1]) - step.free * ramp_start;
  return step;
}

}  // namespace

OscillatorStep oscillator_step(double omega_rad_s, double damping_ratio, double tau_s) {
  const double size = omega_rad_s * tau_s * (1.0 + 2.0 * damping_ratio);  // ‖Fτ‖ in (η, η̇/ω)
  if (size > kClosedFormSize && damping_ratio <= 2.0) return closed_step(omega_rad_s, damping_ratio, tau_s);
  // Series on τ/2ˢ with ‖X‖ ≤ 1, then doubled s times: over [τ, 2τ] the load is p₀ + sτ + sτ',
  // so free(2τ) = free², start(2τ) = (I + free) start, slope(2τ) = (I + free) slope + τ start.
  int squarings = 0;
  double h = tau_s;
  if (size > 1.0) {
    squarings = static_cast<int>(std::ceil(std::log2(size)));
    h = std::ldexp(tau_s, -squarings);
  }
  OscillatorStep step = taylor_step(omega_rad_s, damping_ratio, h, std::min(size, 1.0));
  for (int k = 0; k < squarings; ++k) {
    const Eigen::Matrix2d grow = Eigen::Matrix2d::Identity() + step.free;
    step.slope = grow * step.slope + h * step.start;
    step.start = grow * step.start;
    step.free = step.free * step.free;
    h *= 2.0;
  }
  return step;
}

}  // namespace pounding::solvers
