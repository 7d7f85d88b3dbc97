#pragma once
// The two buildings' free motion in modal coordinates. Each building alone is classically damped
// (Rayleigh), so with its real mass-normalised modes Φ_b (Φᵀ M Φ = I, Φᵀ K Φ = Ω², Φᵀ C Φ = 2ZΩ)
// q_b = Φ_b η_b decouples it into 3N single-DOF oscillators:
//   z = (η, η̇),  η̈ᵢ = −2ζᵢωᵢ η̇ᵢ − ωᵢ² ηᵢ − Γᵢ a_g(t),  Γ = Φᵀ M r,
// η ordered building 1's modes first, each building's longest period first. Its Jacobian is
// [[0, I], [−Ω², −2ZΩ]]: diagonal blocks, so a Newton system costs O(n). The map y = T z with
// T = diag(Φ, Φ) (Φ block-diagonal over the buildings) and its inverse T⁻¹ = diag(ΦᵀM, ΦᵀM)
// carry states, rates and Jacobians between the forms. Units: η, η̇ in √t·m (and s⁻¹).

#include <Eigen/Core>
#include <array>

#include "pounding/dynamics/coupled_system.hpp"

namespace pounding::dynamics {

class ModalSystem {
 public:
  /// `system` must outlive this object. @throws std::invalid_argument if a building's damping is
  /// not diagonal in its modes (Rayleigh damping always is, to round-off).
  explicit ModalSystem(const CoupledSystem& system);

  const CoupledSystem& system() const { return system_; }
  int dof() const { return system_.dof(); }
  int state_size() const { return system_.state_size(); }
  const VectorXd& omega_rad_s() const { return omega_rad_s_; }  // ωᵢ
  /// Γᵢc = φᵢᵀ M r_c (√t): a row per mode, a column per ground-motion component.
  const MatrixXd& participation() const { return participation_; }
  const VectorXd& damping_per_s() const { return damping_per_s_; }  // 2ζᵢωᵢ

  /// Free motion ż = (η̇, −Ω²η − 2ZΩη̇ − Γ a_g(t)): O(n).
  void rhs(double t, ConstVectorRef z, Eigen::Ref<VectorXd> z_dot) const;
  /// The constant Jacobian [[0, I], [−Ω², −2ZΩ]] of rhs.
  void jacobian(Eigen::Ref<MatrixXd> jacobian) const;

  /// y = T z (physical state or rate from modal). O(n²/2) for two equal buildings.
  void to_physical(ConstVectorRef z, Eigen::Ref<VectorXd> y) const;
  /// z = T⁻¹ y = (ΦᵀM q, ΦᵀM q̇): exact inverse of to_physical for mass-normalised Φ.
  void to_modal(ConstVectorRef y, Eigen::Ref<VectorXd> z) const;
  /// T⁻¹ J T of a physical Jacobian J (2n×2n): what the modal form integrates while a contact
  /// force acts (holds, compliant laws). O(r n²), r the rows where J differs from the free
  /// Jacobian (the contact floors' accelerations).
  void jacobian_to_modal(const MatrixXd& physical, Eigen::Ref<MatrixXd> modal) const;

  /// Absolute tolerances of z from the physical ones `physical_atol` (over y, analysis::
  /// ComponentAtol): per building b, every η of b gets w_b = 1 / max_j ‖Φ_b,j‖₂ / a_j over the
  /// (u, v, φ) rows j of the floors where b has a contact candidate (all floors if none), and η̇ᵢ
  /// gets w_b ωᵢ. Why: CVODE's test bounds the error ε by ‖ε/w‖₂ ≤ √N, so a physical component
  /// errs by |Φ_j ε| ≤ ‖Φ_j‖₂ ‖ε‖₂ ≤ a_j √N: the bound the physical form has. A rate error δ
  /// displaces an oscillator by about δ/ωᵢ before the mode turns, so w_b ωᵢ keeps that within w_b.
  VectorXd atol(const VectorXd& physical_atol) const;

 private:
  const CoupledSystem& system_;
  std::vector<MatrixXd> shapes_;        // Φ_b, columns the modes, per building
  std::vector<MatrixXd> inverse_;       // Φ_bᵀ M_b
  MatrixXd shape_full_, inverse_full_;  // block-diagonal over both buildings (Jacobian maps)
  VectorXd omega_rad_s_, damping_per_s_;
  MatrixXd participation_;
};

}  // namespace pounding::dynamics
