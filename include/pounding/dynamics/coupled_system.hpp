#pragma once
// The two buildings as one first-order system, independent of any solver:
//   y = (q₁, q₂, q̇₁, q̇₂),  ẏ = A y + B a_g(t),  A = [[0, I], [−M⁻¹K, −M⁻¹C]],  B = [0; −r],
// with q_b ordered floor by floor (u, v, φ). Bouc–Wen columns (yielding_springs.hpp) append their
// hysteretic variables: y = (q, q̇, z), and the motion is no longer linear. Units: m, rad, s, t, kN.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <memory>
#include <mutex>
#include <vector>

#include "pounding/contact/candidates.hpp"
#include "pounding/contact/gap.hpp"
#include "pounding/contact/impact.hpp"
#include "pounding/excitation/ground_motion.hpp"
#include "pounding/model/building.hpp"
#include "pounding/model/modal_basis.hpp"
#include "pounding/dynamics/yielding_springs.hpp"

namespace pounding::dynamics {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using ConstVectorRef = const Eigen::Ref<const VectorXd>&;
// The functions below that take SpringStates (the yielding springs' branches) default to
// nullptr: every spring elastic without slip; for buildings that do not yield it is ignored.

class CoupledSystem {
 public:
  /// `levels`: the floor pairs at a common elevation (contact::common_levels, pair by pair); every
  /// slab-to-slab candidate lies on one of them. @pre two or more buildings; level floors within
  /// their buildings.
  CoupledSystem(std::vector<model::Building> buildings, excitation::GroundMotion ground_motion,
                std::vector<contact::Level> levels, std::vector<contact::Candidate> candidates);

  int dof() const { return dof_; }
  /// 2n, plus one z per Bouc–Wen spring (springs().smooth_count()).
  int state_size() const { return 2 * dof_ + springs_.smooth_count(); }
  int building_count() const { return static_cast<int>(buildings_.size()); }
  /// Index in q of the u of `floor` (1-based) of `building` (0-based).
  int floor_index(int building, int floor) const { return offset_[building] + 3 * (floor - 1); }

  const model::Building& building(int b) const { return buildings_[b]; }
  const excitation::GroundMotion& ground_motion() const { return ground_motion_; }
  const std::vector<contact::Level>& levels() const { return levels_; }
  const std::vector<contact::Candidate>& candidates() const { return candidates_; }
  const VectorXd& mass_diagonal() const { return mass_; }
  const MatrixXd& stiffness() const { return stiffness_; }  // block-diagonal K (kN/m, kN, kN·m)
  const MatrixXd& damping() const { return damping_; }      // block-diagonal C
  /// r_c: the direction of ground-motion component c repeated per floor, size n: (cos β, sin β, 0)
  /// for H1 (c = 0), (−sin β, cos β, 0) for a pair's H2 (c = 1).
  /// @pre 0 <= component < ground_motion().component_count().
  Eigen::MatrixXd::ConstColXpr influence(int component = 0) const { return influence_.col(component); }
  /// Every r_c as a column (n × components).
  const MatrixXd& influences() const { return influence_; }
  /// Σ_c r_c a_c(t): the ground's acceleration on every DOF (m/s², zero on rotations).
  VectorXd ground_acceleration(double t) const;
  /// Building b's complete modal basis under the ground motion (model::modal_basis with b's part
  /// of influences()), built at the first call and kept, so that a run's solvers share one. Safe to
  /// call from several threads. @throws std::runtime_error as model::modal_basis (and tries
  /// again at the next call).
  const model::ModalBasis& modal_basis(int b) const;

  /// The ground motion's effective force f(t) = −M Σ_c r_c a_c(t) (kN, kN·m).
  void external_force(double t, Eigen::Ref<VectorXd> force) const;

  /// Free motion (no contact): ẏ = A y + B a_g(t), plus M⁻¹ times the yielding springs' slip
  /// forces in `springs`.
  void rhs(double t, ConstVectorRef y, Eigen::Ref<VectorXd> y_dot, const SpringStates* springs = nullptr) const;
  /// The yielding column springs (empty when every building's columns stay elastic).
  const YieldingSprings& springs() const { return springs_; }
  /// The constant Jacobian A of the free motion (with every spring elastic; 2n square, without
  /// Bouc–Wen states).
  const MatrixXd& jacobian() const { return a_matrix_; }
  /// The full Jacobian (state_size() square) of rhs with `springs` in state y, its acceleration
  /// rows `acceleration_rows` (n × 2n, as constrained_acceleration_jacobian gives them) completed
  /// by the Bouc–Wen states' rows and columns.
  void full_jacobian(ConstVectorRef y, const Eigen::SparseMatrix<double>& acceleration_rows,
                     Eigen::Ref<MatrixXd> jacobian, const std::vector<std::size_t>& held = {}) const;
  /// The Bouc–Wen states' blocks of the Jacobian (YieldingSprings::smooth_jacobian), with the
  /// contacts `held` kept closed: ∂q̈/∂z projected by P = I − M⁻¹Gᵀ W⁻¹ G, as constrained_rhs
  /// solves the hold forces after the springs' forces (rows G frozen at y).
  void smooth_jacobian(ConstVectorRef y, const std::vector<std::size_t>& held, Eigen::SparseMatrix<double>& accel_by_z,
                       Eigen::SparseMatrix<double>& z_rate_by_velocity, VectorXd& z_rate_by_z) const;

  /// Gap state of candidate `index` in state y.
  contact::GapState gap(ConstVectorRef y, std::size_t index) const;
  /// One floor's part of a gap's row G: the floor (building 0 or 1, 1-based floor), the index in q
  /// of its u, and its row over (u, v, φ).
  struct RowBlock {
    int building = 0;
    int floor = 1;
    int first = 0;
    Eigen::RowVector3d row;
  };
  /// The floors candidate `c`'s row G reads, with their rows in gap state `s`: the striking floor,
  /// the struck one and, for a column point, the column's lower floor unless it is the ground.
  struct RowBlocks {
    std::array<RowBlock, 3> blocks;
    int count = 2;
    const RowBlock* begin() const { return blocks.data(); }
    const RowBlock* end() const { return blocks.data() + count; }
  };
  RowBlocks row_blocks(const contact::Candidate& c, const contact::GapState& s) const;
  /// How deep (m) candidate `index`'s contact point, at gap state `s` in state y, lies inside
  /// the struck slab's outline as it stands in y: its distance to the nearest edge when inside, 0
  /// outside (contact::depth_inside). Unlike −g, which measures behind the struck edge's line
  /// only, it is 0 for a corner beside the slab's end, however far behind that line.
  double depth_inside_m(ConstVectorRef y, std::size_t index, const contact::GapState& s) const;
  /// g̈ (m/s²) of candidate `index` in state y moving with ẏ = y_dot: G q̈ + h.
  double gap_acceleration(ConstVectorRef y, ConstVectorRef y_dot, std::size_t index) const;
  /// The round-off of candidate `index`'s gap rate in state y (m/s): ġ is a difference of terms
  /// G_j q̇_j, and below 1e-9 of their size (plus 1e-15 m/s) a pair is neither approaching nor
  /// separating. Two identical buildings side by side close at 1e-23 m/s by rounding alone.
  double gap_rate_round_off_mps(ConstVectorRef y, std::size_t index) const;
  /// One slab: `floor` (1-based) of `building` (0-based).
  struct Slab {
    int building = 0;
    int floor = 1;
    bool operator==(const Slab&) const = default;
  };
  /// The velocities (u̇, v̇, φ̇) of `slabs` in state y, stacked in their order (3 per slab), and
  /// their inverse masses (1/m, 1/m, 1/J).
  VectorXd slab_velocities(ConstVectorRef y, const std::vector<Slab>& slabs) const;
  void add_slab_velocities(Eigen::Ref<VectorXd> y, const std::vector<Slab>& slabs, const VectorXd& change) const;
  VectorXd slab_inverse_mass(const std::vector<Slab>& slabs) const;
  /// ġ = G q̇ of candidate `c` in gap state `s` as a row over the velocities of `slabs`.
  /// @pre every floor row_blocks(c, s) reads is one of `slabs`.
  Eigen::RowVectorXd slab_row(const contact::GapState& s, const contact::Candidate& c,
                              const std::vector<Slab>& slabs) const;

  /// Motion with the contacts `held` kept closed (g̈ = −3ġ/τ − 2g/τ², a Baumgarte correction with
  /// τ = `hold_time_constant_s` that stops drift) by normal forces λ (kN, ≥ 0 pushes the slabs
  /// apart). Writes ẏ and λ (one per held contact). Dependent contacts share their force
  /// (least squares).
  void constrained_rhs(double t, ConstVectorRef y, const std::vector<std::size_t>& held, Eigen::Ref<VectorXd> y_dot,
                       Eigen::Ref<VectorXd> forces_kN, const SpringStates* springs = nullptr) const;
  /// The held contacts' forces as a complementarity problem: λ ≥ 0 (kN), the stabilised g̈ ≥ 0
  /// (m/s²), λᵢ g̈ᵢ = 0. A held contact with λ = 0 and g̈ > 0 would separate on its own: it is to
  /// be released. Unlike constrained_rhs, which keeps every held gap closed whatever the sign of
  /// its force, this decides which contacts can stay held together.
  contact::LcpSolution hold_complementarity(double t, ConstVectorRef y, const std::vector<std::size_t>& held,
                                            const SpringStates* springs = nullptr) const;
  /// The physical normal forces that would keep `held` closed (g̈ = 0, no drift correction): what
  /// decides whether a slow contact is held. `pressing[k]` says whether force k is compressive
  /// beyond round-off: its gap acceleration W_kk λ_k exceeds 1e-9 (1 + Σ|G_kj q̈_j|) m/s², the
  /// round-off of the free accelerations it balances (two identical buildings pressed together
  /// by nothing get forces of 1e-16 kN either way).
  struct PhysicalHoldForces {
    VectorXd forces_kN;
    std::vector<bool> pressing;
  };
  PhysicalHoldForces physical_hold_forces(double t, ConstVectorRef y, const std::vector<std::size_t>& held,
                                          const SpringStates* springs = nullptr) const;
  /// Jacobian of constrained_rhs with the constraint rows frozen at y: the free Jacobian with
  /// the acceleration rows projected by P = I − M⁻¹Gᵀ W⁻¹ G, plus the Baumgarte terms. Exact in
  /// the velocity rows and in the columns of floors outside the held contacts; in the contact
  /// floors' columns it leaves out the turning of G (terms carrying λ, q̈ or q̇), an error that
  /// vanishes at rest and is first order in the motion (0.15 % of ‖J‖ at 5 cm, 5 mrad, 0.5 m/s,
  /// 0.05 rad/s): enough for a Newton matrix (tests/dynamics/test_constrained_jacobian.cpp).
  void constrained_jacobian(ConstVectorRef y, const std::vector<std::size_t>& held,
                            Eigen::Ref<MatrixXd> jacobian) const;
  /// The acceleration rows [∂q̈/∂q, ∂q̈/∂q̇] (n × 2n) of constrained_jacobian(), sparse: the same
  /// terms in O(n + k²) work and storage for k held contacts (K and C couple only a storey's two
  /// floors; the projection has rank k and touches only the held floors' neighbourhoods).
  /// The yielding springs' tangent (YieldingSprings::add_tangent_rows) is included.
  void constrained_acceleration_jacobian(ConstVectorRef y, const std::vector<std::size_t>& held,
                                         Eigen::SparseMatrix<double>& rows,
                                         const SpringStates* springs = nullptr) const;

  /// W = G M⁻¹ Gᵀ (1/t) of candidate `index` in state y: the inverse of the pair's effective mass
  /// along the normal, 1/m₁ + 1/m₂ with each slab's m = 1/(1/m + h²/J), h the lever arm ρ × n.
  double normal_inverse_mass(ConstVectorRef y, std::size_t index) const;
  /// Adds a compliant contact force `force_kN` (> 0 pushes the slabs apart) of candidate `index`
  /// along the struck edge's normal, with its moments about both CMs, to the accelerations of ẏ.
  void add_contact_force(ConstVectorRef y, std::size_t index, double force_kN, Eigen::Ref<VectorXd> y_dot) const;
  /// Adds the Jacobian of the force F = −k g − c ġ of candidate `index` (k kN/m, c kN·s/m) to
  /// the acceleration rows (n × 2n) of constrained_acceleration_jacobian(): −M⁻¹GᵀG k in ∂q̈/∂q,
  /// −M⁻¹GᵀG c in ∂q̈/∂q̇, with the row G frozen at y (as in constrained_jacobian: the turning of
  /// G, terms carrying F or q̇, is left out).
  void add_contact_force_jacobian(ConstVectorRef y, std::size_t index, double stiffness_kN_per_m,
                                  double damping_kNs_per_m, Eigen::SparseMatrix<double>& rows) const;

  /// The sway shear (kN) of column `column` (0-based) of building b's storey `storey` along x (0)
  /// or y (1) in state y: its spring's force where b's columns yield, else k d with its elastic
  /// stiffness k and its drift d = t·(q_storey − q_storey−1) (the rows of T, model/building.hpp).
  /// Positive when the storey's top has moved along +x (+y) relative to its bottom.
  /// @pre building b uses columns.
  double column_sway_shear_kN(ConstVectorRef y, int building, int storey, std::size_t column, int direction,
                              const SpringStates* springs = nullptr) const;

  /// Energies (kJ) and powers (kW) of the relative motion.
  double kinetic_energy(ConstVectorRef y) const;
  /// With `springs`: the energy the yielding springs store (YieldingSprings::stored_energy_change).
  double strain_energy(ConstVectorRef y, const SpringStates* springs = nullptr) const;
  double damping_power(ConstVectorRef y) const;          // q̇ᵀ C q̇ ≥ 0
  double input_power(double t, ConstVectorRef y) const;  // −q̇ᵀ M Σ_c r_c a_c(t)

  static constexpr double hold_time_constant_s = 1e-2;

 private:
  contact::SlabMotion slab(ConstVectorRef y, int building, int floor) const;
  /// G of candidate `index` over all n velocities.
  Eigen::RowVectorXd full_row(ConstVectorRef y, std::size_t index) const;
  /// Rows G (one per held contact, over all n velocities) and g̈'s velocity-only part.
  /// With `drift_correction` false, the bias is the curvature term alone.
  void constraint_rows(ConstVectorRef y, const std::vector<std::size_t>& held, MatrixXd& rows, VectorXd& bias,
                       bool drift_correction = true) const;
  /// M⁻¹Gᵀ G [k, c] (n × 2n, 36 entries): the acceleration rows of the force −k g − c ġ of
  /// candidate `index` with its row G frozen at y, to be subtracted.
  Eigen::SparseMatrix<double> contact_force_rows(ConstVectorRef y, std::size_t index, double stiffness_kN_per_m,
                                                 double damping_kNs_per_m) const;

  /// The bases modal_basis() built. Behind a pointer because std::once_flag neither copies nor
  /// moves; copies of the system share them, as they have the same buildings and influence.
  struct ModalBases {
    explicit ModalBases(std::size_t count) : built(count), basis(count) {}
    std::vector<std::once_flag> built;
    std::vector<model::ModalBasis> basis;
  };

  std::vector<model::Building> buildings_;
  excitation::GroundMotion ground_motion_;
  std::vector<contact::Level> levels_;
  std::vector<contact::Candidate> candidates_;
  int dof_ = 0;
  std::vector<int> offset_;  // per building: the index in q of its floor 1's u
  VectorXd mass_;            // diagonal of M, size n
  MatrixXd stiffness_;       // block-diagonal K
  MatrixXd damping_;         // block-diagonal C
  MatrixXd influence_;       // r_c as columns: (cos β, sin β, 0) per floor, and a pair's (−sin β, cos β, 0)
  MatrixXd a_matrix_;        // A
  // K and C couple only a storey's two floors: the free motion and the energies use them sparse,
  // O(n) instead of the dense A's O(n²).
  Eigen::SparseMatrix<double> stiffness_sparse_, damping_sparse_;
  Eigen::SparseMatrix<double> acceleration_rows_;  // −M⁻¹[K, C]: A's lower half, sparse
  YieldingSprings springs_;
  std::shared_ptr<ModalBases> modal_bases_ = std::make_shared<ModalBases>(buildings_.size());
};

}  // namespace pounding::dynamics
