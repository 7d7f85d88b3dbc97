#include "pounding/solvers/run_budget.hpp"

#include <atomic>
#include <cmath>
#include <fmt/format.h>

#include "pounding/input_error.hpp"

namespace pounding::solvers {
namespace {

std::atomic<bool> interrupt_flag{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the flag is set from a signal handler");

}  // namespace

void request_interrupt() noexcept { interrupt_flag.store(true); }
bool interrupt_requested() noexcept { return interrupt_flag.load(); }
void clear_interrupt() noexcept { interrupt_flag.store(false); }

void RunBudget::validate() const {
  if (!(max_wall_time_s > 0.0) || !std::isfinite(max_wall_time_s)) {
    throw InputError("max_wall_time_s", format_value(max_wall_time_s), "must be positive (s)");
  }
}

BudgetClock::BudgetClock(const RunBudget& budget)
    : max_wall_time_s_(budget.max_wall_time_s), start_(std::chrono::steady_clock::now()) {}

bool BudgetClock::exhausted(double t_s, RunResult& result) {
  if (interrupt_requested()) {
    result.status = RunStatus::interrupted;
    result.status_detail = fmt::format("interrupted by a signal at t = {} s", t_s);
    return true;
  }
  if (calls_++ % 16 != 0) return false;
  const double elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (elapsed_s <= max_wall_time_s_) return false;
  result.status = RunStatus::time_limit;
  result.status_detail = fmt::format("the wall-time budget of {} s was used up at t = {} s", max_wall_time_s_, t_s);
  return true;
}

bool diverged(double t_s, const Eigen::VectorXd& state, RunResult& result) {
  if (std::isfinite(t_s) && state.allFinite()) return false;
  result.status = RunStatus::non_finite;
  result.status_detail = fmt::format("the solution is no longer finite at t = {} s", t_s);
  return true;
}

}  // namespace pounding::solvers
