#pragma once
// Collects what a run reports from its states: peaks, the sampled history and the energy
// integrals. Shared by every solution path so their outputs compare column for column. With a
// RunSink the history rows and impacts go to the sink as they come and the history is not kept.

#include <functional>
#include <optional>
#include <vector>

#include "pounding/dynamics/coupled_system.hpp"
#include "pounding/solvers/integrator.hpp"
#include "pounding/solvers/run_result.hpp"
#include "pounding/solvers/run_sink.hpp"

namespace pounding::solvers {

class Recorder {
 public:
  /// Writes the components `indices` of the state at t into y (others may be left stale): a
  /// cheaper `at` for the peaks, which read two to four components each.
  using ComponentsAt = std::function<void(double t, const std::vector<int>& indices, dynamics::VectorXd& y)>;

  /// History of the levels `history_levels` (1-based indices into system.levels(); empty: every
  /// level), each as building 1's floor then building 2's. `sink` (may be null; must outlive the
  /// recorder) receives the columns at the first row, then every row and impact; the history in
  /// the result then has its columns and no rows. @pre indices valid.
  Recorder(const dynamics::CoupledSystem& system, const std::vector<int>& history_levels, double history_interval_s,
           RunSink* sink = nullptr);

  /// A state the run passes through (step ends, samples, events): updates the peaks.
  void observe(double t, const dynamics::VectorXd& y);
  /// Writes a history row at t (also observes it).
  void sample(double t, const dynamics::VectorXd& y);
  /// Advances over (t_a, t_b] of a smooth stretch whose states `at(t)` returns and whose end
  /// state is `y_b`: history samples that fall inside, the peaks (turning points inside located
  /// on `at` to round-off, so a peak does not depend on where the steps end), and the energy
  /// integrals (3-point Gauss–Legendre, or `closed_form` when given: the integrator's own, for a
  /// stretch without contact forces). `constraint_power(t, y)` is the power of sustained-contact
  /// forces (kW). `components_at`, when given, locates the peaks instead of `at`.
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
  void locate_peaks(double t_a, double t_b, const dynamics::VectorXd& y_b,
                    const std::function<dynamics::VectorXd(double)>& at, const ComponentsAt& components_at);
  /// Updates `peak` at the turning point of `value` inside (t_a, t_b), if its rate changes sign
  /// there and it can beat the peak.
  template <class Value, class Rate>
  void locate_peak(Peak& peak, double t_a, double t_b, const dynamics::VectorXd& y_a, const dynamics::VectorXd& y_b,
                   const std::function<dynamics::VectorXd(double)>& at, const Value& value, const Rate& rate);

  const dynamics::CoupledSystem& system_;
  std::vector<contact::Level> history_levels_;
  double interval_s_;
  double next_sample_s_;
  std::array<std::vector<model::Point2>, 2> vertices_;  // contact vertices per building, by outline number
  std::vector<BuildingPeaks> peaks_;
  History history_;
  EnergyAudit energy_;
  RunSink* sink_;
  std::optional<double> last_row_t_s_;  // a row is written once per instant
  std::size_t impacts_streamed_ = 0;
};

/// Vertices of `building`'s slab that take part in some candidate (as vertex or edge end).
std::vector<model::Point2> contact_vertices(const std::vector<contact::Candidate>& candidates, int building);

}  // namespace pounding::solvers
