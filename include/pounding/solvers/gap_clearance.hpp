#pragma once
// How long every gap provably stays open in free flight: a rigorous bound on how fast a gap can
// close, from each mode's energy amplitude and the mode shapes' rows at the contact floors. Over
// a window this long no gap can cross zero, dip below it and recover, or graze it, so the loop
// may step across the window in one step with nothing to examine inside (docs/model.md, "Steps
// far from contact", gives the derivation).
//
// Mode k of a building (model/modal_basis.hpp), η̈ + 2ζω η̇ + ω² η = −Γ a_g, has the amplitude
// A = √(η̇² + ω² η²), whose rate is η̇ (−Γ a_g − 2ζω η̇)/A ≤ |Γ a_g| for ζ ≥ 0. Over a window of
// length τ with |a_g| ≤ a: A ≤ Â = A(t) + |Γ| a τ, so |η̇| ≤ Â and |η| ≤ Â/ω; a floor DOF j then
// has |q̇_j| ≤ Σ_k |Φ_jk| Â_k and |q_j| ≤ Σ_k |Φ_jk| Â_k/ω_k. The gap's rate (contact/gap.hpp)
//   ġ = n·(u̇, v̇)_A + (ρ_A × n) φ̇_A − n·(u̇, v̇)_B − ((P − C_B) × n) φ̇_B,   |n| = 1,
// with |ρ_A| = r_A (the vertex's rest distance from A's CM: the slab is rigid) and
// |P − C_B| ≤ r_AB + |(u, v)_A − (u, v)_B| + r_A |φ_A| (r_AB its rest distance from B's CM;
// |R(φ) − I| ≤ |φ|), is bounded by a constant L over the window, and g(t + s) ≥ g(t) − L s.

#include <Eigen/Core>
#include <vector>

#include <limits>

#include "pounding/dynamics/coupled_system.hpp"

namespace pounding::solvers {

class GapClearance {
 public:
  /// @throws std::runtime_error if a building's damping is not classical (model::modal_basis).
  explicit GapClearance(const dynamics::CoupledSystem& system);

  /// The longest window [t, t + τ], τ ≤ horizon_s (s), over which every candidate i with
  /// watched[i] provably keeps g_i > clearance_m, for the free motion from y = (q, q̇) at t
  /// under any ground motion with each component's |a_c| ≤ peak_accel_mps2[c] inside the window; 0 when some
  /// watched gap is not above clearance_m now. Also a lower bound when the window is shorter
  /// than horizon_s (to within 2⁻²⁴ of the horizon, by bisection).
  /// @pre watched.size() == candidates, horizon_s ≥ 0, peak_accel_mps2 ≥ 0; no contact force
  ///   acts in the window (free flight).
  double open_time_s(const Eigen::Ref<const Eigen::VectorXd>& y, const std::vector<bool>& watched, double clearance_m,
                     double horizon_s, const Eigen::Vector2d& peak_accel_mps2) const;
  /// The shortest damped period (s) among every building's oscillating modes (ζ < 1; infinity if
  /// none oscillates).
  double shortest_damped_period_s() const { return shortest_damped_period_s_; }

 private:
  struct BuildingModes {
    int offset = 0;              // index in q of the building's first DOF
    Eigen::MatrixXd projection;  // Φᵀ M: η = projection · q_b
    Eigen::VectorXd omega_rad_s;
    Eigen::MatrixXd participation;      // |Γ| per mode, a column per ground-motion component
    std::vector<int> floors;            // contact floors (1-based), in the order of the rows below
    Eigen::MatrixXd rate_rows;          // |Φ_jk| over the contact floors' (u, v, φ): |q̇_j| ≤ rate_rows Â
    Eigen::MatrixXd displacement_rows;  // |Φ_jk| / ω_k: |q_j| ≤ displacement_rows Â
    // The rows times |Γ_c|, one per component: Â's growth per unit a_c τ.
    std::vector<Eigen::VectorXd> rate_growth, displacement_growth;
  };
  struct Pair {
    int striking = 0, struck = 0;          // buildings
    int striking_row = 0, struck_row = 0;  // first bound row of the candidate's floor in each
    double arm_striking_m = 0.0;           // r_A
    double arm_struck_m = 0.0;             // r_AB
  };

  std::vector<BuildingModes> buildings_;
  std::vector<Pair> pairs_;
  double shortest_damped_period_s_ = std::numeric_limits<double>::infinity();
  const dynamics::CoupledSystem& system_;
  // Scratch for open_time_s (no allocation per call).
  mutable std::vector<Eigen::VectorXd> amplitude_, eta_, eta_rate_, rate_bound_, rate_growth_, displacement_bound_,
      displacement_growth_;
};

}  // namespace pounding::solvers
