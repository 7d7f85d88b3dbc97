#pragma once
// Collects what a run reports from its states: peaks, the sampled history and the energy
// integrals. Shared by every solution path so their outputs compare column for column.

#include <functional>
#include <vector>

#include "pounding/dynamics/coupled_system.hpp"
#include "pounding/solvers/run_result.hpp"

namespace pounding::solvers {

class Recorder {
 public:
  /// History of the levels `history_levels` (1-based indices into system.levels(); empty: every
  /// level), each as building 1's floor then building 2's. @pre indices valid.
  Recorder(const dynamics::CoupledSystem& system, const std::vector<int>& history_levels, double history_interval_s);

  /// A state the run passes through (step ends, samples, events): updates the peaks.
  void observe(double t, const dynamics::VectorXd& y);
  /// Writes a history row at t (also observes it).
  void sample(double t, const dynamics::VectorXd& y);
  /// Advances over (t_a, t_b] of a smooth stretch whose states `at(t)` returns and whose end
  /// state is `y_b`: history samples that fall inside, the peaks at t_b, and the energy
  /// integrals (3-point Gauss–Legendre). `constraint_power(t, y)` is the power of
  /// sustained-contact forces (kW).
  void advance(double t_a, double t_b, const dynamics::VectorXd& y_b,
               const std::function<dynamics::VectorXd(double)>& at,
               const std::function<double(double, const dynamics::VectorXd&)>& constraint_power);
  void add_impact_loss(double energy_kJ) { energy_.impact_loss_kJ += energy_kJ; }
  /// HHT: energy a step's update removed (kJ), see HhtStepper::algorithmic_dissipation.
  void add_algorithmic_dissipation(double energy_kJ) { energy_.algorithmic_dissipation_kJ += energy_kJ; }

  /// Moves the collected peaks, history and energy (with the final state's energies) into `result`.
  void finish(const dynamics::VectorXd& final_state, RunResult& result);

 private:
  void append_row(double t, const dynamics::VectorXd& y);

  const dynamics::CoupledSystem& system_;
  std::vector<contact::Level> history_levels_;
  double interval_s_;
  double next_sample_s_;
  std::array<std::vector<model::Point2>, 2> vertices_;  // contact vertices per building
  std::vector<BuildingPeaks> peaks_;
  History history_;
  EnergyAudit energy_;
};

/// Vertices of `building`'s slab that take part in some candidate (as vertex or edge end).
std::vector<model::Point2> contact_vertices(const std::vector<contact::Candidate>& candidates, int building);

}  // namespace pounding::solvers
