#pragma once
// What the outputs read from a state besides the state itself: the floors' absolute
// accelerations (with their exact rate in free motion) and every storey drift ratio (at the CM
// and at each slab corner, with its rate), evaluated at an Instant once and shared by the history
// rows and the peaks. Also the contact vertices each building reports, by outline number.

#include <array>
#include <functional>
#include <optional>
#include <vector>

#include "pounding/dynamics/coupled_system.hpp"
#include "pounding/model/polygon.hpp"

namespace pounding::solvers {

/// A contact carrying a normal force (kN, > 0 pushes the slabs apart): candidate index and force.
struct ContactForce {
  std::size_t candidate = 0;
  double force_kN = 0.0;
};

/// What the solver integrates at a state, so the recorder's accelerations and contact forces are
/// the solver's own, not a copy of its force laws.
struct RecordedDynamics {
  /// ẏ at (t, y) with the contact forces and held contacts of the present stretch.
  std::function<void(double, const dynamics::VectorXd&, Eigen::Ref<dynamics::VectorXd>)> derivative;
  /// The contacts carrying a force at (t, y); empty function: none ever do (impulses only).
  std::function<std::vector<ContactForce>(double, const dynamics::VectorXd&)> contact_forces;
  /// True while no contact force acts, so ẏ = A y + B a_g (the system's free motion), whose
  /// accelerations' rates the recorder then has exactly; empty function: always.
  std::function<bool()> free_motion;
};

/// Every storey drift ratio at a state and its rate (1/s), at RunKinematics::drift_index(building,
/// floor, slot); slot 0, 1: x, y at the CM; 2k + 2, 2k + 3: x, y at slab corner k + 1.
struct Drifts {
  dynamics::VectorXd value, rate;
};

/// What the outputs computed at one instant: the end of one stretch is the start of the next,
/// so nothing is computed twice. Accelerations and drifts are kept when a peak group or the
/// history needs them; the accelerations' rate only where it was had exactly.
struct Instant {
  std::optional<double> t_s;
  dynamics::VectorXd y, accel;  // accel: q̈ + r a_g with the dynamics going on from t_s
  Drifts drifts;
  dynamics::VectorXd accel_rate;
  bool rate_known = false;
};

class RunKinematics {
 public:
  /// @pre `system` outlives this.
  RunKinematics(const dynamics::CoupledSystem& system, RecordedDynamics dynamics);

  const dynamics::CoupledSystem& system() const { return system_; }
  const RecordedDynamics& dynamics() const { return dynamics_; }
  /// True while no contact force acts (RecordedDynamics::free_motion).
  bool free_motion() const { return !dynamics_.free_motion || dynamics_.free_motion(); }

  /// Fills `into` at (t, y), with the accelerations and drifts when asked.
  void measure(double t, const dynamics::VectorXd& y, bool accelerations, bool drifts, Instant& into) const;
  /// q̈ + r a_g (m/s², rad/s²) of every DOF at (t, y), ordered as q, into `accel`.
  void absolute_accelerations(double t, const dynamics::VectorXd& y, dynamics::VectorXd& accel) const;
  /// Their rates (m/s³, rad/s³) in free motion, given the accelerations `accel` at (t, y).
  void free_acceleration_rates(double t, const dynamics::VectorXd& y, const dynamics::VectorXd& accel,
                               dynamics::VectorXd& rate) const;
  /// Every storey drift at y, into d.
  void storey_drifts(const dynamics::VectorXd& y, Drifts& d) const;
  /// One of them (for root finding, where the table would be wasted).
  struct Drift {
    double value, rate;
  };
  Drift storey_drift(const dynamics::VectorXd& y, int building, int floor, std::size_t slot) const;
  std::size_t drift_slots(int building) const;
  std::size_t drift_index(int building, int floor, std::size_t slot) const;

  /// Building b's vertices that take part in some candidate, ordered by their number in the slab
  /// outline (contact_vertex_numbers), as impacts and candidates name them.
  const std::vector<model::Point2>& contact_vertices(int b) const { return vertices_[b]; }
  const std::vector<int>& contact_vertex_numbers(int b) const { return vertex_numbers_[b]; }

 private:
  const dynamics::CoupledSystem& system_;
  RecordedDynamics dynamics_;
  std::vector<std::size_t> drift_offset_;  // building b's drifts from [b]; the count last
  std::vector<std::vector<model::Point2>> vertices_;
  std::vector<std::vector<int>> vertex_numbers_;
  // Scratch space of the hot path, sized once (no allocation per step).
  mutable dynamics::VectorXd y_dot_, y_ddot_;              // absolute_accelerations, free_acceleration_rates
  mutable std::vector<model::Point2> below_, below_rate_;  // storey_drifts
};

/// Vertices of `building`'s slab that take part in some candidate (as vertex or edge end).
std::vector<model::Point2> contact_vertices(const std::vector<contact::Candidate>& candidates, int building);

/// The 1-based numbers in `slab`'s outline of `points` (each one of its vertices, as candidates
/// copy them), and the points reordered by number.
std::vector<int> outline_numbers(const model::Polygon& slab, std::vector<model::Point2>& points);

/// The velocity (m/s) of a slab point given at rest, `arm` from the CM, from the slab's (u̇, v̇)
/// and φ̇; c, s: cos φ and sin φ (point_displacement's rate).
inline model::Point2 point_velocity(const model::Point2& arm, double c, double s, double u_rate, double v_rate,
                                    double phi_rate) {
  return {u_rate - phi_rate * (s * arm.x() + c * arm.y()), v_rate + phi_rate * (c * arm.x() - s * arm.y())};
}

}  // namespace pounding::solvers
