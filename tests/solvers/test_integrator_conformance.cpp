// One suite run over every Integrator behind the seam (integrator.hpp), like Drake's typed
// generic_integrator_test: each case is a small hand-made OdeFunctions with a closed form, and
// each contract of the seam (accuracy, interpolant, stop times, roots, restarts, counters) is
// checked the same way for CVODE (BDF, Adams), ARKODE (ERK; DIRK orders 4 and 3), both Newton
// solvers where they apply (the second-order one also on sparse Jacobian rows), and the exact
// path (free flight, and its held stretch).

// GCC 12 reports -Wrestrict inside Boost.Test's generated case names (std::string operator+,
// libstdc++ code inlined into this file): a known false positive, GCC bug 105329.
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ == 12
#pragma GCC diagnostic ignored "-Wrestrict"
#endif

#include <boost/test/data/monomorphic.hpp>
#include <boost/test/data/test_case.hpp>
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <functional>
#include <memory>
#include <numbers>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "pounding/solvers/arkode_integrator.hpp"
#include "pounding/solvers/cvode_integrator.hpp"
#include "../support/state_space_exact.hpp"

namespace bdata = boost::unit_test::data;
namespace tt = boost::test_tools;
using namespace pounding::solvers;
using Eigen::VectorXd;

namespace {

constexpr double kRtol = 1e-8, kAtol = 1e-10;  // the SUNDIALS integrators' tolerances here
constexpr double kPi = std::numbers::pi;

// ---------------------------------------------------------------------------------------------
// The implementations under test.

using Factory = std::function<std::unique_ptr<Integrator>(OdeFunctions&, double, const VectorXd&)>;

enum class Beyond { throws, extends };  // what interpolate() does outside the last step

struct Method {
  std::string name;
  Factory make;
  /// The tolerances the method works to: the global error of a short run is checked against
  /// global_error_factor · (rtol |y| + atol). The exact path's free flight is exact up to
  /// round-off, its held stretch is CVODE (BDF) at ExactSettings' tolerances.
  double rtol = kRtol, atol = kAtol;
  bool declares_linear = true;  // false sends the exact path down its held (CVODE) stretch
  bool uses_jacobian = true;    // false for the explicit ERK
  Beyond beyond_step = Beyond::throws;
  /// The exact path diagonalises J: a free mass (J = [[0, 1], [0, 0]]) is refused (@throws).
  bool diagonalisable_only = false;
  /// Global error allowed after a short run, in units of the local tolerance rtol |y| + atol:
  /// each step's local error is kept below one such unit (weighted norm ≤ 1), and the runs here
  /// last at most 2 s of a stable, at most lightly damped, system.
  double global_error_factor = 100.0;
};

/// CVODE BDF at the exact path's hold tolerances (rtol 1e-12) takes ~1200 steps on the
/// constant-force case and ends 214 local tolerances off; its global error per tolerance grows
/// as the tolerance tightens (48 at rtol 1e-8, 79 at 1e-10; Adams at 1e-12: 20). Measured with
/// a plain CvodeIntegrator, to the digit the same as the exact path's held stretch.
constexpr double kTightBdfGlobalErrorFactor = 1000.0;

std::ostream& operator<<(std::ostream& out, const Method& method) { return out << method.name; }

Factory cvode(CvodeMethod method, NewtonSolver newton) {
  return [=](OdeFunctions& f, double t0, const VectorXd& y0) {
    return std::make_unique<CvodeIntegrator>(f, CvodeSettings{method, kRtol, kAtol, newton}, t0, y0);
  };
}

Factory arkode(ArkodeMethod method, int order, NewtonSolver newton) {
  return [=](OdeFunctions& f, double t0, const VectorXd& y0) {
    return make_arkode_integrator(f, ArkodeSettings{method, kRtol, kAtol, order, newton}, t0, y0);
  };
}

/// `inner` with OdeFunctions::acceleration_jacobian() provided (the lower half of `inner`'s dense
/// Jacobian, sparse), so the second-order Newton solver takes its sparse-LU path as it does for
/// the coupled buildings; the integrator built on it is owned here and every call forwarded.
class WithSparseRows final : public Integrator {
 public:
  WithSparseRows(OdeFunctions& inner, const Factory& make, double t0, const VectorXd& y0)
      : functions_(inner), integrator_(make(functions_, t0, y0)) {}

  void restart(double t, const VectorXd& y) override { integrator_->restart(t, y); }
  void set_max_step(double h_s) override { integrator_->set_max_step(h_s); }
  void set_stop_time(double t_s) override { integrator_->set_stop_time(t_s); }
  StepOutcome step(double t_final) override { return integrator_->step(t_final); }
  const VectorXd& state() const override { return integrator_->state(); }
  void interpolate(double t, Eigen::Ref<VectorXd> y) override { integrator_->interpolate(t, y); }
  std::vector<int> roots_found() override { return integrator_->roots_found(); }
  IntegratorCounters counters() override { return integrator_->counters(); }

 private:
  class Functions final : public OdeFunctions {
   public:
    explicit Functions(OdeFunctions& inner) : inner_(inner) {}
    int state_size() const override { return inner_.state_size(); }
    int root_count() const override { return inner_.root_count(); }
    bool is_linear() const override { return inner_.is_linear(); }
    void rhs(double t, const Eigen::Ref<const VectorXd>& y, Eigen::Ref<VectorXd> y_dot) override {
      inner_.rhs(t, y, y_dot);
    }
    void jacobian(double t, const Eigen::Ref<const VectorXd>& y, Eigen::Ref<Eigen::MatrixXd> jac) override {
      inner_.jacobian(t, y, jac);
    }
    void roots(double t, const Eigen::Ref<const VectorXd>& y, Eigen::Ref<VectorXd> g) override {
      inner_.roots(t, y, g);
    }
    bool acceleration_jacobian(double t, const Eigen::Ref<const VectorXd>& y,
                               Eigen::SparseMatrix<double>& rows) override {
      Eigen::MatrixXd dense(state_size(), state_size());
      inner_.jacobian(t, y, dense);
      rows = dense.bottomRows(state_size() / 2).sparseView();
      return true;
    }

   private:
    OdeFunctions& inner_;
  };

  Functions functions_;
  std::unique_ptr<Integrator> integrator_;
};

Factory sparse_rows(Factory make) {
  return
      [=](OdeFunctions& f, double t0, const VectorXd& y0) { return std::make_unique<WithSparseRows>(f, make, t0, y0); };
}

Factory exact() {
  return [](OdeFunctions& f, double t0, const VectorXd& y0) {
    return std::make_unique<pounding::testing::StateSpaceExactIntegrator>(f, t0, y0);
  };
}

std::vector<Method> methods() {
  const ExactSettings held;
  return {
      {"cvode-bdf/second-order", cvode(CvodeMethod::bdf, NewtonSolver::second_order)},
      {"cvode-bdf/dense", cvode(CvodeMethod::bdf, NewtonSolver::dense)},
      {"cvode-bdf/sparse", sparse_rows(cvode(CvodeMethod::bdf, NewtonSolver::second_order))},
      {"cvode-adams/second-order", cvode(CvodeMethod::adams, NewtonSolver::second_order)},
      {"cvode-adams/dense", cvode(CvodeMethod::adams, NewtonSolver::dense)},
      {"arkode-erk", arkode(ArkodeMethod::erk, 0, NewtonSolver::second_order), kRtol, kAtol, true, false},
      {"arkode-dirk4/second-order", arkode(ArkodeMethod::dirk, 4, NewtonSolver::second_order)},
      {"arkode-dirk4/dense", arkode(ArkodeMethod::dirk, 4, NewtonSolver::dense)},
      {"arkode-dirk4/sparse", sparse_rows(arkode(ArkodeMethod::dirk, 4, NewtonSolver::second_order))},
      {"arkode-dirk3/second-order", arkode(ArkodeMethod::dirk, 3, NewtonSolver::second_order)},
      {"arkode-dirk3/dense", arkode(ArkodeMethod::dirk, 3, NewtonSolver::dense)},
      // Round-off of the closed form evaluated through an eigendecomposition.
      {"exact/free", exact(), 1e-13, 1e-15, true, true, Beyond::extends, true},
      {"exact/held", exact(), held.hold_rtol, held.hold_atol, false, true, Beyond::throws, false,
       kTightBdfGlobalErrorFactor},
  };
}

// ---------------------------------------------------------------------------------------------
// The problems: independent unit-mass oscillators x_i'' = f_i − k_i x_i − c_i x_i', y = (x, x').

struct Dof {
  double force = 0.0;      // f (m/s²)
  double stiffness = 0.0;  // k (1/s²)
  double damping = 0.0;    // c (1/s), underdamped: c² < 4k when k > 0
};

struct Motion {
  double x, v;
};

/// The closed form of one DOF started at (x0, v0), time tau later.
Motion closed_form(const Dof& d, double x0, double v0, double tau) {
  const double f = d.force, k = d.stiffness, c = d.damping;
  if (k == 0.0 && c == 0.0) return {x0 + v0 * tau + 0.5 * f * tau * tau, v0 + f * tau};
  if (k == 0.0) {  // the velocity relaxes to the terminal f / c
    const double terminal = f / c, decay = std::exp(-c * tau);
    return {x0 + terminal * tau + (v0 - terminal) * (1.0 - decay) / c, terminal + (v0 - terminal) * decay};
  }
  const double omega = std::sqrt(k), zeta = c / (2.0 * omega), omega_d = omega * std::sqrt(1.0 - zeta * zeta);
  const double a = x0 - f / k, b = (v0 + zeta * omega * a) / omega_d;
  const double decay = std::exp(-zeta * omega * tau), cs = std::cos(omega_d * tau), sn = std::sin(omega_d * tau);
  return {f / k + decay * (a * cs + b * sn),
          decay * (-zeta * omega * (a * cs + b * sn) + omega_d * (-a * sn + b * cs))};
}

using RootFunction = std::function<void(double t, const VectorXd& y, Eigen::Ref<VectorXd> g)>;

class Oscillators final : public OdeFunctions {
 public:
  Oscillators(std::vector<Dof> dofs, int root_count, RootFunction roots, bool linear)
      : dofs_(std::move(dofs)), root_count_(root_count), roots_(std::move(roots)), linear_(linear) {}

  int dof() const { return static_cast<int>(dofs_.size()); }
  int state_size() const override { return 2 * dof(); }
  int root_count() const override { return root_count_; }
  bool is_linear() const override { return linear_; }
  /// The phase changes (free flight ↔ held contact) between restarts.
  void set_linear(bool linear) { linear_ = linear; }

  void rhs(double, const Eigen::Ref<const VectorXd>& y, Eigen::Ref<VectorXd> y_dot) override {
    const int n = dof();
    y_dot.head(n) = y.tail(n);
    for (int i = 0; i < n; ++i) {
      y_dot[n + i] = dofs_[i].force - dofs_[i].stiffness * y[i] - dofs_[i].damping * y[n + i];
    }
  }
  void jacobian(double, const Eigen::Ref<const VectorXd>&, Eigen::Ref<Eigen::MatrixXd> jac) override {
    const int n = dof();
    jac.setZero();
    jac.topRightCorner(n, n).setIdentity();
    for (int i = 0; i < n; ++i) {
      jac(n + i, i) = -dofs_[i].stiffness;
      jac(n + i, n + i) = -dofs_[i].damping;
    }
  }
  void roots(double t, const Eigen::Ref<const VectorXd>& y, Eigen::Ref<VectorXd> g) override { roots_(t, y, g); }

  /// The closed-form state at t of the motion that was at y0 at t0.
  VectorXd exact(double t0, const VectorXd& y0, double t) const {
    const int n = dof();
    VectorXd y(2 * n);
    for (int i = 0; i < n; ++i) {
      const Motion m = closed_form(dofs_[i], y0[i], y0[n + i], t - t0);
      y[i] = m.x;
      y[n + i] = m.v;
    }
    return y;
  }

 private:
  std::vector<Dof> dofs_;
  int root_count_;
  RootFunction roots_;
  bool linear_;
};

/// A root function that never changes sign: SUNDIALS wants at least one.
void no_root(double, const VectorXd&, Eigen::Ref<VectorXd> g) { g.setOnes(); }

/// Constant force with a damper, and constant force on a damped spring (period 1 s, 5 %
/// damping), side by side: the problem of the tests that are not about the free mass.
std::vector<Dof> damped_dofs() {
  const double omega = 2.0 * kPi;
  return {{2.0, 0.0, 0.5}, {3.0, omega * omega, 2.0 * 0.05 * omega}};
}

VectorXd damped_start() {
  VectorXd y0(4);
  y0 << -0.2, 0.05, 0.3, -0.4;
  return y0;
}

/// Largest |y_i| of the closed form over [t0, t1] (sampled finely), per component.
VectorXd peak_magnitude(const Oscillators& f, double t0, const VectorXd& y0, double t1) {
  VectorXd peak = y0.cwiseAbs();
  for (int s = 1; s <= 400; ++s) peak = peak.cwiseMax(f.exact(t0, y0, t0 + (t1 - t0) * s / 400.0).cwiseAbs());
  return peak;
}

/// True when |actual − expected| ≤ global_error_factor (rtol peak + atol) in every component.
bool within_tolerance(const Method& m, const VectorXd& actual, const VectorXd& expected, const VectorXd& peak,
                      double* worst_ratio = nullptr) {
  const VectorXd allowed = (m.global_error_factor * (m.rtol * peak.array() + m.atol)).matrix();
  const double ratio = ((actual - expected).cwiseAbs().array() / allowed.array()).maxCoeff();
  if (worst_ratio) *worst_ratio = std::max(*worst_ratio, ratio);
  return ratio <= 1.0;
}

/// The loop's own order after a (re)start: the stop time, then the maximum step.
void begin(Integrator& integrator, double stop_s, double max_step_s) {
  integrator.set_stop_time(stop_s);
  integrator.set_max_step(max_step_s);
}

constexpr double kFar = 1e3;  // a t_final beyond every stop time: only stop times bound steps

}  // namespace

// ---------------------------------------------------------------------------------------------

BOOST_DATA_TEST_CASE(MatchesTheConstantForceClosedFormAtStepsAndInsideThem, bdata::make(methods()), method) {
  // ẍ = F alone (a free mass), with a damper, and on a damped spring, side by side.
  std::vector<Dof> dofs = damped_dofs();
  dofs.insert(dofs.begin(), Dof{-9.81, 0.0, 0.0});
  VectorXd y0(6);
  y0 << 0.1, -0.2, 0.05, 1.5, 0.3, -0.4;
  if (method.diagonalisable_only) {
    Oscillators free_mass(dofs, 1, no_root, method.declares_linear);
    BOOST_CHECK_THROW(method.make(free_mass, 0.3, y0), std::runtime_error);
    dofs.erase(dofs.begin());  // and the rest of the contract on the two damped DOFs
    y0 = damped_start();
  }
  Oscillators f(dofs, 1, no_root, method.declares_linear);
  const double t0 = 0.3, t_end = 2.3;
  const VectorXd peak = peak_magnitude(f, t0, y0, t_end);
  auto integrator = method.make(f, t0, y0);
  begin(*integrator, t_end, 0.05);

  double t_prev = t0, worst = 0.0;
  int steps = 0;
  VectorXd y(y0.size());
  for (StepOutcome out; out.kind != StepKind::stop_time; ++steps) {
    out = integrator->step(kFar);
    BOOST_TEST_REQUIRE((out.kind == StepKind::step || out.kind == StepKind::stop_time), out.failure);
    BOOST_TEST_REQUIRE(steps < 10000);
    BOOST_TEST(within_tolerance(method, integrator->state(), f.exact(t0, y0, out.t_s), peak, &worst),
               "state at t = " << out.t_s);
    for (double s : {0.0, 0.25, 0.5, 0.75, 1.0}) {
      const double t = t_prev + s * (out.t_s - t_prev);
      integrator->interpolate(t, y);
      BOOST_TEST(within_tolerance(method, y, f.exact(t0, y0, t), peak, &worst), "interpolant at t = " << t);
    }
    t_prev = out.t_s;
  }
  BOOST_TEST(t_prev == t_end);
  BOOST_TEST_MESSAGE(method << ": " << steps << " steps, largest error " << worst << " of the allowed");
}

BOOST_DATA_TEST_CASE(CountersRunFromTheLastRestart, bdata::make(methods()), method) {
  Oscillators f(damped_dofs(), 1, no_root, method.declares_linear);
  const VectorXd y0 = damped_start();
  auto integrator = method.make(f, 0.0, y0);
  begin(*integrator, kFar, 0.02);
  const auto take_steps = [&](int count) {
    for (int i = 0; i < count; ++i) {
      const StepOutcome out = integrator->step(kFar);
      BOOST_TEST_REQUIRE((out.kind == StepKind::step), out.failure);
    }
  };
  take_steps(150);  // long enough for SUNDIALS to re-evaluate the Jacobian on its own schedule
  const IntegratorCounters before = integrator->counters();
  BOOST_TEST(before.steps == 150);
  BOOST_TEST_MESSAGE(method << ": " << before.jacobian_evaluations << " Jacobians in 150 steps");

  // Documented (integrator.hpp): right after restart() no step has been taken; what restart()
  // itself evaluated (the exact path's eigendecomposition and forcing) counts in the new stretch.
  VectorXd y = integrator->state();
  y[2] = -y[2];  // an impulse, as after an impact
  integrator->restart(0.7, y);
  begin(*integrator, kFar, 0.02);
  const IntegratorCounters fresh = integrator->counters();
  BOOST_TEST(fresh.steps == 0);
  BOOST_TEST(fresh.error_test_failures == 0);
  BOOST_TEST(fresh.rhs_evaluations <= 2);
  BOOST_TEST(fresh.root_evaluations <= 1);
  BOOST_TEST(fresh.jacobian_evaluations <= 1);

  take_steps(10);
  const IntegratorCounters after = integrator->counters();
  BOOST_TEST(after.steps == 10);
  BOOST_TEST(after.rhs_evaluations >= 1);             // the exact path fits its forcing once per record segment
  BOOST_TEST(after.root_evaluations >= after.steps);  // g at every step's end
  // Ten steps' worth, not 160: nothing carried over from before the restart.
  BOOST_TEST(after.rhs_evaluations <= before.rhs_evaluations);
  BOOST_TEST(after.root_evaluations < before.root_evaluations);
  BOOST_TEST(after.jacobian_evaluations <= before.jacobian_evaluations);
  if (method.uses_jacobian) {
    BOOST_TEST(after.jacobian_evaluations >= 1);
  } else {
    BOOST_TEST(after.jacobian_evaluations == 0);
  }
}

BOOST_DATA_TEST_CASE(HonoursStopTimesExactlyAndOnce, bdata::make(methods()), method) {
  Oscillators f(damped_dofs(), 1, no_root, method.declares_linear);
  const VectorXd y0 = damped_start();
  const VectorXd peak = peak_magnitude(f, 0.0, y0, 1.5);
  auto integrator = method.make(f, 0.0, y0);
  begin(*integrator, 0.3337, 0.05);

  double t_prev = 0.0;
  for (double stop : {0.3337, 0.3338, 0.9001}) {
    integrator->set_stop_time(stop);
    for (StepOutcome out; out.kind != StepKind::stop_time;) {
      out = integrator->step(kFar);
      BOOST_TEST_REQUIRE((out.kind == StepKind::step || out.kind == StepKind::stop_time), out.failure);
      BOOST_TEST_REQUIRE(out.t_s <= stop, "stepped to " << out.t_s << " past the stop time " << stop);
      BOOST_TEST_REQUIRE(out.t_s > t_prev);
      t_prev = out.t_s;
    }
    BOOST_TEST(t_prev == stop);  // bit for bit: the loop compares it with a record knot
    BOOST_TEST(within_tolerance(method, integrator->state(), f.exact(0.0, y0, stop), peak));
  }
  // Documented: a stop time applies once. With none set, the next step goes past it.
  const StepOutcome next = integrator->step(kFar);
  BOOST_TEST((next.kind == StepKind::step));
  BOOST_TEST(next.t_s > 0.9001);
}

BOOST_DATA_TEST_CASE(InterpolatesOnlyWithinTheLastStep, bdata::make(methods()), method) {
  const double omega = 2.0 * kPi;
  Oscillators f({{0.0, omega * omega, 0.0}, {1.0, 0.0, 0.5}}, 1, no_root, method.declares_linear);
  VectorXd y0(4);
  y0 << 0.05, 0.0, 0.0, 0.2;
  const VectorXd peak = peak_magnitude(f, 0.0, y0, 1.0);
  auto integrator = method.make(f, 0.0, y0);
  begin(*integrator, kFar, 0.04);
  double t_prev = 0.0;
  VectorXd y(4);
  for (int i = 0; i < 20; ++i) {
    const StepOutcome out = integrator->step(kFar);
    BOOST_TEST_REQUIRE((out.kind == StepKind::step), out.failure);
    // At the step's end the interpolant is the state itself (to round-off).
    integrator->interpolate(out.t_s, y);
    BOOST_TEST((y - integrator->state()).cwiseAbs().maxCoeff() <= 1e-14 * peak.maxCoeff());
    for (double s : {0.1, 0.3, 0.5, 0.7, 0.9}) {
      const double t = t_prev + s * (out.t_s - t_prev);
      integrator->interpolate(t, y);
      BOOST_TEST(within_tolerance(method, y, f.exact(0.0, y0, t), peak), "t = " << t);
    }
    // Outside the last step (half a step either side): documented in integrator.hpp.
    const double h = out.t_s - t_prev;
    for (double t : {t_prev - 0.5 * h, out.t_s + 0.5 * h}) {
      if (method.beyond_step == Beyond::throws) {
        BOOST_CHECK_THROW(integrator->interpolate(t, y), std::runtime_error);
      } else {
        integrator->interpolate(t, y);
        BOOST_TEST(within_tolerance(method, y, f.exact(0.0, y0, t), peak), "closed form extended to t = " << t);
      }
    }
    t_prev = out.t_s;
  }
}

BOOST_DATA_TEST_CASE(ReportsRootsOnlyWhenClosing, bdata::make(methods()), method) {
  // x = A sin ωt; the gap g = x − A/2 opens (crosses zero upwards) at ωt = π/6 and closes
  // (downwards) at 5π/6, opens at 13π/6 and closes at 17π/6.
  const double omega = 2.0 * kPi, amplitude = 0.05;
  const auto gap = [amplitude](double, const VectorXd& y, Eigen::Ref<VectorXd> g) { g[0] = y[0] - amplitude / 2; };
  Oscillators f({{0.0, omega * omega, 0.0}}, 1, gap, method.declares_linear);
  VectorXd y0(2);
  y0 << 0.0, amplitude * omega;
  const VectorXd peak = peak_magnitude(f, 0.0, y0, 1.5);
  auto integrator = method.make(f, 0.0, y0);
  begin(*integrator, kFar, 0.02);

  // Position error → time error through the closing speed |ẋ| = Aω cos(π/6).
  const double t_tolerance =
      method.global_error_factor * (method.rtol * amplitude + method.atol) / (amplitude * omega * 0.866);
  for (double expected : {5.0 * kPi / (6.0 * omega), 17.0 * kPi / (6.0 * omega)}) {
    StepOutcome out;
    for (int i = 0; i < 10000 && out.kind == StepKind::step; ++i) out = integrator->step(kFar);
    BOOST_TEST_REQUIRE((out.kind == StepKind::root), "kind " << int(out.kind) << " " << out.failure);
    BOOST_TEST(std::abs(out.t_s - expected) <= t_tolerance, "root at " << out.t_s << ", expected " << expected);
    BOOST_TEST(integrator->roots_found() == std::vector<int>{-1}, tt::per_element());
    BOOST_TEST(within_tolerance(method, integrator->state(), f.exact(0.0, y0, out.t_s), peak));
    integrator->restart(out.t_s, integrator->state());  // the loop restarts after every root
    begin(*integrator, kFar, 0.02);
  }
}

BOOST_DATA_TEST_CASE(ListsCoincidentRootsTogether, bdata::make(methods()), method) {
  // Two identical damped oscillators from the same state (a flush face meeting a wall: two
  // vertices at once). x + A/2 closes for both at the same instant; its negative opens there
  // (not listed); x + 0.9 A closes later (not listed yet).
  const double omega = 2.0 * kPi, amplitude = 0.05;
  const auto gaps = [amplitude](double, const VectorXd& y, Eigen::Ref<VectorXd> g) {
    g << y[0] + amplitude / 2, y[1] + amplitude / 2, -(y[1] + amplitude / 2), y[0] + 0.9 * amplitude;
  };
  const Dof spring{0.0, omega * omega, 0.02 * omega};
  Oscillators f({spring, spring}, 4, gaps, method.declares_linear);
  VectorXd y0(4);
  y0 << 0.0, 0.0, amplitude * omega, amplitude * omega;
  auto integrator = method.make(f, 0.0, y0);
  begin(*integrator, kFar, 0.03);
  StepOutcome out;
  for (int i = 0; i < 10000 && out.kind == StepKind::step; ++i) out = integrator->step(kFar);
  BOOST_TEST_REQUIRE((out.kind == StepKind::root), out.failure);
  const VectorXd expected = f.exact(0.0, y0, out.t_s);
  BOOST_TEST(std::abs(expected[0] + amplitude / 2) <=
             method.global_error_factor * (method.rtol * amplitude + method.atol));
  BOOST_TEST(integrator->roots_found() == (std::vector<int>{-1, -1, 0, 0}), tt::per_element());
}

BOOST_DATA_TEST_CASE(ReportsEachOfTwoRootsAtTheSameInstantOnce, bdata::make(methods()), method) {
  // x₁ = v₁(1 − e^{−t}) (a damper) and x₂ = (v₂/2) sin 2t (a spring) both reach 1 at t = 0.5 in
  // exact arithmetic, by different arithmetic. Gaps 1 − x₁ and 1 − x₂ close there; x₂ − 1
  // opens there (never listed); 1.1 − x₂ closes later. The integration error separates the two
  // closings by about the tolerance, far more than the root finder's round-off tolerance: they
  // may come in one root return or in two consecutive ones, each at 0.5 within tolerance.
  const double t_meet = 0.5;
  const auto gaps = [](double, const VectorXd& y, Eigen::Ref<VectorXd> g) {
    g << 1.0 - y[0], 1.0 - y[1], y[1] - 1.0, 1.1 - y[1];
  };
  Oscillators f({{0.0, 0.0, 1.0}, {0.0, 4.0, 0.0}}, 4, gaps, method.declares_linear);
  VectorXd y(4);
  y << 0.0, 0.0, 1.0 / (1.0 - std::exp(-t_meet)), 2.0 / std::sin(2.0 * t_meet);
  auto integrator = method.make(f, 0.0, y);
  begin(*integrator, kFar, 0.03);
  // Closing speeds there: 1.54 and 1.28 m/s.
  const double t_tolerance = method.global_error_factor * (method.rtol * 1.0 + method.atol) / 1.28;
  std::vector<int> times_listed(4, 0);
  int returns = 0;
  for (; times_listed[0] == 0 || times_listed[1] == 0; ++returns) {
    StepOutcome out;
    for (int i = 0; i < 10000 && out.kind == StepKind::step; ++i) out = integrator->step(kFar);
    BOOST_TEST_REQUIRE((out.kind == StepKind::root), out.failure);
    BOOST_TEST_REQUIRE(std::abs(out.t_s - t_meet) <= t_tolerance, "root at " << out.t_s);
    const std::vector<int> found = integrator->roots_found();
    for (int i = 0; i < 4; ++i) times_listed[i] += found[i] != 0;
    BOOST_TEST(found[0] + found[1] < 0);  // every return lists at least one of the two
    integrator->restart(out.t_s, integrator->state());
    begin(*integrator, kFar, 0.03);
  }
  BOOST_TEST(times_listed == (std::vector<int>{1, 1, 0, 0}), tt::per_element());
  BOOST_TEST_MESSAGE(method << ": the two closings came in " << returns << " root return(s)");
}

namespace {

/// A ball under gravity with linear drag (ẍ = −9.81 − 0.5 ẋ) dropped from 1 m onto the floor
/// g = x; each impact reverses the velocity with restitution 0.7; four bounces. With
/// `alternate_phases` every restart flips OdeFunctions::is_linear(), so the exact path switches
/// between its closed form and its held (CVODE) stretch. Closed-form impact instants:
/// bisection of the closed-form flight x(τ) = 0 from each exact rebound.
void check_bounces(const Method& method, bool alternate_phases) {
  const Dof ball{-9.81, 0.0, 0.5};
  const auto floor_gap = [](double, const VectorXd& y, Eigen::Ref<VectorXd> g) { g[0] = y[0]; };
  Oscillators f({ball}, 1, floor_gap, method.declares_linear);
  const double restitution = 0.7;
  VectorXd y(2);
  y << 1.0, 0.0;
  auto integrator = method.make(f, 0.0, y);
  begin(*integrator, kFar, 0.02);

  double t_exact = 0.0, v_exact = 0.0, x_exact = 1.0;  // the exact start of each flight
  for (int bounce = 0; bounce < 4; ++bounce) {
    // The flight's landing: first zero of x after the apex.
    double lo = 1e-9, hi = 10.0;
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      const Motion m = closed_form(ball, x_exact, v_exact, mid);
      (m.x > 0.0 || m.v > 0.0 ? lo : hi) = mid;
    }
    const double landing = t_exact + hi;
    const double impact_speed = -closed_form(ball, x_exact, v_exact, hi).v;

    StepOutcome out;
    for (int i = 0; i < 10000 && out.kind == StepKind::step; ++i) out = integrator->step(kFar);
    BOOST_TEST_REQUIRE((out.kind == StepKind::root), "bounce " << bounce << ": " << out.failure);
    // Errors of the earlier flights carry over: allow the tolerance once per flight flown.
    const double t_tolerance =
        (bounce + 1) * method.global_error_factor * (method.rtol * 1.0 + method.atol) / impact_speed;
    BOOST_TEST(std::abs(out.t_s - landing) <= t_tolerance,
               "bounce " << bounce << " at " << out.t_s << ", expected " << landing);
    BOOST_TEST(integrator->roots_found() == std::vector<int>{-1}, tt::per_element());

    y = integrator->state();
    y[1] = -restitution * y[1];
    if (alternate_phases) f.set_linear(!f.is_linear());
    integrator->restart(out.t_s, y);
    begin(*integrator, kFar, 0.02);
    BOOST_TEST(integrator->state() == y, tt::per_element());
    BOOST_TEST(integrator->counters().steps == 0);
    t_exact = landing;
    x_exact = 0.0;
    v_exact = restitution * impact_speed;
  }
}

}  // namespace

BOOST_DATA_TEST_CASE(RestartsAfterAnImpulseAndFindsTheNextBounces, bdata::make(methods()), method) {
  check_bounces(method, false);
}

BOOST_AUTO_TEST_CASE(ExactPathSwitchesBetweenItsClosedFormAndItsHeldStretches) {
  // Odd flights are integrated by the held stretch: its tolerances bound the whole run.
  const ExactSettings held;
  check_bounces({"exact/alternating", exact(), held.hold_rtol, held.hold_atol}, true);
}
