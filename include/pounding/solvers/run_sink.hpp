#pragma once
// Where a run sends its history rows and impacts the moment they are final, so a caller can keep
// them outside memory (the io layer streams them to files) and a killed run loses nothing it had
// computed. The solver layer knows nothing about files; it only calls this interface.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "pounding/solvers/run_result.hpp"

namespace pounding::solvers {

class RunSink {
 public:
  virtual ~RunSink() = default;
  /// Once, when the run records its first state (before any row or impact): the history's column
  /// names (`t_s` first, as History::columns), empty for a run without history (no row or contact
  /// force follows).
  virtual void history_columns(const std::vector<std::string>& columns) = 0;
  /// One history row, in time order: t (s) and the values of columns[1..].
  virtual void history_row(double t_s, const Eigen::VectorXd& values) = 0;
  /// One impact, in the order RunResult::impacts lists them, once nothing will change it.
  virtual void impact(const ImpactRecord& impact) = 0;
  /// One contact's force at a history row's instant, after that row.
  virtual void contact_force(const ContactForceSample& sample) = 0;
  /// After each stretch of the run: the simulated time reached and the record's end (s), and the
  /// impacts passed to impact() so far. Called once per solver step: a sink that shows it must
  /// throttle itself.
  virtual void progress(double /*t_s*/, double /*end_s*/, std::size_t /*impacts*/) {}
};

}  // namespace pounding::solvers
