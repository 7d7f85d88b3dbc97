#define BOOST_TEST_MODULE hht
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <numbers>

#include "../support/two_slabs.hpp"
#include "pounding/analysis/run_scene.hpp"
#include "pounding/io/scene_reader.hpp"
#include "pounding/solvers/hht.hpp"

namespace tt = boost::test_tools;
using namespace pounding;
using solvers::HhtStepper;

namespace {

constexpr double kOmega = 2.0 * std::numbers::pi;  // 1 Hz

/// A single-DOF oscillator u'' + 2ζω u' + ω² u = 0 with the HHT stepper.
HhtStepper oscillator(double zeta, double alpha) {
  return HhtStepper(Eigen::VectorXd::Ones(1), Eigen::MatrixXd::Constant(1, 1, 2 * zeta * kOmega),
                    Eigen::MatrixXd::Constant(1, 1, kOmega * kOmega),
                    [](double, Eigen::Ref<Eigen::VectorXd> f) { f.setZero(); }, alpha);
}

/// u(t) after n steps of size h from u = 1, u' = 0.
HhtStepper::State run(HhtStepper& stepper, double h, int n) {
  HhtStepper::State s = stepper.at(0.0, Eigen::VectorXd::Ones(1), Eigen::VectorXd::Zero(1));
  for (int i = 0; i < n; ++i) s = stepper.step(s, h);
  return s;
}

double energy(const HhtStepper::State& s) { return 0.5 * (s.v[0] * s.v[0] + kOmega * kOmega * s.d[0] * s.d[0]); }

}  // namespace

BOOST_AUTO_TEST_CASE(ConvergesAtSecondOrderToTheDampedOscillator) {
  const double zeta = 0.05, alpha = -0.1, t_end = 2.0;
  const double omega_d = kOmega * std::sqrt(1 - zeta * zeta);
  const double exact = std::exp(-zeta * kOmega * t_end) *
                       (std::cos(omega_d * t_end) + zeta * kOmega / omega_d * std::sin(omega_d * t_end));
  double previous_error = 0.0;
  for (int n : {200, 400, 800, 1600}) {
    HhtStepper stepper = oscillator(zeta, alpha);
    const double error = std::abs(run(stepper, t_end / n, n).d[0] - exact);
    if (previous_error > 0.0) BOOST_TEST(previous_error / error == 4.0, tt::tolerance(0.1));
    previous_error = error;
  }
}

BOOST_AUTO_TEST_CASE(TrapezoidalRulePeriodElongationIsExact) {
  // α = 0 is the average-acceleration rule: free vibration advances by exactly 2 atan(Ω/2) per
  // step, so T̄/T = Ω / (2 atan(Ω/2)) ≈ 1 + Ω²/12.
  const double h = 0.05, big_omega = kOmega * h;
  HhtStepper stepper = oscillator(0.0, 0.0);
  HhtStepper::State s = stepper.at(0.0, Eigen::VectorXd::Ones(1), Eigen::VectorXd::Zero(1));
  for (int n = 1; n <= 200; ++n) {
    s = stepper.step(s, h);
    BOOST_TEST(s.d[0] == std::cos(n * 2 * std::atan(big_omega / 2)), tt::tolerance(1e-9));
  }
  BOOST_TEST(big_omega / (2 * std::atan(big_omega / 2)) - 1 == big_omega * big_omega / 12, tt::tolerance(0.02));
}

BOOST_AUTO_TEST_CASE(NumericalDampingGrowsWithAlphaAndIsThirdOrderInOmega) {
  // HHT-α is second-order accurate, so its algorithmic damping ratio ξ̄ is O(Ω³) at low
  // frequency (plain Newmark with γ = ½ − α would give the first-order −αΩ/2): halving Ω = ωh
  // divides ξ̄ by 8. ξ̄ grows with |α| and is zero for α = 0. Measured from the energy decay of
  // free vibration, E ∝ exp(−2ξ̄ω t).
  auto damping_ratio = [](double alpha, double h) {
    const int steps = static_cast<int>(std::lround(20.0 / h));  // 20 periods
    HhtStepper stepper = oscillator(0.0, alpha);
    return -std::log(energy(run(stepper, h, steps)) / energy(run(stepper, h, 0))) / (2 * kOmega * h * steps);
  };
  double previous = 0.0;
  for (double alpha : {0.0, -0.05, -0.1, -0.2, -1.0 / 3.0}) {
    const double coarse = damping_ratio(alpha, 0.02), fine = damping_ratio(alpha, 0.01);
    if (alpha == 0.0) {
      BOOST_TEST(std::abs(coarse) < 1e-10);
    } else {
      BOOST_TEST(coarse / fine == 8.0, tt::tolerance(0.05));
      BOOST_TEST(coarse > previous);
    }
    previous = coarse;
  }
}

BOOST_AUTO_TEST_CASE(StableForStepsFarLongerThanThePeriod) {
  // Ω = 1000. Unconditional stability: nothing grows over time and the displacement never
  // exceeds its initial amplitude. (For α < 0 the velocity has a large transient in the first
  // steps, h·a with a ∝ ω², which the amplification matrix then damps: its spectral radius at
  // Ω → ∞ is (1 + α)/(1 − α) < 1.)
  for (double alpha : {0.0, -0.1, -1.0 / 3.0}) {
    HhtStepper stepper = oscillator(0.0, alpha);
    HhtStepper::State s = stepper.at(0.0, Eigen::VectorXd::Ones(1), Eigen::VectorXd::Zero(1));
    double first_half = 0.0, second_half = 0.0;
    for (int n = 1; n <= 1000; ++n) {
      s = stepper.step(s, 1000.0 / kOmega);
      BOOST_TEST_REQUIRE(std::abs(s.d[0]) <= 1.0 + 1e-9);
      double& peak = n <= 500 ? first_half : second_half;
      peak = std::max(peak, energy(s));
    }
    BOOST_TEST(second_half <= first_half * (1 + 1e-9));
    if (alpha < 0.0) BOOST_TEST(std::abs(s.d[0]) < 1e-50);
  }
}

BOOST_AUTO_TEST_CASE(StepHalvingLocatesAFreeFlightContactWithinTheTolerance) {
  // Building 1 (T = 10⁴ s: free flight) at 1 m/s towards a 10⁹ t block 0.0737 m away: contact at
  // t_c = 0.0737 s, inside the second 0.05 s step. Halving must end with the contact within
  // 1e-4 m, i.e. within 1e-4 s, after about log2(Δt·v/tol) = log2(500) ≈ 9 halvings.
  const double gap = 0.0737, v = 1.0, tol = 1e-4, dt = 0.05;
  const auto system = testing::two_slabs({1.0, 1e4, 0.0}, testing::diamond(gap), {1e9, 0.01, 0.9}, gap, 0.2);
  solvers::HhtOptions options;
  options.dt_s = dt;
  options.contact_tolerance_m = tol;
  options.initial_state = testing::pushed(system, v);
  const auto result = solvers::run_hht(system, options, "hht");
  BOOST_TEST_REQUIRE(!result.impacts.empty());
  const double t_contact = gap / v;
  BOOST_TEST(std::abs(result.impacts[0].t_s - t_contact) <= tol / v);
  const double expected_halvings = std::log2(dt * v / tol);
  BOOST_TEST(std::abs(result.statistics.halvings - expected_halvings) <= 1.0);
  BOOST_TEST(result.statistics.unresolved_contacts == 0);
}

BOOST_AUTO_TEST_CASE(PaperSceneImpactTimesConvergeToCvodeAsTheStepShrinks) {
  // Reference: CVODE BDF at rtol 1e-11. The interpolating variant converges; halving stops
  // improving at the contact tolerance (its contact instant is only known to tol/|ġ|, here
  // 1e-4 m / 0.83 m/s ≈ 1.2e-4 s); applying impacts at step ends is first order in Δt.
  auto scene = io::read_scene(POUNDING_EXAMPLES_DIR "/paper/paper.toml");
  scene.solver.rtol = 1e-11;
  scene.solver.atol = 1e-13;
  const auto reference = analysis::run_scene(scene).result;
  BOOST_TEST_REQUIRE(!reference.impacts.empty());
  const double t_ref = reference.impacts[0].t_s, v_ref = reference.impacts[0].approach_velocity_mps;

  scene.solver.method = "hht";
  auto first_impact_error = [&](double dt, const char* location) {
    scene.solver.dt_s = dt;
    scene.solver.event_location = location;
    const auto result = analysis::run_scene(scene).result;
    BOOST_TEST_REQUIRE(!result.impacts.empty());
    const double error = std::abs(result.impacts[0].t_s - t_ref);
    BOOST_TEST_MESSAGE(location << " dt = " << dt << " s: first impact error " << error << " s");
    return error;
  };
  double previous = 1.0;
  for (double dt : {0.05, 0.01, 0.002, 0.0005}) {
    const double error = first_impact_error(dt, "interpolate");
    BOOST_TEST(error < previous);
    previous = error;
  }
  BOOST_TEST(previous < 1e-6);
  for (double dt : {0.01, 0.002, 0.0005}) {
    BOOST_TEST(first_impact_error(dt, "halving") < 2 * scene.solver.contact_tolerance_m / v_ref);
  }
  BOOST_TEST(first_impact_error(0.002, "end-of-step") > first_impact_error(0.002, "interpolate"));
}
