#pragma once
// The member forces of a run (OutputSelection::member_forces; docs/model.md §2c): each storey's
// restoring shear V_x, V_y (kN) and torque T (kN·m, about the building's CM), the force its
// columns (or its storey matrix) exert on the floor above, and each column's shears V_x, V_y (kN)
// and end moments M = V H / 2 (kN·m: a column between rigid slabs bends in double curvature).
// A yielding column's shear is its spring's force (YieldingSprings::force_kN), an elastic one's
// k times its drift. Neither damping nor P-Δ is a member force: the storey shear is the columns'
// share of K q, without the Rayleigh term C q̇ and the geometric stiffness.
// Signs: V has the sign of the drift that calls it up (+ for the floor above displaced along +x
// or +y from the one below, which the columns then pull back), T that of the twist Δφ.

#include <string>
#include <vector>

#include "pounding/dynamics/coupled_system.hpp"
#include "pounding/solvers/run_result.hpp"

namespace pounding::solvers {

/// The quantities one run's member forces hold, in history.csv's column order: per building,
/// per storey, the storey's V_x, V_y, T, then per column V_x, V_y, M_x, M_y (M_x: the end
/// moment of the bending under the sway along x, about the plan's y axis).
class MemberForces {
 public:
  /// @pre `system` outlives this.
  explicit MemberForces(const dynamics::CoupledSystem& system);

  const std::vector<MemberForce>& quantities() const { return quantities_; }
  /// history.csv's column names, one per quantity ("B1_s2_Vx_kN", "B1_s2_col3_Mx_kNm").
  std::vector<std::string> column_names() const;
  /// The quantities at state y into `out` (size quantities().size()); `springs`: the yielding
  /// springs' states (null when none yields).
  void measure(const dynamics::VectorXd& y, const dynamics::SpringStates* springs,
               Eigen::Ref<Eigen::VectorXd> out) const;

 private:
  /// A column along one direction, or a matrix storey's spring along x or y: force F along the
  /// row t over the storey's (Δu, Δv, Δφ).
  struct Member {
    double stiffness_kN_per_m = 0.0;
    Eigen::RowVector3d row;
    std::optional<std::size_t> spring;  // its yielding spring, if it yields
    int out = -1;                       // its V's index in the output (columns); -1: a storey spring
    double half_height_m = 0.0;         // H/2: its end moment per kN of shear (columns)
  };
  struct Storey {
    int upper = 0, lower = -1;  // first index of the floors' (u, v, φ) in y; -1: the ground
    Eigen::Matrix3d remainder;  // the storey's stiffness beside its members' (a matrix's torsion)
    std::vector<Member> members;
    int out = 0;  // V_x's index in the output
  };

  std::vector<MemberForce> quantities_;
  std::vector<Storey> storeys_;
  const dynamics::YieldingSprings& springs_;
};

}  // namespace pounding::solvers
