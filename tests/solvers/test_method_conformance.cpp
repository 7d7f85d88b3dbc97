// The integrators the registry runs (analysis::methods(): each event-driven method's factory, in
// each form and order it offers, the exact path's modal propagator among them) behind the
// Integrator seam on a coupled system, against closed forms: two one-storey slabs with uncoupled
// x, y and torsion (tests/support/two_slabs.hpp), building 1 set moving along x under a constant
// ground acceleration. Its x is a damped oscillator, u'' + 2ζωu' + ω²u = −a_g (ζ = 0.05 exactly:
// Rayleigh fitted at modes 1 and 3). Each case checks the state at a step end, the interpolant
// inside the last step, a stop time, a root located on the trajectory and a restart from a
// changed state. The integrator_conformance suite checks the seam's finer contracts on
// hand-made ODEs; this one checks that every integrator a user can choose is among them.

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "../support/two_slabs.hpp"
#include "pounding/analysis/methods.hpp"

using namespace pounding;
using Eigen::VectorXd;

namespace {

constexpr double kPeriod_s = 0.5, kZeta = 0.05, kGroundAccel = 1.5, kVelocity = 0.4;

struct Case {
  std::string name;
  analysis::SolverSettings settings;
};

/// Every integrator the registry offers: each event-driven method, in each order and form. (A
/// loop, not a data test case: Boost registers those before the registry is initialised.)
std::vector<Case> registry_cases() {
  std::vector<Case> cases;
  for (const analysis::MethodInfo& method : analysis::methods()) {
    if (!method.factory) continue;  // hht: fixed steps, not behind the seam
    const bool has_form = analysis::applies(method, analysis::Setting::form);
    std::vector<int> orders(method.orders.begin(), method.orders.end());
    if (orders.empty()) orders.push_back(0);
    for (int order : orders) {
      for (const char* form : {"physical", "modal", "deviation"}) {
        if (!has_form && std::string(form) != "physical") continue;
        Case c{std::string(method.name), {}};
        c.settings.method = std::string(method.name);
        if (!method.orders.empty()) c.settings.order = order, c.name += "/order " + std::to_string(order);
        if (has_form) c.settings.form = form, c.name += std::string("/") + form;
        cases.push_back(c);
      }
    }
  }
  return cases;
}

const dynamics::CoupledSystem& system() {
  static const dynamics::CoupledSystem instance = testing::two_slabs(
      {100.0, kPeriod_s, kZeta}, testing::box(0.5, 0, 10.5, 10), {100.0, kPeriod_s, kZeta}, 0.5, 3.0, kGroundAccel);
  return instance;
}

/// The free motion of system(), with one root function: building 1's x reaching `level_m`.
class FreeMotion final : public solvers::OdeFunctions {
 public:
  explicit FreeMotion(double level_m) : level_m_(level_m) {}
  int state_size() const override { return system().state_size(); }
  int root_count() const override { return 1; }
  bool is_linear() const override { return true; }
  bool is_free_motion() const override { return true; }
  void rhs(double t, const Eigen::Ref<const VectorXd>& y, Eigen::Ref<VectorXd> y_dot) override {
    system().rhs(t, y, y_dot);
  }
  void jacobian(double, const Eigen::Ref<const VectorXd>&, Eigen::Ref<Eigen::MatrixXd> jac) override {
    jac = system().jacobian();
  }
  bool acceleration_jacobian(double, const Eigen::Ref<const VectorXd>& y, Eigen::SparseMatrix<double>& rows) override {
    system().constrained_acceleration_jacobian(y, {}, rows);
    return true;
  }
  void roots(double, const Eigen::Ref<const VectorXd>& y, Eigen::Ref<VectorXd> g) override {
    g[0] = level_m_ - y[x_index()];
  }
  static int x_index() { return system().floor_index(0, 1); }

 private:
  double level_m_;
};

/// Building 1's (u, u̇) a time tau after (u0, v0): the damped oscillator under −a_g.
std::pair<double, double> closed_form(double u0, double v0, double tau) {
  const double omega = 2.0 * std::numbers::pi / kPeriod_s, omega_d = omega * std::sqrt(1.0 - kZeta * kZeta);
  const double a = u0 + kGroundAccel / (omega * omega), b = (v0 + kZeta * omega * a) / omega_d;
  const double decay = std::exp(-kZeta * omega * tau), c = std::cos(omega_d * tau), s = std::sin(omega_d * tau);
  return {-kGroundAccel / (omega * omega) + decay * (a * c + b * s),
          decay * (-kZeta * omega * (a * c + b * s) + omega_d * (-a * s + b * c))};
}

struct Tolerances {
  double displacement_m, velocity_mps;
};

/// What the method is held to: 100 times its error tolerance per step on |u| ≤ 0.05 m and
/// |u̇| ≤ 0.5 m/s (a global error over a few hundred steps), round-off for the exact path.
Tolerances tolerances(const analysis::UsedSettings& used) {
  if (used.method->reference) return {1e-12, 1e-11};
  return {100.0 * (used.rtol * 0.05 + used.atol), 100.0 * (used.rtol * 0.5 + used.atol * 10.0)};
}

/// An integrator and the factory that made it: a factory owns what its integrators refer to
/// (the modal form's ModalSystem), as the event loop keeps it for the whole run.
struct Made {
  solvers::IntegratorFactory factory;
  std::unique_ptr<solvers::Integrator> integrator;
  solvers::Integrator* operator->() const { return integrator.get(); }
};

Made make(const analysis::UsedSettings& used, FreeMotion& motion, const VectorXd& y0) {
  Made made{used.method->factory(used, system()), nullptr};
  made.integrator = made.factory(motion, 0.0, y0);
  return made;
}

VectorXd pushed_state() { return testing::pushed(system(), kVelocity); }

/// Steps towards t_final until a step of kind `until` (StepKind::failure: to t_final); a failure is reported and
/// ends the stepping. `step_start`, when given, receives the time the last step started from.
solvers::StepOutcome step_until(solvers::Integrator& integrator, double t_final, solvers::StepKind until,
                                double* step_start = nullptr) {
  solvers::StepOutcome out{};
  double t = 0.0;
  do {
    t = out.t_s;
    out = integrator.step(t_final);
    if (out.kind == solvers::StepKind::failure) {
      BOOST_ERROR(out.failure);
      break;
    }
  } while (out.kind != until && out.t_s < t_final);
  if (step_start) *step_start = t;
  return out;
}

}  // namespace

BOOST_AUTO_TEST_CASE(StateAndInterpolantFollowTheClosedForm) {
  for (const Case& c : registry_cases()) {
    BOOST_TEST_CONTEXT(c.name) {
      const analysis::UsedSettings used = analysis::resolve(c.settings, &system());
      const Tolerances tol = tolerances(used);
      FreeMotion motion(1.0);  // out of reach: no root
      auto integrator = make(used, motion, pushed_state());
      integrator->set_max_step(0.01);
      double t_prev = 0.0;
      const double t = step_until(*integrator.integrator, 0.8, solvers::StepKind::failure, &t_prev).t_s;
      const int x = FreeMotion::x_index(), n = system().dof();
      const auto [u, v] = closed_form(0.0, kVelocity, t);
      BOOST_TEST(std::abs(integrator->state()[x] - u) <= tol.displacement_m);
      BOOST_TEST(std::abs(integrator->state()[n + x] - v) <= tol.velocity_mps);
      VectorXd y(system().state_size());
      for (double f : {0.25, 0.5, 0.75}) {
        const double t_inside = t_prev + f * (t - t_prev);
        integrator->interpolate(t_inside, y);
        const auto [u_in, v_in] = closed_form(0.0, kVelocity, t_inside);
        BOOST_TEST(std::abs(y[x] - u_in) <= tol.displacement_m, "interpolant at t = " << t_inside);
        BOOST_TEST(std::abs(y[n + x] - v_in) <= tol.velocity_mps, "interpolant at t = " << t_inside);
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(AStopTimeEndsAStepExactlyThere) {
  for (const Case& c : registry_cases()) {
    BOOST_TEST_CONTEXT(c.name) {
      const analysis::UsedSettings used = analysis::resolve(c.settings, &system());
      FreeMotion motion(1.0);
      auto integrator = make(used, motion, pushed_state());
      integrator->set_max_step(0.05);
      integrator->set_stop_time(0.123);
      const solvers::StepOutcome out = step_until(*integrator.integrator, 1.0, solvers::StepKind::stop_time);
      BOOST_TEST((out.kind == solvers::StepKind::stop_time));
      BOOST_TEST(out.t_s == 0.123);
    }
  }
}

BOOST_AUTO_TEST_CASE(ARootIsLocatedOnTheTrajectoryAndARestartTakesTheNewState) {
  for (const Case& c : registry_cases()) {
    BOOST_TEST_CONTEXT(c.name) {
      const analysis::UsedSettings used = analysis::resolve(c.settings, &system());
      const Tolerances tol = tolerances(used);
      // Building 1 rises to u = 0.02 m on its way to the first maximum: the crossing by bisection of
      // the closed form. The root's time error is the displacement error over the speed there.
      const double level_m = 0.02;
      double lo = 0.0, hi = 0.1;
      for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (closed_form(0.0, kVelocity, mid).first < level_m ? lo : hi) = mid;
      }
      const double t_cross = 0.5 * (lo + hi);
      FreeMotion motion(level_m);
      auto integrator = make(used, motion, pushed_state());
      integrator->set_max_step(0.01);
      solvers::StepOutcome out = step_until(*integrator.integrator, 1.0, solvers::StepKind::root);
      BOOST_TEST_REQUIRE((out.kind == solvers::StepKind::root));
      const double speed = closed_form(0.0, kVelocity, t_cross).second;
      BOOST_TEST(std::abs(out.t_s - t_cross) <= tol.displacement_m / speed + 1e-12);
      BOOST_TEST(integrator->roots_found()[0] != 0);

      // Restart there with building 1 stopped (an impact brought it to rest): from then on it sinks
      // back under −a_g alone, from (u, 0).
      VectorXd y = integrator->state();
      const int x = FreeMotion::x_index(), n = system().dof();
      const double u_restart = y[x];
      y[n + x] = 0.0;
      integrator->restart(out.t_s, y);
      const double t_restart = out.t_s, t_end = t_restart + 0.3;
      out = step_until(*integrator.integrator, t_end, solvers::StepKind::failure);
      const auto [u, v] = closed_form(u_restart, 0.0, out.t_s - t_restart);
      BOOST_TEST(std::abs(integrator->state()[x] - u) <= tol.displacement_m);
      BOOST_TEST(std::abs(integrator->state()[n + x] - v) <= tol.velocity_mps);
    }
  }
}
