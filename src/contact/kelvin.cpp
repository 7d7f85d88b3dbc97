#include "pounding/contact/kelvin.hpp"

#include <cmath>
#include <numbers>

namespace pounding::contact {

double kelvin_damping_ratio(double restitution) {
  if (restitution <= 0.0) return 1.0;
  const double log_e = std::log(restitution);
  return -log_e / std::sqrt(std::numbers::pi * std::numbers::pi + log_e * log_e);
}

KelvinRelease kelvin_release(double damping_ratio) {
  const double xi = damping_ratio;
  if (xi >= 1.0) {  // critical: δ = v₀ t e^{−ωt}, the force ∝ (2 − ωt)
    return {2.0, std::exp(-2.0), 2.0 * std::exp(-2.0)};
  }
  const double root = std::sqrt(1.0 - xi * xi);  // ω_d / ω
  // kδ + cδ̇ ∝ (1 − 2ξ²) sin ω_d t + 2ξ√(1 − ξ²) cos ω_d t: zero past the half period's start.
  const double phase = std::numbers::pi - std::atan2(2.0 * xi * root, 1.0 - 2.0 * xi * xi);
  const double omega_time = phase / root;
  const double decay = std::exp(-xi * omega_time);
  return {omega_time, -decay * (std::cos(phase) - xi / root * std::sin(phase)), decay * std::sin(phase) / root};
}

double kelvin_damping(double stiffness_kN_per_m, double restitution, double normal_inverse_mass_per_t) {
  return 2.0 * kelvin_damping_ratio(restitution) * std::sqrt(stiffness_kN_per_m / normal_inverse_mass_per_t);
}

}  // namespace pounding::contact
