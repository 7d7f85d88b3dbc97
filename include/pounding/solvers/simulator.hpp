#pragma once
// One event loop for every run that an ODE integrator steps between events: the event-driven
// paths (event_driven.cpp) and the needed gap's contact-free run (analysis/needed_gap.cpp). A
// HybridSystem says what is integrated (OdeFunctions), its root functions, and what happens at
// its events; the Simulator runs the phases, one function each, in this order (as Drake's
// Simulator::AdvanceTo documents its steps):
//
//  1. start        HybridSystem::start at t0: what holds at the initial instant (integrators report
//                  no root at their initial time), then the integrator is made and
//                  HybridSystem::prepare sees it once.
//  2. begin_phase  At t0 and after every restart: the next record sample becomes the stop time
//                  (the record's end where the integrator carries the forcing itself:
//                  Integrator::steps_across_samples), then HybridSystem::begin_phase sets what
//                  bounds the integrator's steps.
//  3. step         Integrator::step to a root, a stop time or its own step end. A failure is
//                  offered to HybridSystem::recover (restart there once) or ends the run; a state
//                  or time that is not finite ends it (RunStatus::non_finite).
//  4. examine      HybridSystem::examine_step over the step: an event inside it that no root
//                  flagged (a contact the interpolant shows) cuts the step there.
//  5. record       HybridSystem::record over the step, or its part up to the event.
//  6. event        At a root or an event of 4: HybridSystem::on_event applies its jumps; if it asks,
//                  the integrator restarts there (counters kept) and the loop goes to 2.
//  7. after_step   After a step without event (or an event that changed nothing the integrator
//                  sees): HybridSystem::after_step; at a stop time the next one is set. Back to 3
//                  until the record ends, the system stops itself (HybridSystem::stopped), or the
//                  wall-time budget, an interrupt or the step limit ends the run.
//  8. end          The outcome: how the run ended, where, and the integrator's counters summed
//                  over every restart; the system closes its own records.
//
// Units: s. The Simulator never throws for a numerical failure (the outcome says it); what the
// system or the integrator throws passes through.

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pounding/excitation/ground_motion.hpp"
#include "pounding/solvers/integrator.hpp"
#include "pounding/solvers/run_budget.hpp"
#include "pounding/solvers/run_result.hpp"

namespace pounding::solvers {

/// What ends a step other than its own end: the roots the integrator flagged
/// (Integrator::roots_found), or an event the system found inside the step (`hidden` set: its
/// index in the system's own terms, e.g. a candidate).
struct EventCause {
  std::vector<int> root_flags;
  std::optional<std::size_t> hidden;
};

/// An event inside a step that no root flagged (phase 4): its instant and what it is.
struct HiddenEvent {
  double t_s = 0.0;
  std::size_t index = 0;
};

class HybridSystem : public OdeFunctions {
 public:
  /// 1. The initial instant t0, state y (which an event there may change).
  virtual void start(double t0, Eigen::VectorXd& y) = 0;
  /// 1. Once, with the integrator made from the start's state.
  virtual void prepare(Integrator& /*integrator*/) {}
  /// 2. A smooth stretch begins at (t, y): the integrator's step bound.
  virtual void begin_phase(double t, const Eigen::VectorXd& y, Integrator& integrator) = 0;
  /// 3. The integrator failed on the step after t with `failure` (its flag and message): true to
  /// restart it at (t, y) and go on, false to end the run. Default: end it.
  virtual bool recover(double /*t*/, const Eigen::VectorXd& /*y*/, const std::string& /*failure*/) { return false; }
  /// 4. The step (t_a, t_b] that ended in y_b: an event inside it that no root flagged, if any.
  virtual std::optional<HiddenEvent> examine_step(double /*t_a*/, double /*t_b*/, const Eigen::VectorXd& /*y_b*/,
                                                  Integrator& /*integrator*/) {
    return std::nullopt;
  }
  /// 5. What (t_a, t_b] adds to the records; y_b is the state at t_b, the integrator's interpolant
  /// covers the stretch.
  virtual void record(double t_a, double t_b, const Eigen::VectorXd& y_b, Integrator& integrator) = 0;
  /// 6. The event at (t, y): applies its jumps to y. @return true when the integrator must
  /// restart at (t, y) (the velocities jumped or the equations changed).
  virtual bool on_event(double t, Eigen::VectorXd& y, const EventCause& cause) = 0;
  /// 7. After a step that ended at (t, y) without an event.
  virtual void after_step(double t, const Eigen::VectorXd& y, Integrator& integrator) = 0;
  /// True once the system has ended the run itself (its own status).
  virtual bool stopped() const = 0;
};

struct SimulatorLimits {
  long max_steps = 10'000'000;  // integrator steps over the whole run, all restarts summed
  RunBudget budget;             // wall time; the run also stops when interrupted
};

/// How a run ended. `status` is completed when the record's end was reached or the system stopped
/// itself (its own status says why); otherwise time_limit, interrupted, step_limit,
/// solver_failure or non_finite, with `detail` naming where.
struct SimulatorOutcome {
  RunStatus status = RunStatus::completed;
  std::string detail;
  double end_s = 0.0;           // the last instant reached
  Eigen::VectorXd end_state;    // the state there
  IntegratorCounters counters;  // summed over every restart
  long restarts = 0;
};

class Simulator {
 public:
  /// Runs `system` under `motion` (its sample times are the stop times) with `limits`.
  /// @pre limits validated (RunBudget::validate); `system` and `motion` outlive the Simulator.
  Simulator(HybridSystem& system, const excitation::GroundMotion& motion, SimulatorLimits limits);

  /// Phases 1–8 from (t0, y0) to the end of `motion`, with the integrator `make_integrator` makes.
  SimulatorOutcome run(double t0, Eigen::VectorXd y0, const IntegratorFactory& make_integrator);
  /// The outcome so far (status completed), for a caller whose run() threw: the instant and
  /// state reached, the counters of the integrators before the last restart.
  SimulatorOutcome outcome_so_far() const;

 private:
  void begin_phase();
  void set_next_stop();
  void restart();
  /// 3–7 once; false when the run ends.
  bool advance();
  /// 6: the event at (t, y), then a restart if the system asks for one.
  void event(double t, Eigen::VectorXd& y, const EventCause& cause);
  void end(RunStatus status, std::string detail);
  void accumulate_counters();

  HybridSystem& system_;
  const excitation::GroundMotion& motion_;
  SimulatorLimits limits_;
  BudgetClock budget_;
  std::unique_ptr<Integrator> integrator_;
  double t_ = 0.0;
  Eigen::VectorXd y_;
  SimulatorOutcome outcome_;
};

}  // namespace pounding::solvers
