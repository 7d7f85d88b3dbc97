#pragma once
// What every run may spend, and the interrupt request a signal handler raises: a run that
// exceeds its budget or is interrupted ends with a named status, never a hang.

#include <chrono>
#include <optional>
#include <string>

#include "pounding/solvers/run_result.hpp"

namespace pounding::solvers {

/// Asks every run in this process to stop at its next step with status `interrupted`.
/// Async-signal-safe (sets a lock-free atomic flag).
void request_interrupt() noexcept;
bool interrupt_requested() noexcept;
/// Withdraws the request (for a process that runs again after an interrupt, and for tests).
void clear_interrupt() noexcept;

struct RunBudget {
  double max_wall_time_s = 3600.0;  // wall-clock seconds a run may take (default one hour)
  /// @throws InputError (key `max_wall_time_s`) unless positive and finite.
  void validate() const;
};

/// Checks a running run against its budget; construct it when the run starts.
class BudgetClock {
 public:
  explicit BudgetClock(const RunBudget& budget);
  /// Sets `result`'s status (interrupted or time_limit) and detail and returns true when the run
  /// must end now at simulated time `t_s`. Reads the clock only every 16th call (it is cheap
  /// next to a step, but not free).
  bool exhausted(double t_s, RunResult& result);

 private:
  double max_wall_time_s_;
  std::chrono::steady_clock::time_point start_;
  unsigned calls_ = 0;
};

/// Sets `result` to non_finite and returns true if the state or time at t_s is NaN or infinite
/// (a solution that diverged: nothing after it means anything).
bool diverged(double t_s, const Eigen::VectorXd& state, RunResult& result);

}  // namespace pounding::solvers
