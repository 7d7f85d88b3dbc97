#pragma once
// Impact law: instantaneous, frictionless, Newton restitution (docs/model.md §6). Pure functions on
// a group of slabs, whose velocities are stacked (u̇, v̇, φ̇) slab by slab: the two slabs of one
// floor pair (six velocities, building 1's slab first), or every slab of a row that one instant's
// contacts join (a middle building's slab struck from both sides).

#include <Eigen/Core>
#include <vector>

#include "pounding/input_error.hpp"

namespace pounding::contact {

/// The coefficients of restitution Newton's law admits: 0 (plastic) to 1 (elastic). The scene's
/// [contact] row and the solvers' own preconditions check against this one declaration.
inline constexpr Range kRestitutionRange{0.0, 1.0};

using Vector6d = Eigen::Matrix<double, 6, 1>;
using RowVector6d = Eigen::Matrix<double, 1, 6>;

/// (1/m₁, 1/m₁, 1/J₁, 1/m₂, 1/m₂, 1/J₂) of the two slabs of one floor.
Vector6d inverse_mass(double mass1_t, double polar1_tm2, double mass2_t, double polar2_tm2);

/// One contact of an impact: ġ = jacobian · q̇ over the group's velocities (3 per slab).
struct ContactRow {
  Eigen::RowVectorXd jacobian;
  double gap_rate_mps = 0.0;  // ġ⁻, before the impact
  double restitution = 0.5;   // k ∈ [0, 1] for this contact
};

/// Single contact, the paper's law: a = G M⁻¹ Gᵀ, I = (1 + k)(−ġ⁻)/a (kN·s), Δq̇ = M⁻¹ Gᵀ I.
/// Gives ġ⁺ = −k ġ⁻. @pre ġ⁻ < 0, 0 ≤ k ≤ 1.
double single_impulse(const ContactRow& contact, const Eigen::VectorXd& inverse_mass);

struct ImpulseSolution {
  std::vector<double> impulses_kNs;  // one per contact, ≥ 0
  Eigen::VectorXd velocity_change;   // Δq̇ = M⁻¹ Gᵀ I, over the group's velocities
  bool exact = true;                 // false when the iterative fallback was used
  double lcp_residual = 0.0;         // the fallback's residual (LcpSolution::residual)
};

/// Contacts on one group of slabs at one instant, solved together as the linear complementarity
/// problem w = ġ⁻ + W I − e ≥ 0, I ≥ 0, Iᵢ wᵢ = 0 with W = G M⁻¹ Gᵀ and e_i = −k min(ġ⁻_i, 0)
/// (restitution acts on approaching contacts; the others only may not start to approach).
/// For one approaching contact this is single_impulse(). Exact by active-set enumeration up to
/// 12 contacts, projected Gauss–Seidel beyond.
/// @pre every row and `inverse_mass` of one size (3 per slab).
ImpulseSolution solve_impulses(const std::vector<ContactRow>& contacts, const Eigen::VectorXd& inverse_mass);

struct LcpSolution {
  Eigen::VectorXd x;  // ≥ 0
  Eigen::VectorXd w;  // W x + offset ≥ 0, xᵢ wᵢ = 0
  bool exact = true;  // false when the iterative fallback was used
  /// The fallback's residual max_i |min(W_ii x_i, w_i)| / max_i |offset_i| (dimensionless; 0 when
  /// exact): how far the sweeps left the complementarity conditions, relative to the problem.
  double residual = 0.0;
};

/// The linear complementarity problem w = W x + offset ≥ 0, x ≥ 0, xᵢ wᵢ = 0 for a symmetric
/// positive semi-definite W: by active-set enumeration (sparsest solution first) up to 12
/// unknowns; beyond, split into the blocks W couples, each enumerated up to 12 unknowns, a larger
/// block by projected Gauss–Seidel swept until its residual is below 1e-12 (at most 20 000
/// sweeps; the run's statistics report every such solve and the largest residual).
/// @pre W square, offset of the same size.
LcpSolution solve_lcp(const Eigen::MatrixXd& w_matrix, const Eigen::VectorXd& offset);

/// The impulses (kN·s, of either sign) that bring every row's ġ to zero together, least squares
/// where rows depend, and their Δq̇ = M⁻¹ Gᵀ I for the group's `velocities` q̇.
/// @pre rows, `inverse_mass` and `velocities` of one size.
ImpulseSolution closing_impulses(const std::vector<Eigen::RowVectorXd>& rows, const Eigen::VectorXd& inverse_mass,
                                 const Eigen::VectorXd& velocities);

/// A contact of the group that is not held, in closing_impulses_keeping: its ġ may not fall below
/// `min_rate_mps` (m/s; its rebound after the impact, or 0: not closing).
struct KeptRow {
  Eigen::RowVectorXd jacobian;
  double min_rate_mps = 0.0;
};

/// closing_impulses for `held`, while the group's other contacts `kept` keep what the impact
/// gave them: a mixed complementarity problem, the held rows brought to ġ = 0 by impulses of
/// either sign, each kept row pushed (impulse ≥ 0) only as far as it would otherwise fall below its
/// minimum rate (the sparsest such set, by enumeration over the kept rows, least squares where
/// rows depend). Where the held rows' own closing leaves every kept row at or above its minimum
/// it is that closing, bit for bit. The impulses are held rows first, then kept ones.
/// @pre rows, `inverse_mass` and `velocities` of one size; at most 12 kept rows.
ImpulseSolution closing_impulses_keeping(const std::vector<Eigen::RowVectorXd>& held, const std::vector<KeptRow>& kept,
                                         const Eigen::VectorXd& inverse_mass, const Eigen::VectorXd& velocities);

/// Kinetic energy ½ q̇ᵀ M q̇ of the group (kJ).
double kinetic_energy(const Eigen::VectorXd& velocities, const Eigen::VectorXd& inverse_mass);

/// ġ = row · q̇ (m/s). A floor pair's six velocities are summed as Eigen sums a fixed six-vector,
/// so that two-building runs keep their bits whatever the group's storage.
double gap_rate(const Eigen::RowVectorXd& row, const Eigen::VectorXd& velocities);

}  // namespace pounding::contact
