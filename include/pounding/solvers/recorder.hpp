#pragma once
// Collects what a run reports from its states: the peaks and the sampled history that its
// OutputSelection asks for, and the energy integrals (always). Shared by every solution path so
// their outputs compare column for column. With a RunSink the history rows and impacts go to the
// sink as they come and the history is not kept. Its parts: the history's columns and row values
// are declared once in history_schema.hpp, the energy integrals are EnergyBalance's
// (energy_balance.hpp); the peaks, located on the same instants the history samples, stay here.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "pounding/dynamics/coupled_system.hpp"
#include "pounding/solvers/energy_balance.hpp"
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
/// `t_s` first, then per level building 1's slab then building 2's, each with the columns of
/// history_quantities() (history_schema.hpp). @pre indices valid.
std::vector<std::string> history_columns(const dynamics::CoupledSystem& system, const std::vector<int>& history_levels);

class Recorder {
 public:
  /// Writes the components `indices` of the state at t into y (others may be left stale): a
  /// cheaper `at` for the peaks, which read two to four components each.
  using ComponentsAt = std::function<void(double t, const std::vector<int>& indices, dynamics::VectorXd& y)>;

  /// History of the levels `history_levels` (1-based indices into system.levels(); empty: every
  /// level), each as building 1's floor then building 2's, when `outputs.history`; the peak groups
  /// `outputs` asks for (the others are neither computed nor reported). `sink` (may be null; must
  /// outlive the recorder) receives the columns at the first sample (none without history), then
  /// every row, contact force and impact; the history in the result then has its columns and no
  /// rows. @pre indices valid.
  Recorder(const dynamics::CoupledSystem& system, RecordedDynamics dynamics, const std::vector<int>& history_levels,
           double history_interval_s, const OutputSelection& outputs, RunSink* sink = nullptr);

  /// Writes a history row at t (once per instant, with history) and updates the peaks at the
  /// state y, which the next stretch starts from (the run's start, or an event's state after the
  /// event, with the dynamics that go on from there).
  void sample(double t, const dynamics::VectorXd& y);
  /// Advances over (t_a, t_b] of a smooth stretch whose states `at(t)` returns and whose end
  /// state is `y_b`: history samples that fall inside, the peaks (turning points inside located
  /// on `at` to round-off, so a peak does not depend on where the steps end; for accelerations
  /// the rate is exact in free motion and a central difference on `at` while contact forces
  /// act), and the energy integrals (3-point Gauss–Legendre, or `closed_form` when given: the
  /// integrator's own, for a stretch without contact forces). `constraint_power(t, y)` is the
  /// power of sustained-contact forces (kW). `components_at`, when given, locates the peaks of
  /// displacements and drifts instead of `at` (accelerations need the whole state). The stretch
  /// starts from the state last sampled or advanced to at t_a (else from `at(t_a)`), whose
  /// quantities are not computed again.
  void advance(double t_a, double t_b, const dynamics::VectorXd& y_b,
               const std::function<dynamics::VectorXd(double)>& at,
               const std::function<double(double, const dynamics::VectorXd&)>& constraint_power,
               const std::optional<StretchEnergy>& closed_form = std::nullopt,
               const ComponentsAt& components_at = {});
  /// Peaks are located on pieces of a stretch no longer than this (s; 0: whole stretches), for
  /// paths whose steps may span more than a quarter of the shortest oscillation period (the exact
  /// path's clearance steps): within a quarter period no rate changes sign twice unseen.
  void set_peak_step(double peak_step_s) { peak_step_s_ = peak_step_s; }
  void add_impact_loss(double energy_kJ) { energy_.add_impact_loss(energy_kJ); }
  /// Passes the impacts appended to `impacts` since the last call to the sink (if any). Call it
  /// once an event's records are final.
  void stream_new_impacts(const std::vector<ImpactRecord>& impacts);
  /// HHT: energy a step's update removed (kJ), see HhtStepper::algorithmic_dissipation.
  void add_algorithmic_dissipation(double energy_kJ) { energy_.add_algorithmic_dissipation(energy_kJ); }

  /// Moves the collected peaks, history and energy (with the final state's energies) and the
  /// output selection into `result`, and streams any impact of `result` not streamed yet.
  void finish(const dynamics::VectorXd& final_state, RunResult& result);

 private:
  /// Every storey drift ratio at y and its rate (1/s), at drift_index(building, floor, slot); slot
  /// 0, 1: x, y at the CM; 2k + 2, 2k + 3: x, y at slab corner k + 1.
  struct Drifts {
    dynamics::VectorXd value, rate;
  };
  /// What the recorder computed at one instant: the end of one stretch is the start of the next,
  /// so nothing is computed twice. Accelerations and drifts are kept when a peak group or the
  /// history needs them; the accelerations' rate only where advance() had it exactly.
  struct Instant {
    std::optional<double> t_s;
    dynamics::VectorXd y, accel;  // accel: q̈ + r a_g with the dynamics going on from t_s
    Drifts drifts;
    dynamics::VectorXd accel_rate;
    bool rate_known = false;
  };
  /// The components of the state that a floor's peaks read, for ComponentsAt.
  struct FloorComponents {
    std::array<std::vector<int>, 3> coordinate;  // (u, u̇), (v, v̇), (φ, φ̇)
    std::vector<int> vertex;                     // u, φ and their rates
    std::vector<int> drift;                      // the floor's and the floor below's (u, v, φ) and rates
  };

  /// Fills `into` at (t, y) with what the outputs need (accelerations and drifts when asked).
  void measure(double t, const dynamics::VectorXd& y, bool accelerations, bool drifts, Instant& into) const;
  void update_peaks(const Instant& at);
  void append_row(const Instant& at);
  bool free_motion() const;
  /// q̈ + r a_g (m/s², rad/s²) of every DOF at (t, y), ordered as q, into `accel`.
  void absolute_accelerations(double t, const dynamics::VectorXd& y, dynamics::VectorXd& accel) const;
  /// Their rates (m/s³, rad/s³) in free motion, given the accelerations `accel` at (t, y).
  void free_acceleration_rates(double t, const dynamics::VectorXd& y, const dynamics::VectorXd& accel,
                               dynamics::VectorXd& rate) const;
  void locate_acceleration_peaks(double t_a, double t_b, const std::function<dynamics::VectorXd(double)>& at);
  void storey_drifts(const dynamics::VectorXd& y, Drifts& d) const;
  /// One of them (for root finding, where the table would be wasted).
  struct Drift {
    double value, rate;
  };
  Drift storey_drift(const dynamics::VectorXd& y, int building, int floor, std::size_t slot) const;
  std::size_t drift_slots(int building) const;
  std::size_t drift_index(int building, int floor, std::size_t slot) const;
  void locate_drift_peaks(double t_a, double t_b, const std::function<dynamics::VectorXd(double)>& at,
                          const ComponentsAt& components_at);
  void locate_peaks(double t_a, double t_b, const std::function<dynamics::VectorXd(double)>& at,
                    const ComponentsAt& components_at);
  /// The state at t with (at least) the components `indices` right, from `components_at` when
  /// given, else `at`; in partial_, valid until the next call.
  const dynamics::VectorXd& read_components(double t, const std::vector<int>& indices,
                                            const std::function<dynamics::VectorXd(double)>& at,
                                            const ComponentsAt& components_at);
  /// Updates `peak` at the turning point of `value` inside (t_a, t_b), if its rate changes sign
  /// there and it can beat the peak.
  template <class StateAt, class Value, class Rate>
  void locate_peak(Peak& peak, double t_a, double t_b, const StateAt& state_at, const Value& value, const Rate& rate);

  const dynamics::CoupledSystem& system_;
  RecordedDynamics dynamics_;
  OutputSelection outputs_;
  std::vector<contact::Level> history_levels_;
  double interval_s_;
  double next_sample_s_;
  std::array<std::size_t, 3> drift_offset_{};  // building 1's drifts from [0], building 2's from [1], count [2]
  std::array<std::vector<model::Point2>, 2> vertices_;  // contact vertices per building, by outline number
  std::array<std::vector<FloorComponents>, 2> components_;  // per building and floor, as peaks_
  std::vector<BuildingPeaks> peaks_;
  History history_;
  EnergyBalance energy_;
  RunSink* sink_;
  bool started_ = false;                // the sink has its columns
  std::optional<double> last_row_t_s_;  // a row is written once per instant
  double peak_step_s_ = 0.0;
  Instant start_, last_;  // the stretch being advanced starts at start_; last_: the latest instant
  // Scratch space of the hot path, sized once (no allocation per step).
  mutable dynamics::VectorXd y_dot_, y_ddot_;                // absolute_accelerations, free_acceleration_rates
  mutable std::vector<model::Point2> below_, below_rate_;  // storey_drifts
  dynamics::VectorXd partial_, accel_lo_, accel_hi_;        // states and accelerations inside a stretch
  Eigen::VectorXd row_;
  std::size_t impacts_streamed_ = 0;
};

/// Vertices of `building`'s slab that take part in some candidate (as vertex or edge end).
std::vector<model::Point2> contact_vertices(const std::vector<contact::Candidate>& candidates, int building);

}  // namespace pounding::solvers
