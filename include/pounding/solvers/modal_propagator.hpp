#pragma once
// The exact advance of one damped oscillator under a load linear in time (the Nigam–Jennings
// recurrence of response spectra):
//   η̈ + 2ζω η̇ + ω² η = p₀ + s τ   on [0, τ]   ⇒
//   (η, η̇)(τ) = free · (η, η̇)(0) + start · p₀ + slope · s.
// Real arithmetic throughout, for any ζ ≥ 0 (under-, critically and overdamped alike).

#include <Eigen/Core>

namespace pounding::solvers {

struct OscillatorStep {
  Eigen::Matrix2d free;   // e^{Fτ}, F = [[0, 1], [−ω², −2ζω]]
  Eigen::Vector2d start;  // response to a unit constant load p₀ (η in m per m/s², η̇ in m/s per m/s²)
  Eigen::Vector2d slope;  // response to a unit load rate s
};

/// The oscillator's step over τ (s), exact to round-off (1e-13 relative, tests/solvers/
/// test_modal_exact.cpp): a Taylor series where the closed form would cancel (ωτ small), the
/// closed form (ζ ≤ 2) or the spectral form of two real modes (ζ > 2) elsewhere.
/// @pre ω > 0, ζ ≥ 0, τ ≥ 0.
OscillatorStep oscillator_step(double omega_rad_s, double damping_ratio, double tau_s);

}  // namespace pounding::solvers
