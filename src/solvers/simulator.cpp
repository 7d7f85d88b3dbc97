#include "pounding/solvers/simulator.hpp"

#include <fmt/format.h>

namespace pounding::solvers {

Simulator::Simulator(HybridSystem& system, const excitation::GroundMotion& motion, SimulatorLimits limits)
    : system_(system), motion_(motion), limits_(std::move(limits)), budget_(limits_.budget) {}

SimulatorOutcome Simulator::run(double t0, Eigen::VectorXd y0, const IntegratorFactory& make_integrator) {
  t_ = t0;
  y_ = std::move(y0);
  // 1. start
  system_.start(t_, y_);
  integrator_ = make_integrator(system_, t_, y_);
  system_.prepare(*integrator_);
  begin_phase();
  while (!system_.stopped() && advance()) {
  }
  accumulate_counters();
  outcome_.end_s = t_;
  outcome_.end_state = y_;
  return std::move(outcome_);
}

void Simulator::set_next_stop() {
  // Record samples are where the forcing's slope changes: never step across one, unless the
  // integrator carries the forcing itself; then only the record's end bounds its steps.
  if (integrator_->steps_across_samples()) {
    if (t_ < motion_.end_s()) integrator_->set_stop_time(motion_.end_s());
  } else if (const auto next = motion_.next_sample_after(t_)) {
    integrator_->set_stop_time(*next);
  }
}

void Simulator::begin_phase() {
  // 2. begin_phase
  set_next_stop();
  system_.begin_phase(t_, y_, *integrator_);
}

void Simulator::accumulate_counters() {
  const IntegratorCounters c = integrator_->counters();
  IntegratorCounters& sum = outcome_.counters;
  sum.steps += c.steps;
  sum.rhs_evaluations += c.rhs_evaluations;
  sum.root_evaluations += c.root_evaluations;
  sum.jacobian_evaluations += c.jacobian_evaluations;
  sum.error_test_failures += c.error_test_failures;
}

void Simulator::restart() {
  accumulate_counters();  // re-initialisation resets the integrator's own counters
  integrator_->restart(t_, y_);
  ++outcome_.restarts;
  begin_phase();
}

void Simulator::end(RunStatus status, std::string detail) {
  outcome_.status = status;
  outcome_.detail = std::move(detail);
}

SimulatorOutcome Simulator::outcome_so_far() const {
  SimulatorOutcome so_far = outcome_;
  so_far.end_s = t_;
  so_far.end_state = y_;
  return so_far;
}

void Simulator::event(double t, Eigen::VectorXd& y, const EventCause& cause) {
  // 6. event
  const bool restart_needed = system_.on_event(t, y, cause);
  t_ = t;
  y_ = y;
  if (restart_needed) restart();
}

bool Simulator::advance() {
  RunResult stop;  // BudgetClock and diverged() write the reason here
  if (budget_.exhausted(t_, stop)) {
    end(stop.status, stop.status_detail);
    return false;
  }
  const double t_end = motion_.end_s();
  if (t_ >= t_end) return false;  // an event exactly at the end: no stop time is left to obey
  // 3. step
  const StepOutcome outcome = integrator_->step(t_end);
  if (outcome.kind == StepKind::failure) {
    if (!system_.recover(t_, y_, outcome.failure)) {
      end(RunStatus::solver_failure, fmt::format("after t = {} s: {}", t_, outcome.failure));
      return false;
    }
    restart();
    return true;
  }
  const double t = outcome.t_s;
  Eigen::VectorXd y = integrator_->state();
  if (diverged(t, y, stop)) {
    end(stop.status, stop.status_detail);
    return false;
  }
  // 4. examine: an event inside the step cuts it there
  if (const std::optional<HiddenEvent> hidden = system_.examine_step(t_, t, y, *integrator_)) {
    Eigen::VectorXd y_event(y.size());
    integrator_->interpolate(hidden->t_s, y_event);
    system_.record(t_, hidden->t_s, y_event, *integrator_);  // 5. record
    event(hidden->t_s, y_event, {.root_flags = {}, .hidden = hidden->index});
    return true;
  }
  system_.record(t_, t, y, *integrator_);  // 5. record
  if (outcome.kind == StepKind::root) {
    const long restarts = outcome_.restarts;
    event(t, y, {.root_flags = integrator_->roots_found(), .hidden = std::nullopt});
    if (outcome_.restarts != restarts) return true;
  }
  // 7. after_step
  t_ = t;
  y_ = y;
  if (outcome.kind == StepKind::stop_time) set_next_stop();
  system_.after_step(t, y, *integrator_);
  if (outcome_.counters.steps + integrator_->counters().steps > limits_.max_steps) {
    end(RunStatus::step_limit, fmt::format("more than {} steps by t = {} s", limits_.max_steps, t));
    return false;
  }
  return t < t_end;
}

}  // namespace pounding::solvers
