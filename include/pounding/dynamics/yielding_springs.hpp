#pragma once
// The yielding column springs of the buildings (model::HystereticLaw, docs/model.md
// "Yielding columns"): one spring per column, storey and direction (x, y) of every building whose
// columns yield. Spring j's drift d_j = t_j · q is the column's top-to-bottom displacement along
// its direction (small rotations, as the stiffness: T = [[1, 0, −Δy], [0, 1, Δx]] per floor).
//
// A bilinear spring is split into a linear part α k, which stays in K, and an elastic–perfectly-
// plastic part of stiffness (1 − α) k with slip s_j: its force (1 − α) k (d_j − s_j) never exceeds
// (1 − α) k d_y. K keeps the initial stiffness (and so does the Rayleigh damping C = a0 M + a1 K,
// as codes do), and the slips enter the motion as the force Σ (1 − α) k s_j t_j:
//   M q̈ + C q̇ + K q = −M r a_g + Σ_j (1 − α) k_j s_j t_j.
// Between events each spring is on one branch: elastic (s_j constant) or yielding up or down
// (s_j = d_j ∓ d_y, the force constant), so the motion is piecewise linear and its branch
// changes are root functions ("witnesses") the integrator locates:
//   elastic:    d_y − |d_j − s_j|   falls where the spring yields;
//   yielding ±: ±ḋ_j                falls where it unloads.
// A Bouc–Wen spring (model::HystereticLaw::Kind::bouc_wen) is smooth instead: its plastic part's
// force is (1 − α) k d_y z_j, i.e. its slip is s_j = d_j − d_y z_j, with z_j an extra ODE state
// after (q, q̇) in y (z_index) obeying ż = (ḋ/d_y)(A − |z|ⁿ(β sgn(ḋ z) + γ)); it has no branches
// and no witness. Its part stores ½ (1 − α) k d_y² z²/A and dissipates the rest of its work at
// the rate dissipation_power() ≥ 0.
// A degrading (IMK) spring (model::HystereticLaw::Kind::imk_peak_oriented, dynamics/imk_law.hpp) is
// piecewise linear too, with α = 0 and its force on the line of its present branch (SpringBranch::
// line, SpringState::line): F = F_0 + K_b (d − d_0), so its slip is s = d − F/k and its slip force
// (k − K_b) moves with q; its witness is the nearest end of the branch, min(d − lower, upper − d),
// and, on a loading branch, sign · ḋ. Its law's memory (peaks, backbone, energies) is the
// solver's (solvers::YieldStates), which sets the line at each branch change. It stores ½F²/K_u.
// A bilinear spring whose column has failed in shear and lost its stiffness (failed branch,
// YieldingSpring::loses_stiffness) carries no force: its slip is d/(1 − α), so that its slip force
// k d t cancels its share of K q; it has no witness and stores nothing.
// Units: m, s, kN.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "pounding/dynamics/imk_law.hpp"
#include "pounding/model/building.hpp"

namespace pounding::dynamics {

enum class SpringBranch { elastic, yielding_up, yielding_down, failed, line };

/// One spring's discrete state: its branch, its slip s (m; the plastic drift) while elastic, and
/// a degrading spring's line (SpringBranch::line).
struct SpringState {
  SpringBranch branch = SpringBranch::elastic;
  double slip_m = 0.0;
  LineBranch line{};
};

/// The branch and slip of every yielding spring, one per spring: a run's discrete state.
using SpringStates = std::vector<SpringState>;

/// Bouc–Wen's shape parameters (model::HystereticLaw): A, β, γ and the exponent n.
struct BoucWenShape {
  double a = 1.0, beta = 0.5, gamma = 0.5, n = 2.0;
};

struct YieldingSpring {
  int building = 0;                 // 0-based in the scene
  int storey = 1;                   // 1-based: joins floor storey − 1 (the ground for 1) and floor storey
  int direction = 0;                // 0: x, 1: y
  std::string column;               // the column's scene key ("columns[3]", "column_grid[1] x[2] y[1]")
  std::size_t column_index = 0;     // 0-based in its building's column list
  double stiffness_kN_per_m = 0.0;  // initial k
  double hardening_ratio = 0.0;     // α
  double yield_drift_m = 0.0;       // d_y
  double storey_height_m = 0.0;     // H of its storey
  /// d = Σ coefficients[i] · q[indices[i]] (the lower floor's terms absent for storey 1).
  std::vector<int> indices;
  std::vector<double> coefficients;
  /// A smooth (Bouc–Wen) spring: its shape, and the index in y of its z. Empty: bilinear.
  std::optional<BoucWenShape> bouc_wen;
  int z_index = -1;
  /// A degrading (IMK) spring's law (K_e = k, F_y = k d_y on both sides). Empty: not degrading.
  std::optional<ImkParameters> imk;
  double shear_capacity_kN = 0.0;  // V_c of its column along its direction; 0: not checked
  bool loses_stiffness = false;    // on reaching V_c its column loses its stiffness (failed branch)

  /// (1 − α) k (kN/m): the stiffness of the elastic–perfectly-plastic part.
  double plastic_stiffness() const { return (1.0 - hardening_ratio) * stiffness_kN_per_m; }
  /// Its force (kN) at drift d and slip s: α k d + (1 − α) k (d − s) = k (d − (1 − α) s).
  double force_kN(double drift_m, double slip_m) const {
    return stiffness_kN_per_m * (drift_m - (1.0 - hardening_ratio) * slip_m);
  }
};

class YieldingSprings {
 public:
  YieldingSprings() = default;
  /// The springs of the buildings whose hysteresis yields; `offsets[b]` is building b's first
  /// index in q. @pre the buildings are assembled (make_building: frame factor resolved).
  YieldingSprings(const std::vector<model::Building>& buildings, const std::vector<int>& offsets);

  bool empty() const { return springs_.empty(); }
  std::size_t size() const { return springs_.size(); }
  const YieldingSpring& operator[](std::size_t j) const { return springs_[j]; }
  const std::vector<YieldingSpring>& all() const { return springs_; }
  /// The spring of column `column` (0-based) of building `building`'s storey `storey` along x (0)
  /// or y (1); none when that building's columns do not yield. A storey given as a matrix: its
  /// storey spring for `column` 0.
  std::optional<std::size_t> index_of(int building, int storey, std::size_t column, int direction) const;
  /// The number of smooth (Bouc–Wen) springs: the ODE states z after (q, q̇) in y.
  int smooth_count() const { return smooth_count_; }
  /// n, the number of displacements: y = (q, q̇, z).
  int dof() const { return dof_; }

  /// d_j (m) for displacements q, or ḋ_j (m/s) for velocities q̇.
  double drift(const Eigen::Ref<const Eigen::VectorXd>& q, std::size_t j) const;
  /// s_j (m) in state y: the stored slip while elastic, d_j ∓ d_y while yielding; d_j − d_y z_j
  /// for a smooth spring.
  double slip(const Eigen::Ref<const Eigen::VectorXd>& y, const SpringStates& states, std::size_t j) const;
  /// Adds Σ (1 − α) k s_j t_j (kN, kN·m) in state y to `force` (size n).
  void add_slip_force(const Eigen::Ref<const Eigen::VectorXd>& y, const SpringStates& states,
                      Eigen::Ref<Eigen::VectorXd> force) const;
  /// Writes the smooth springs' ż (1/s) in state y into `z_dot` (size smooth_count()).
  void hysteretic_rates(const Eigen::Ref<const Eigen::VectorXd>& y, Eigen::Ref<Eigen::VectorXd> z_dot) const;
  /// Adds the yielding springs' ∂(slip force)/∂q = (1 − α) k t tᵀ, scaled by M⁻¹ (`inverse_mass`),
  /// to the ∂q̈/∂q block of `rows` (n × 2n): the springs on a yielding branch, and every smooth one.
  void add_tangent_rows(const SpringStates& states, const Eigen::VectorXd& inverse_mass,
                        Eigen::SparseMatrix<double>& rows) const;
  /// The smooth springs' blocks of the Jacobian in state y: ∂q̈/∂z = −M⁻¹ (1 − α) k d_y t
  /// (n × m), ∂ż/∂q̇ = Φ t/d_y (m × n) and the diagonal ∂ż/∂z = (ḋ/d_y) Φ'(z) (m), with
  /// Φ = A − |z|ⁿ (β sgn(ḋ z) + γ), whose sign term is piecewise constant.
  void smooth_jacobian(const Eigen::Ref<const Eigen::VectorXd>& y, const Eigen::VectorXd& inverse_mass,
                       Eigen::SparseMatrix<double>& accel_by_z, Eigen::SparseMatrix<double>& z_rate_by_velocity,
                       Eigen::VectorXd& z_rate_by_z) const;
  /// F_j (kN): spring j's force in state y (YieldingSpring::force_kN at its drift and slip).
  double force_kN(const Eigen::Ref<const Eigen::VectorXd>& y, const SpringStates& states, std::size_t j) const;
  /// Spring j's witness in y = (q, q̇) (see the header comment); 1 for a smooth spring.
  double witness(const Eigen::Ref<const Eigen::VectorXd>& y, const SpringStates& states, std::size_t j) const;
  /// The energy (kJ) the slips take out of ½ qᵀ K q: the springs store
  /// ½ qᵀ K q − Σ (1 − α) k s_j d_j + ½ Σ (1 − α) k s_j², a smooth one ½ α k d² + ½ (1 − α) k d_y² z²/A.
  double stored_energy_change(const Eigen::Ref<const Eigen::VectorXd>& y, const SpringStates& states) const;
  /// The rate (kW) at which smooth spring j dissipates energy in state y:
  /// (1 − α) k d_y ḋ z |z|ⁿ (β sgn(ḋ z) + γ)/A ≥ 0; 0 for a bilinear spring (it dissipates at its
  /// events, YieldStates).
  double dissipation_power(const Eigen::Ref<const Eigen::VectorXd>& y, std::size_t j) const;

 private:
  std::vector<YieldingSpring> springs_;
  /// Per building: the index of its first spring (none: its columns do not yield) and its number
  /// of columns; its springs run storey by storey, column by column, x then y.
  std::vector<std::optional<std::size_t>> first_spring_;
  std::vector<std::size_t> column_count_;
  int dof_ = 0;           // n: y = (q, q̇, z)
  int smooth_count_ = 0;  // the springs with a z
};

}  // namespace pounding::dynamics
