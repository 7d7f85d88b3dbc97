#pragma once
// One building's motion in real modal coordinates. With classical damping (Rayleigh,
// C = a0 M + a1 K) the equations M q̈ + C q̇ + K q = −M r a_g(t) decouple into one damped
// oscillator per mode:
//   η̈_k + 2 ζ_k ω_k η̇_k + ω_k² η_k = −Γ_k a_g(t),   q = Φ η,   η = Φᵀ M q,
// Φ mass-normalised (Φᵀ M Φ = I), Γ = Φᵀ M r, ζ_k = a0/(2ω_k) + a1 ω_k/2. A pair of ground-motion
// components c loads each mode by −Σ_c Γ_kc a_c(t), with Γ_c = Φᵀ M r_c.

#include <Eigen/Core>

#include "pounding/model/building.hpp"

namespace pounding::model {

struct ModalBasis {
  Eigen::VectorXd omega_rad_s;    // ascending (longest period first), all > 0 (K is SPD)
  Eigen::VectorXd damping_ratio;  // ζ ≥ 0; above 1 the mode is overdamped (no oscillation)
  Eigen::MatrixXd shapes;         // Φ (3N × 3N), columns mass-normalised
  Eigen::MatrixXd projection;     // Φᵀ M: η = projection · q (and η̇ = projection · q̇)
  Eigen::MatrixXd participation;  // Γ = Φᵀ M r (t^½ per unit of r), a column per ground-motion component
  /// The quasi-static response of the modes left out (keep_modes_below) to a unit ground
  /// acceleration, R = −Σ_dropped φᵢ Γᵢ / ωᵢ² over the DOFs (m per m/s², i.e. s²), a column per
  /// component: the building moves as Φ η + Σ_c R_c a_c(t). Zero when every mode is kept.
  Eigen::MatrixXd dropped_static_s2;

  int size() const { return static_cast<int>(omega_rad_s.size()); }
};

/// Largest departure of Φᵀ C Φ from diag(2ζω), relative to its largest diagonal entry, that still
/// counts as the Rayleigh damping the modes decouple (round-off leaves ~1e-14).
inline constexpr double kClassicalDampingTolerance = 1e-9;

/// The modal basis of `building` under ground motion along `influence` (a column r_c over the
/// building's DOFs per component, (cos β, sin β, 0) per floor for H1), from the modes the building keeps
/// (Building::modes); a run reads its buildings' bases from dynamics::CoupledSystem::modal_basis, built once.
/// @pre influence.rows() == building.dof(), building.modes those of its M and K.
/// @throws std::runtime_error if building.damping is not a0 M + a1 K (Φᵀ C Φ ≠ diag(2ζω) within
///   kClassicalDampingTolerance): the modes would not decouple it.
ModalBasis modal_basis(const Building& building, const Eigen::Ref<const Eigen::MatrixXd>& influence);

/// `full` (a complete basis, modal_basis()) with only its modes of frequency ωᵢ/2π < cutoff_hz;
/// the others are replaced by their quasi-static response R a_g (dropped_static_s2, residual
/// flexibility), the rest of what the ground moves them by being their dynamic response to it.
/// Φ keeps its 3N rows (shapes is 3N × kept, projection kept × 3N). cutoff_hz = 0 keeps every
/// mode. Since R lies in the span of the dropped modes, Φᵀ M R = 0: projecting a physical state
/// on the kept modes drops the correction. @pre cutoff_hz ≥ 0, `full` complete.
ModalBasis keep_modes_below(const ModalBasis& full, double cutoff_hz);

}  // namespace pounding::model
