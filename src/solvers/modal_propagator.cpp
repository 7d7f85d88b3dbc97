#include "pounding/solvers/modal_propagator.hpp"

#include <cmath>

namespace pounding::solvers {
namespace {

/// Balanced ‖Fτ‖ above which the closed form is used (for ζ ≤ 2): below it the series is both
/// more accurate and, with few terms, as cheap.
constexpr double kClosedFormSize = 0.25;

/// e^X, φ₁(X) e₂ τ and φ₂(X) e₂ τ² with X = Fτ by their series, for ‖X‖ = `size` ≤
/// kClosedFormSize in the balanced norm ωτ(1 + 2ζ): summed until the next term is below 2⁻⁵⁶.
/// By Cayley–Hamilton Xʲ = aⱼ I + bⱼ X with a scalar recurrence, so each series is two scalar sums.
OscillatorStep taylor_step(double omega, double zeta, double tau, double size) {
  const double trace = -2.0 * zeta * omega * tau, det = omega * omega * tau * tau;
  double a = 1.0, b = 0.0;                                            // Xʲ/j! = a I + b X
  double a0 = 0.0, b0 = 0.0, a1 = 0.0, b1 = 0.0, a2 = 0.0, b2 = 0.0;  // e^X, φ₁(X), φ₂(X) as (a, b)
  double remainder = 1.0;  // size^(j+1)/(j + 1)!: bounds the balanced norm of the next term
  for (int j = 0;; ++j) {
    const double to_phi1 = 1.0 / double(j + 1), to_phi2 = to_phi1 / double(j + 2);  // j!/(j+1)!, j!/(j+2)!
    a0 += a, b0 += b;
    a1 += a * to_phi1, b1 += b * to_phi1;
    a2 += a * to_phi2, b2 += b * to_phi2;
    remainder *= size * to_phi1;
    if (remainder <= 0x1p-56) break;
    const double next_a = -det * b * to_phi1;  // X^{j+1} = −det bⱼ I + (aⱼ + tr bⱼ) X
    b = (a + trace * b) * to_phi1;
    a = next_a;
  }
  OscillatorStep step;
  step.free << a0, b0 * tau, -b0 * omega * omega * tau, a0 + trace * b0;
  step.start << tau * tau * b1, tau * (a1 + trace * b1);  // τ φ₁(X) e₂, X e₂ = (τ, tr)
  step.slope << tau * tau * tau * b2, tau * tau * (a2 + trace * b2);
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

/// (e^x − 1 − x)/x² for x ≤ 0, by its series where the closed form would cancel.
double phi2(double x) {
  if (x < -0.5) return (std::expm1(x) - x) / (x * x);
  double sum = 0.0, term = 0.5;  // xʲ/(j + 2)!
  for (int j = 0; j < 20 && std::abs(term) > 0x1p-56 * std::abs(sum); ++j) {
    sum += term;
    term *= x / double(j + 3);
  }
  return sum;
}

/// Overdamped (ζ > 2): two real eigenvalues λ₁ = −ω/(ζ + √(ζ² − 1)) (slow) and λ₂ = −2ζω − λ₁,
/// at least 14 times apart, so the spectral form f(F) = f(λ₁) P₁ + f(λ₂) P₂ has no cancellation,
/// and expm1 keeps the slow mode's load response accurate however small λ₁τ is.
OscillatorStep overdamped_step(double omega, double zeta, double tau) {
  const double slow = -omega / (zeta + std::sqrt(zeta * zeta - 1.0)), fast = -2.0 * zeta * omega - slow;
  // P₁ = (F − λ₂)/(λ₁ − λ₂), P₂ = (F − λ₁)/(λ₂ − λ₁); their second columns are (1, λ)/(±Δλ).
  const double gap = slow - fast;
  Eigen::Matrix2d p1, p2;
  p1 << -fast, 1.0, -omega * omega, -2.0 * zeta * omega - fast;
  p2 << -slow, 1.0, -omega * omega, -2.0 * zeta * omega - slow;
  p1 /= gap;
  p2 /= -gap;
  OscillatorStep step;
  step.free = std::exp(slow * tau) * p1 + std::exp(fast * tau) * p2;
  const double x1 = slow * tau, x2 = fast * tau;
  step.start = tau * (std::expm1(x1) / x1 * p1.col(1) + std::expm1(x2) / x2 * p2.col(1));
  step.slope = tau * tau * (phi2(x1) * p1.col(1) + phi2(x2) * p2.col(1));
  return step;
}

}  // namespace

OscillatorStep oscillator_step(double omega_rad_s, double damping_ratio, double tau_s) {
  const double size = omega_rad_s * tau_s * (1.0 + 2.0 * damping_ratio);  // ‖Fτ‖ in (η, η̇/ω)
  if (size <= kClosedFormSize) return taylor_step(omega_rad_s, damping_ratio, tau_s, size);
  if (damping_ratio <= 2.0) return closed_step(omega_rad_s, damping_ratio, tau_s);
  return overdamped_step(omega_rad_s, damping_ratio, tau_s);
}

}  // namespace pounding::solvers
