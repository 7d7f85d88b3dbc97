#pragma once
// Collects what a run reports from its states: peaks, the sampled history and the energy
// integrals. Shared by every solution path so their outputs compare column for column. With a
// RunSink the history rows and impacts go to the sink as they come and the history is not kept.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "pounding/dynamics/coupled_system.hpp"
#include "pounding/solvers/integrator.hpp"
#include "pounding/solvers/run_result.hpp"
#include "pounding/solvers/run_sink.hpp"

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

/// The free motion's dynamics (no contact forces between impacts), for the fixed-step path.
RecordedDynamics free_dynamics(const dynamics::CoupledSystem& system);

/// The columns of history.csv for the levels `history_levels` (1-based; empty: every level),
/// `t_s` first. Per level, building 1's slab then building 2's, each: u_m, v_m, phi_rad, the
/// contact vertices' vtxN_dx_m, the CM's absolute accelerations ax_abs_mps2, ay_abs_mps2 and
/// phi_ddot_radps2, the storey drift ratios drift_x and drift_y at the CM and cN_drift_x,
/// cN_drift_y at each slab corner N. @pre indices valid.
std::vector<std::string> history_columns(const dynamics::CoupledSystem& system, const std::vector<int>& history_levels);

class Recorder {
 public:
  /// Writes the components `indices` of the state at t into y (others may be left stale): a
  /// cheaper `at` for the peaks, which read two to four components each.
  using ComponentsAt = std::function<void(double t, const std::vector<int>& indices, dynamics::VectorXd& y)>;

  /// History of the levels `history_levels` (1-based indices into system.levels(); empty: every
  /// level), each as building 1's floor then building 2's. `sink` (may be null; must outlive the
  /// recorder) receives the columns at the first row, then every row, contact force and impact;
  /// the history in the result then has its columns and no rows. @pre indices valid.
  Recorder(const dynamics::CoupledSystem& system, RecordedDynamics dynamics, const std::vector<int>& history_levels,
           double history_interval_s, RunSink* sink = nullptr);

  /// A state the run passes through (step ends, samples, events): updates the peaks (the
  /// accelerations with the dynamics of the stretch that starts or goes on at t).
  void observe(double t, const dynamics::VectorXd& y);
  /// Writes a history row at t (also observes it).
  void sample(double t, const dynamics::VectorXd& y);
  /// Advances over (t_a, t_b] of a smooth stretch whose states `at(t)` returns and whose end
  /// state is `y_b`: history samples that fall inside, the peaks (turning points inside located
  /// on `at` to round-off, so a peak does not depend on where the steps end; for accelerations
  /// the rate is exact in free motion and a central difference on `at` while contact forces
  /// act), and the energy integrals (3-point Gauss–Legendre, or `closed_form` when given: the
  /// integrator's own, for a stretch without contact forces). `constraint_power(t, y)` is the
  /// power of sustained-contact forces (kW). `components_at`, when given, locates the peaks of
  /// displacements and drifts instead of `at` (accelerations need the whole state).
  void advance(double t_a, double t_b, const dynamics::VectorXd& y_b,
               const std::function<dynamics::VectorXd(double)>& at,
               const std::function<double(double, const dynamics::VectorXd&)>& constraint_power,
               const std::optional<StretchEnergy>& closed_form = std::nullopt,
               const ComponentsAt& components_at = {});
  void add_impact_loss(double energy_kJ) { energy_.impact_loss_kJ += energy_kJ; }
  /// Passes the impacts appended to `impacts` since the last call to the sink (if any). Call it
  /// once an event's records are final.
  void stream_new_impacts(const std::vector<ImpactRecord>& impacts);
  /// HHT: energy a step's update removed (kJ), see HhtStepper::algorithmic_dissipation.
  void add_algorithmic_dissipation(double energy_kJ) { energy_.algorithmic_dissipation_kJ += energy_kJ; }

  /// Moves the collected peaks, history and energy (with the final state's energies) into
  /// `result`, and streams any impact of `result` not streamed yet.
  void finish(const dynamics::VectorXd& final_state, RunResult& result);

 private:
  void append_row(double t, const dynamics::VectorXd& y);
  bool free_motion() const;
  /// q̈ + r a_g (m/s², rad/s²) of every DOF at (t, y), ordered as q.
  dynamics::VectorXd absolute_accelerations(double t, const dynamics::VectorXd& y) const;
  /// Their rates (m/s³, rad/s³) in free motion, given the accelerations `accel` at (t, y).
  dynamics::VectorXd free_acceleration_rates(double t, const dynamics::VectorXd& y, const dynamics::VectorXd& accel) const;
  /// y_a, y_b, a_a, a_b: the states and accelerations at the stretch's ends.
  void locate_acceleration_peaks(double t_a, double t_b, const dynamics::VectorXd& y_a, const dynamics::VectorXd& y_b,
                                 const dynamics::VectorXd& a_a, const dynamics::VectorXd& a_b,
                                 const std::function<dynamics::VectorXd(double)>& at);
  /// Every storey drift ratio at y and its rate (1/s), at drift_index(building, floor, slot); slot
  /// 0, 1: x, y at the CM; 2k + 2, 2k + 3: x, y at slab corner k + 1.
  struct Drifts {
    dynamics::VectorXd value, rate;
  };
  Drifts storey_drifts(const dynamics::VectorXd& y) const;
  /// One of them (for root finding, where the table would be wasted).
  struct Drift {
    double value, rate;
  };
  Drift storey_drift(const dynamics::VectorXd& y, int building, int floor, std::size_t slot) const;
  std::size_t drift_slots(int building) const;
  std::size_t drift_index(int building, int floor, std::size_t slot) const;
  void locate_drift_peaks(double t_a, double t_b, const Drifts& d_a, const Drifts& d_b, const dynamics::VectorXd& y_b,
                          const std::function<dynamics::VectorXd(double)>& at, const ComponentsAt& components_at);
  void observe(double t, const dynamics::VectorXd& y, const dynamics::VectorXd& accel, const Drifts& drifts);
  void locate_peaks(double t_a, double t_b, const dynamics::VectorXd& y_a, const dynamics::VectorXd& y_b,
                    const std::function<dynamics::VectorXd(double)>& at, const ComponentsAt& components_at);
  /// Updates `peak` at the turning point of `value` inside (t_a, t_b), if its rate changes sign
  /// there and it can beat the peak.
  template <class Value, class Rate>
  void locate_peak(Peak& peak, double t_a, double t_b, const dynamics::VectorXd& y_a, const dynamics::VectorXd& y_b,
                   const std::function<dynamics::VectorXd(double)>& at, const Value& value, const Rate& rate);

  const dynamics::CoupledSystem& system_;
  RecordedDynamics dynamics_;
  std::vector<contact::Level> history_levels_;
  double interval_s_;
  double next_sample_s_;
  std::array<std::size_t, 3> drift_offset_{};  // building 1's drifts from [0], building 2's from [1], count [2]
  std::array<std::vector<model::Point2>, 2> vertices_;  // contact vertices per building, by outline number
  std::vector<BuildingPeaks> peaks_;
  History history_;
  EnergyAudit energy_;
  RunSink* sink_;
  std::optional<double> last_row_t_s_;  // a row is written once per instant
  std::optional<double> observed_t_s_;  // the last observed instant and its accelerations
  dynamics::VectorXd observed_accel_;
  std::size_t impacts_streamed_ = 0;
};

/// Vertices of `building`'s slab that take part in some candidate (as vertex or edge end).
std::vector<model::Point2> contact_vertices(const std::vector<contact::Candidate>& candidates, int building);

}  // namespace pounding::solvers
