#include <boost/test/unit_test.hpp>

#include "../support/two_slabs.hpp"
#include "../support/state_space_exact.hpp"
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

// Building 1 a free mass pushed by a_g = −1 m/s² onto a 10⁹ t block 1 cm away: with k = 0 the
// first impact (t ≈ 0.14 s) starts a hold that lasts to the end (1 s). On the exact path that
// hold is its one numerically integrated stretch (CVODE Adams at hold_rtol).
dynamics::CoupledSystem pressed_into_hold() {
  return testing::two_slabs({1.0, 1e4, 0.0}, testing::diamond(0.01), {1e9, 0.01, 0.9}, 0.01, 1.0, -1.0);
}

solvers::EventOptions plastic() {
  solvers::EventOptions options;
  options.restitution = 0.0;
  return options;
}

/// The exact integrator, requesting an interrupt (as SIGINT would) at its first step in a held
/// stretch: proves the request reaches the run while it is inside that stretch.
class InterruptWhenHeld final : public solvers::Integrator {
 public:
  InterruptWhenHeld(solvers::OdeFunctions& functions, double t0, const Eigen::VectorXd& y0)
      : functions_(functions), exact_(functions, t0, y0) {}
  void restart(double t, const Eigen::VectorXd& y) override { exact_.restart(t, y); }
  void set_max_step(double h_s) override { exact_.set_max_step(h_s); }
  void set_stop_time(double t_s) override { exact_.set_stop_time(t_s); }
  solvers::StepOutcome step(double t_final) override {
    if (!functions_.is_linear()) solvers::request_interrupt();
    return exact_.step(t_final);
  }
  const Eigen::VectorXd& state() const override { return exact_.state(); }
  void interpolate(double t, Eigen::Ref<Eigen::VectorXd> y) override { exact_.interpolate(t, y); }
  std::vector<int> roots_found() override { return exact_.roots_found(); }
  solvers::IntegratorCounters counters() override { return exact_.counters(); }

 private:
  solvers::OdeFunctions& functions_;
  pounding::testing::StateSpaceExactIntegrator exact_;
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

BOOST_AUTO_TEST_CASE(TheStepBudgetEndsTheExactPathInsideAHeldStretch) {
  const dynamics::CoupledSystem system = pressed_into_hold();
  const auto full = solvers::run_event_driven(system, plastic(), testing::exact(), "exact");
  BOOST_TEST_REQUIRE(solvers::to_string(full.status) == "completed");
  BOOST_TEST_REQUIRE(full.sustained_contacts.size() == 1u);
  const double hold_start_s = full.sustained_contacts[0].start_s;
  BOOST_TEST_REQUIRE(hold_start_s < 0.5);  // the hold, at most 2.5 ms a step, takes > 10 steps
  solvers::EventOptions options = plastic();
  options.max_steps = full.statistics.steps - 10;
  const auto cut = solvers::run_event_driven(system, options, testing::exact(), "exact");
  BOOST_TEST(solvers::to_string(cut.status) == "step_limit");
  BOOST_TEST(cut.end_s > hold_start_s);
  BOOST_TEST(cut.end_s < 1.0);
  BOOST_TEST_REQUIRE(cut.sustained_contacts.size() == 1u);
  BOOST_TEST(cut.sustained_contacts[0].release_reason == "end of run");
}

BOOST_AUTO_TEST_CASE(AnInterruptEndsTheExactPathInsideAHeldStretch) {
  const ClearInterrupt cleanup;
  const solvers::IntegratorFactory interrupting =
      [](solvers::OdeFunctions& functions, double t0,
         const Eigen::VectorXd& y0) -> std::unique_ptr<solvers::Integrator> {
    return std::make_unique<InterruptWhenHeld>(functions, t0, y0);
  };
  const auto result = solvers::run_event_driven(pressed_into_hold(), plastic(), interrupting, "exact");
  BOOST_TEST(solvers::to_string(result.status) == "interrupted");
  BOOST_TEST_REQUIRE(result.sustained_contacts.size() == 1u);
  BOOST_TEST(result.end_s > result.sustained_contacts[0].start_s);
  BOOST_TEST(result.end_s < 0.5);  // one held step after the hold began, not the whole second
}
