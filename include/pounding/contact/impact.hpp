#pragma once
// Impact law: instantaneous, frictionless, Newton restitution (docs/model.md §6). Pure functions on
// one floor pair, whose six velocities are ordered (u̇, v̇, φ̇) of building 1's slab, then
// building 2's.

#include <Eigen/Core>
#include <vector>

namespace pounding::contact {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using RowVector6d = Eigen::Matrix<double, 1, 6>;

/// (1/m₁, 1/m₁, 1/J₁, 1/m₂, 1/m₂, 1/J₂) of the two slabs of one floor.
Vector6d inverse_mass(double mass1_t, double polar1_tm2, double mass2_t, double polar2_tm2);

/// One contact of an impact: ġ = jacobian · q̇ over the floor pair's six velocities.
struct ContactRow {
  RowVector6d jacobian;
  double gap_rate_mps = 0.0;  // ġ⁻, before the impact
  double restitution = 0.5;   // k ∈ [0, 1] for this contact
};

/// Single contact, the paper's law: a = G M⁻¹ Gᵀ, I = (1 + k)(−ġ⁻)/a (kN·s), Δq̇ = M⁻¹ Gᵀ I.
/// Gives ġ⁺ = −k ġ⁻. @pre ġ⁻ < 0, 0 ≤ k ≤ 1.
double single_impulse(const ContactRow& contact, const Vector6d& inverse_mass);

struct ImpulseSolution {
  std::vector<double> impulses_kNs;            // one per contact, ≥ 0
  Vector6d velocity_change = Vector6d::Zero();  // Δq̇ = M⁻¹ Gᵀ I
  bool exact = true;                            // false when the iterative fallback was used
};

/// Contacts on one floor pair at one instant, solved together as the linear complementarity
/// problem w = ġ⁻ + W I − e ≥ 0, I ≥ 0, Iᵢ wᵢ = 0 with W = G M⁻¹ Gᵀ and e_i = −k min(ġ⁻_i, 0)
/// (restitution acts on approaching contacts; the others only may not start to approach).
/// For one approaching contact this is single_impulse(). Exact by active-set enumeration up to
/// 12 contacts, projected Gauss–Seidel beyond.
ImpulseSolution solve_impulses(const std::vector<ContactRow>& contacts, const Vector6d& inverse_mass);

struct LcpSolution {
  Eigen::VectorXd x;      // ≥ 0
  Eigen::VectorXd w;      // W x + offset ≥ 0, xᵢ wᵢ = 0
  bool exact = true;      // false when the iterative fallback was used
};

/// The linear complementarity problem w = W x + offset ≥ 0, x ≥ 0, xᵢ wᵢ = 0 for a symmetric
/// positive semi-definite W: by active-set enumeration (sparsest solution first) up to 12
/// unknowns, projected Gauss–Seidel beyond. @pre W square, offset of the same size.
LcpSolution solve_lcp(const Eigen::MatrixXd& w_matrix, const Eigen::VectorXd& offset);

/// Kinetic energy ½ q̇ᵀ M q̇ of the floor pair (kJ).
double kinetic_energy(const Vector6d& velocities, const Vector6d& inverse_mass);

}  // namespace pounding::contact
