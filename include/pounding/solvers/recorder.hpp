#pragma once
// Collects what a run reports from its states: the peaks and the sampled history that its
// OutputSelection asks for, and the energy integrals (always). Shared by every solution path so
// their outputs compare column for column. With a RunSink the history rows and impacts go to the
// sink as they come and the history is not kept. Its parts: what the outputs read from a state
// (RunKinematics, measured once per Instant), the peaks (PeakTracker), the energy integrals
// (EnergyBalance); the history's columns and row values are declared in history_schema.hpp and
// written here, on the same instants the peaks see.

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "pounding/dynamics/coupled_system.hpp"
#include "pounding/solvers/energy_balance.hpp"
#include "pounding/solvers/integrator.hpp"
#include "pounding/solvers/member_forces.hpp"
#include "pounding/solvers/peak_tracker.hpp"
#include "pounding/solvers/run_kinematics.hpp"
#include "pounding/solvers/run_result.hpp"
#include "pounding/solvers/run_sink.hpp"

namespace pounding::solvers {

/// The free motion's dynamics (no contact forces between impacts), for the fixed-step path.
RecordedDynamics free_dynamics(const dynamics::CoupledSystem& system);

/// The slabs history.csv writes: the levels `levels` (1-based indices into system.levels();
/// empty: every level), each as building 1's floor then building 2's, then `other_floors`
/// ({building 0 or 1, floor 1-based}: any floor of either building) that are not among them.
struct HistorySlabs {
  std::vector<int> levels;
  std::vector<std::array<int, 2>> other_floors;
};

/// The columns of history.csv for `slabs`: `t_s` first, then per slab the columns of
/// history_quantities() (history_schema.hpp), then with `member_forces` MemberForces' columns.
/// @pre indices valid.
std::vector<std::string> history_columns(const dynamics::CoupledSystem& system, const HistorySlabs& slabs,
                                         bool member_forces = false);

class Recorder {
 public:
  using ComponentsAt = PeakTracker::ComponentsAt;

  /// History of the slabs `slabs` (HistorySlabs) when `outputs.history`; the peak groups
  /// `outputs` asks for (the others are neither computed nor reported). `sink` (may be null; must
  /// outlive the recorder) receives the columns at the first sample (none without history), then
  /// every row, contact force and impact; the history in the result then has its columns and no
  /// rows. @pre indices valid.
  Recorder(const dynamics::CoupledSystem& system, RecordedDynamics dynamics, const HistorySlabs& slabs,
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
               const std::optional<StretchEnergy>& closed_form = std::nullopt, const ComponentsAt& components_at = {});
  /// The yielding springs' states the member forces read (outputs.member_forces), kept by the
  /// solver and changed only at events; null (the default): every column elastic.
  void set_spring_states(const dynamics::SpringStates* states) { spring_states_ = states; }
  /// Peaks are located on pieces of a stretch no longer than this (s; 0: whole stretches), for
  /// paths whose steps may span more than a quarter of the shortest oscillation period (the exact
  /// path's clearance steps): within a quarter period no rate changes sign twice unseen.
  void set_peak_step(double peak_step_s) { peak_step_s_ = peak_step_s; }
  /// See EnergyBalance::split_at_samples.
  void split_energy_at_samples(bool on) { energy_.split_at_samples(on); }
  void add_impact_loss(double energy_kJ) { energy_.add_impact_loss(energy_kJ); }
  /// See EnergyBalance::smooth_dissipated_kJ.
  const std::vector<double>& smooth_dissipated_kJ() const { return energy_.smooth_dissipated_kJ(); }
  /// Passes the impacts appended to `impacts` since the last call to the sink (if any). Call it
  /// once an event's records are final.
  void stream_new_impacts(const std::vector<ImpactRecord>& impacts);
  /// HHT: energy a step's update removed (kJ), see HhtStepper::algorithmic_dissipation.
  void add_algorithmic_dissipation(double energy_kJ) { energy_.add_algorithmic_dissipation(energy_kJ); }

  /// Moves the collected peaks, history and energy (with the final state's energies) and the
  /// output selection into `result`, and streams any impact of `result` not streamed yet.
  void finish(const dynamics::VectorXd& final_state, RunResult& result,
              const dynamics::SpringStates* springs = nullptr);

 private:
  void append_row(const Instant& at);
  /// The member forces at (t, y) (outputs.member_forces): their peaks, and the values a history
  /// row written at t ends with.
  void measure_member_forces(double t, const dynamics::VectorXd& y);
  /// Every floor's storey drift ratios and rates at the final state (FloorPeaks::end_drift).
  void record_end_drifts(const dynamics::VectorXd& final_state, std::vector<BuildingPeaks>& peaks) const;

  const dynamics::CoupledSystem& system_;
  RunKinematics kinematics_;
  OutputSelection outputs_;
  PeakTracker peaks_;
  std::vector<std::array<int, 2>> history_slabs_;  // {building, floor} in column order
  double interval_s_;
  double next_sample_s_;
  History history_;
  EnergyBalance energy_;
  RunSink* sink_;
  bool started_ = false;                // the sink has its columns
  std::optional<double> last_row_t_s_;  // a row is written once per instant
  double peak_step_s_ = 0.0;
  Instant start_, last_;  // the stretch being advanced starts at start_; last_: the latest instant
  Eigen::VectorXd row_;
  std::optional<MemberForces> member_forces_;
  std::vector<MemberForce> member_peaks_;
  Eigen::VectorXd member_values_;
  const dynamics::SpringStates* spring_states_ = nullptr;
  std::size_t impacts_streamed_ = 0;
};

}  // namespace pounding::solvers
