#define BOOST_TEST_MODULE run_budget
#include <boost/test/unit_test.hpp>

#include "../support/two_slabs.hpp"
#include "pounding/solvers/hht.hpp"
#include "pounding/solvers/run_budget.hpp"

// Every run ends with a named status, never a hang or a crash: interrupted (SIGINT/SIGTERM),
// time_limit (wall-time budget), non_finite (a diverged solution).

using namespace pounding;

namespace {

dynamics::CoupledSystem pushed_slabs() {
  return testing::two_slabs({}, testing::box(0.1, 0, 10.1, 10), {}, 0.1, 2.0, 3.0);
}

struct ClearInterrupt {
  ~ClearInterrupt() { solvers::clear_interrupt(); }
};

}  // namespace

BOOST_AUTO_TEST_CASE(AnInterruptEndsEveryPathAtItsNextStep) {
  const dynamics::CoupledSystem system = pushed_slabs();
  const ClearInterrupt cleanup;
  solvers::request_interrupt();
  const auto event = solvers::run_event_driven(system, {}, testing::cvode(1e-8, 1e-10), "cvode-bdf");
  BOOST_TEST(solvers::to_string(event.status) == "interrupted");
  BOOST_TEST(event.end_s == 0.0);
  BOOST_TEST(event.status_detail.find("signal") != std::string::npos);
  const auto hht = solvers::run_hht(system, {}, "hht");
  BOOST_TEST(solvers::to_string(hht.status) == "interrupted");
}

BOOST_AUTO_TEST_CASE(AnExhaustedWallTimeBudgetEndsTheRunNamed) {
  const dynamics::CoupledSystem system = pushed_slabs();
  solvers::EventOptions options;
  options.budget.max_wall_time_s = 1e-12;  // used up before the first step
  const auto event = solvers::run_event_driven(system, options, testing::cvode(1e-8, 1e-10), "cvode-bdf");
  BOOST_TEST(solvers::to_string(event.status) == "time_limit");
  solvers::HhtOptions hht_options;
  hht_options.budget.max_wall_time_s = 1e-12;
  BOOST_TEST(solvers::to_string(solvers::run_hht(system, hht_options, "hht").status) == "time_limit");
}

BOOST_AUTO_TEST_CASE(HhtStepBudgetEndsTheRunNamed) {
  solvers::HhtOptions options;
  options.dt_s = 0.01;
  options.max_steps = 50;  // 2 s need 200
  const auto result = solvers::run_hht(pushed_slabs(), options, "hht");
  BOOST_TEST(solvers::to_string(result.status) == "step_limit");
  BOOST_TEST(result.end_s < 2.0);
}

BOOST_AUTO_TEST_CASE(ADivergedSolutionEndsTheRunNamedWithoutReadingOutsideTheRecord) {
  // Velocities near the largest double overflow within a step. The event-driven paths call the
  // ground motion at whatever time the solver's iterate holds: never outside the samples.
  const dynamics::CoupledSystem system = pushed_slabs();
  Eigen::VectorXd wild = Eigen::VectorXd::Zero(system.state_size());
  wild.tail(system.dof()).setConstant(1e305);
  solvers::HhtOptions hht_options;
  hht_options.initial_state = wild;
  const auto hht = solvers::run_hht(system, hht_options, "hht");
  BOOST_TEST(solvers::to_string(hht.status) == "non_finite");
  solvers::EventOptions options;
  options.initial_state = wild;
  const auto event = solvers::run_event_driven(system, options, testing::cvode(1e-8, 1e-10), "cvode-bdf");
  BOOST_TEST(solvers::to_string(event.status) != "completed");
  BOOST_TEST(!event.status_detail.empty());
}
