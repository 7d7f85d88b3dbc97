#include <boost/test/unit_test.hpp>

#include <cmath>
#include <numbers>

#include "../support/two_slabs.hpp"
#include "pounding/analysis/run_scene.hpp"
#include "pounding/io/scene_reader.hpp"

namespace tt = boost::test_tools;
using namespace pounding;
using namespace pounding::testing;

namespace {

/// Closed-form response of u'' + 2ζωu' + ω²u = −a_g(t) from rest, a_g piecewise linear through
/// (times, accel), evaluated at t: the classical segment-by-segment solution, in real arithmetic.
double sdof_response(double omega, double zeta, const std::vector<double>& times, const std::vector<double>& accel,
                     double t) {
  const double omega_d = omega * std::sqrt(1 - zeta * zeta);
  double u = 0.0, v = 0.0;
  for (std::size_t k = 0; k + 1 < times.size(); ++k) {
    const double slope = (accel[k + 1] - accel[k]) / (times[k + 1] - times[k]);
    const double tau = std::min(t, times[k + 1]) - times[k];
    // Particular solution of u'' + 2ζωu' + ω²u = −(a_k + s τ): u_p = p0 + p1 τ.
    const double p1 = -slope / (omega * omega);
    const double p0 = -(accel[k] + 2 * zeta * omega * p1) / (omega * omega);
    const double a = u - p0, b = (v - p1 + zeta * omega * a) / omega_d;
    const double decay = std::exp(-zeta * omega * tau), c = std::cos(omega_d * tau), s = std::sin(omega_d * tau);
    u = p0 + p1 * tau + decay * (a * c + b * s);
    v = p1 + decay * ((-zeta * omega) * (a * c + b * s) + omega_d * (-a * s + b * c));
    if (t <= times[k + 1]) break;
  }
  return u;
}

// The oscillator the closed form describes: slab 1 of two_slabs, far from slab 2 (no contact).
constexpr double kPeriodS = 0.5, kZeta = 0.05, kOmega = 2 * std::numbers::pi / kPeriodS;

/// Both forms of the exact path: the state-space propagator and the modal one (the method's).
enum class Form { state_space, modal };
constexpr Form kForms[] = {Form::state_space, Form::modal};
const char* name(Form form) { return form == Form::modal ? "modal" : "state-space"; }
solvers::IntegratorFactory exact_path(Form form, const dynamics::CoupledSystem& system) {
  return form == Form::modal ? modal_exact(system) : exact();
}

/// The exact path's run of that oscillator under a_g through (times, accel), steps of T/16.
solvers::RunResult run_oscillator(const std::vector<double>& times, const std::vector<double>& accel, Form form) {
  const auto system = two_slabs({100, kPeriodS, kZeta}, diamond(10.0), {1e4, 0.2, 0.05}, 10.0,
                                excitation::GroundMotion(times, accel, 0.0));
  solvers::EventOptions options;
  options.max_step_s = kPeriodS / 16;
  options.history_interval_s = 0.005;
  auto result = solvers::run_event_driven(system, options, exact_path(form, system), "exact");
  BOOST_TEST_REQUIRE(solvers::to_string(result.status) == "completed");
  return result;
}

void check_against_closed_form(const std::vector<double>& times, const std::vector<double>& accel, Form form) {
  BOOST_TEST_CONTEXT(name(form)) {
    const solvers::RunResult result = run_oscillator(times, accel, form);
    const auto& h = result.history;
    const auto column = std::find(h.columns.begin(), h.columns.end(), "B1_f1_u_m") - h.columns.begin() - 1;
    double peak = 0.0, worst = 0.0;
    for (std::size_t r = 0; r < h.time_s.size(); ++r) {
      const double expected = sdof_response(kOmega, kZeta, times, accel, h.time_s[r]);
      peak = std::max(peak, std::abs(expected));
      worst = std::max(worst, std::abs(h.rows[r][column] - expected));
    }
    BOOST_TEST_MESSAGE("largest error " << worst << " m of a peak " << peak << " m");
    BOOST_TEST(peak > 1e-3);
    BOOST_TEST(worst <= 1e-12 * peak);
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(ReproducesTheClosedFormResponseToARamp) {
  for (Form form : kForms) check_against_closed_form({0.0, 1.5}, {0.0, 3.0}, form);
}

BOOST_AUTO_TEST_CASE(ReproducesTheClosedFormResponseToAPiecewiseLinearInput) {
  for (Form form : kForms) {
    check_against_closed_form({0.0, 0.1, 0.25, 0.4, 0.6, 0.61, 1.2}, {0.0, 2.0, -1.0, 0.6, 0.0, 1.5, 0.0}, form);
  }
}

BOOST_AUTO_TEST_CASE(FindsThePeakBetweenStepEndsAndSamples) {
  // The peak of |u| of the closed form (grid of 1e-4 s, then golden section to 1e-12 s) against
  // the run's: located on the trajectory, not taken at step ends (steps of T/16 would miss it by
  // up to 2 %) or history samples (every 5 ms: up to 5e-4 of it).
  const std::vector<double> times{0.0, 0.1, 0.25, 0.4, 0.6, 0.61, 1.2}, accel{0.0, 2.0, -1.0, 0.6, 0.0, 1.5, 0.0};
  auto magnitude = [&](double t) { return std::abs(sdof_response(kOmega, kZeta, times, accel, t)); };
  double t_best = 0.0;
  for (double t = 0.0; t <= 1.2; t += 1e-4) t_best = magnitude(t) > magnitude(t_best) ? t : t_best;
  double a = std::max(0.0, t_best - 1e-4), b = std::min(1.2, t_best + 1e-4);
  const double inv_phi = (std::sqrt(5.0) - 1) / 2;
  while (b - a > 1e-12) {
    const double c = b - inv_phi * (b - a), d = a + inv_phi * (b - a);
    (magnitude(c) > magnitude(d) ? b : a) = magnitude(c) > magnitude(d) ? d : c;
  }
  const double expected = magnitude(0.5 * (a + b));
  for (Form form : kForms) {
    BOOST_TEST_CONTEXT(name(form)) {
      const solvers::RunResult result = run_oscillator(times, accel, form);
      const auto& peak = result.peaks[0].floors[0].u_m;
      BOOST_TEST_MESSAGE("peak " << std::abs(peak.value) << " m at " << peak.t_s << " s; closed form " << expected
                                 << " m at " << 0.5 * (a + b) << " s");
      BOOST_TEST(std::abs(std::abs(peak.value) - expected) <= 1e-10 * expected);
      BOOST_TEST(std::abs(peak.t_s - 0.5 * (a + b)) <= 1e-5);
    }
  }
}

BOOST_AUTO_TEST_CASE(CatchesAGapThatDipsAHairBelowZeroInsideOneStep) {
  // Free vibration whose amplitude exceeds the gap by 1 nm: the gap is below zero for a few
  // microseconds, far inside one bracketing step; only the examination of the gap's minimum
  // finds it. One nanometre short of the gap it must be a touch, not an impact.
  const double gap = 0.05, period = 0.5, omega = 2 * std::numbers::pi / period;
  for (const auto& [excess, form] : {std::pair{+1e-9, Form::state_space}, std::pair{-1e-9, Form::state_space},
                                     std::pair{+1e-9, Form::modal}, std::pair{-1e-9, Form::modal}}) {
    const auto system = two_slabs({100, period, 0.0}, diamond(gap), {1e4, 0.2, 0.05}, gap, 0.3);
    solvers::EventOptions options;
    options.initial_state = pushed(system, (gap + excess) * omega);
    options.max_step_s = period / 16.7;  // no step may end at the minimum (T/4)
    const auto result = solvers::run_event_driven(system, options, exact_path(form, system), "exact");
    BOOST_TEST_CONTEXT("excess " << excess << ", " << name(form)) {
      if (excess > 0) {
        BOOST_TEST_REQUIRE(result.impacts.size() == 1u);
        BOOST_TEST(result.impacts[0].t_s == period / 4, tt::tolerance(1e-3));
        BOOST_TEST(result.statistics.interpolant_events == 1);
      } else {
        BOOST_TEST(result.impacts.empty());
        BOOST_TEST(result.touches.size() == 1u);
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(AgreesWithCvodeOnThePaperSceneImpacts) {
  // Up to the first sustained contact both solve the same linear model: agreement to 1e-8 s.
  // A hold is nonlinear (rotating contact geometry); the exact path re-linearises it every
  // step, so afterwards the two differ by that approximation: impacts faster than 1 cm/s stay
  // within 1e-5 s (measured 2.4e-6 s).
  auto scene = io::read_scene(POUNDING_EXAMPLES_DIR "/paper/paper.toml");
  scene.solver.rtol = 1e-11;
  scene.solver.atol = 1e-13;
  const auto cvode_run = analysis::run_scene(scene).result;
  scene.solver = analysis::with_method(scene.solver, "exact");  // rtol and atol are CVODE's only
  const auto exact_run = analysis::run_scene(scene).result;
  BOOST_TEST_REQUIRE(exact_run.impacts.size() == cvode_run.impacts.size());
  bool held = false;
  for (std::size_t i = 0; i < exact_run.impacts.size(); ++i) {
    const auto& a = cvode_run.impacts[i];
    const auto& b = exact_run.impacts[i];
    BOOST_TEST(a.level == b.level);
    const double dt = std::abs(a.t_s - b.t_s);
    if (!held) BOOST_TEST(dt < 1e-8);
    if (a.approach_velocity_mps > 0.01) BOOST_TEST(dt < 1e-5);
    held = held || a.starts_hold;
  }
  BOOST_TEST(std::abs(exact_run.energy.residual_kJ()) < 1e-6 * exact_run.energy.input_kJ);
}
