#include <boost/test/unit_test.hpp>

#include <cmath>

#include "../support/two_slabs.hpp"
#include "pounding/analysis/run_scene.hpp"
#include "pounding/io/scene_reader.hpp"

namespace tt = boost::test_tools;
using namespace pounding;
using namespace pounding::testing;

namespace {

/// Bisection to round-off for f(a) < 0 < f(b) (or the reverse).
template <typename F>
double bisect(F f, double a, double b) {
  const bool rising = f(a) < 0.0;
  for (int i = 0; i < 200; ++i) {
    const double m = 0.5 * (a + b);
    if ((f(m) < 0.0) == rising)
      a = m;
    else
      b = m;
  }
  return 0.5 * (a + b);
}

// A pressing set-up: building 1 is a free mass (T = 10⁴ s, its spring force is ~10⁻⁹ of the
// push), building 2 a 10⁹ t block (its recoil ~10⁻⁹ of the impact velocities) on a stiff,
// heavily damped storey (T = 0.01 s, ζ = 0.9) that settles A/ω² further away within
// milliseconds. a_g = −A pushes both towards +x.
struct Pressed {
  static constexpr double gap = 0.01, accel = 1.0;
  dynamics::CoupledSystem system = two_slabs({1.0, 1e4, 0.0}, diamond(gap), {1e9, 0.01, 0.9}, gap, 1.0, -accel);
  double effective_gap() const {
    const double omega = 2 * std::numbers::pi / 0.01;
    return gap + accel / (omega * omega);
  }
};

}  // namespace

BOOST_AUTO_TEST_CASE(ContactTimeMatchesDampedOscillatorClosedForm) {
  // Building 1 in free vibration from u̇(0) = v0 towards a heavy neighbour that stays at rest
  // until the first contact: u(t) = v0/ω_d e^{−ζωt} sin ω_d t reaches the gap at t_c.
  const double gap = 0.05, v0 = 1.0, zeta = 0.05, period = 0.5;
  const auto system = two_slabs({100, period, zeta}, diamond(gap), {1e4, 0.2, 0.05}, gap, 0.5);
  BOOST_TEST_REQUIRE(system.candidates().size() == 1u);
  solvers::EventOptions options;
  options.initial_state = pushed(system, v0);
  const auto result = solvers::run_event_driven(system, options, cvode(1e-11, 1e-13), "cvode-bdf");

  const double omega = 2 * std::numbers::pi / period, omega_d = omega * std::sqrt(1 - zeta * zeta);
  auto u = [&](double t) { return v0 / omega_d * std::exp(-zeta * omega * t) * std::sin(omega_d * t); };
  auto u_dot = [&](double t) {
    return v0 * std::exp(-zeta * omega * t) * (std::cos(omega_d * t) - zeta * omega / omega_d * std::sin(omega_d * t));
  };
  const double t_contact = bisect([&](double t) { return u(t) - gap; }, 0.0, 0.25 * period);

  BOOST_TEST_REQUIRE(!result.impacts.empty());
  BOOST_TEST(std::abs(result.impacts[0].t_s - t_contact) < 1e-9);
  BOOST_TEST(result.impacts[0].approach_velocity_mps == u_dot(t_contact), tt::tolerance(1e-7));
  BOOST_TEST(result.impacts[0].separation_velocity_mps == 0.5 * result.impacts[0].approach_velocity_mps,
             tt::tolerance(1e-9));
}

BOOST_AUTO_TEST_CASE(GrazingContactIsATouchNotAnImpact) {
  // Undamped, amplitude v0/ω one hundred-billionth of a metre short of the gap: the gap's
  // minimum lies inside a step, where CVODE sees no sign change; the interpolant check finds it.
  const double gap = 0.05, period = 0.5, omega = 2 * std::numbers::pi / period;
  const auto system = two_slabs({100, period, 0.0}, diamond(gap), {1e4, 0.2, 0.05}, gap, 0.2);
  solvers::EventOptions options;
  options.initial_state = pushed(system, (gap - 1e-11) * omega);
  const auto result = solvers::run_event_driven(system, options, cvode(1e-11, 1e-13), "cvode-bdf");
  BOOST_TEST(result.impacts.empty());
  BOOST_TEST_REQUIRE(result.touches.size() == 1u);
  BOOST_TEST(result.touches[0].t_s == period / 4, tt::tolerance(1e-6));
  BOOST_TEST(std::abs(result.touches[0].gap_rate_mps) < 1e-6);
}

BOOST_AUTO_TEST_CASE(CrossingAnEdgeExtensionIsNotAContact) {
  // Building 2 starts 0.5 m above building 1's top corner: the corner crosses the line of
  // building 2's facing edge beyond its end, and building 2's corner crosses building 1's.
  const auto system = two_slabs({100, 0.5, 0.05}, box(0.1, 10.5, 10.1, 20.5), {1e4, 0.2, 0.05}, 0.1, 1.0);
  BOOST_TEST_REQUIRE(system.candidates().size() >= 2u);
  solvers::EventOptions options;
  options.initial_state = pushed(system, 2.0);  // amplitude 0.16 m > 0.1 m
  const auto result = solvers::run_event_driven(system, options, cvode(1e-9, 1e-11), "cvode-bdf");
  BOOST_TEST(solvers::to_string(result.status) == "completed");
  BOOST_TEST(result.impacts.empty());
  BOOST_TEST(result.touches.empty());
  BOOST_TEST(result.statistics.off_segment_crossings >= 2);
}

BOOST_AUTO_TEST_CASE(PlasticImpactUnderPressureEndsInSustainedContact) {
  const Pressed pressed;
  solvers::EventOptions options;
  options.restitution = 0.0;
  const auto result = solvers::run_event_driven(pressed.system, options, cvode(1e-10, 1e-12), "cvode-bdf");
  BOOST_TEST(solvers::to_string(result.status) == "completed");
  BOOST_TEST(result.end_s == 1.0);
  BOOST_TEST_REQUIRE(result.impacts.size() == 1u);
  BOOST_TEST(result.impacts[0].starts_hold);
  BOOST_TEST_REQUIRE(result.sustained_contacts.size() == 1u);
  const auto& hold = result.sustained_contacts[0];
  BOOST_TEST(hold.release_reason == "end of run");
  BOOST_TEST(hold.max_gap_drift_m < 1e-9);
  BOOST_TEST(hold.max_force_kN == 1.0 * Pressed::accel, tt::tolerance(1e-3));  // holds m·A
  BOOST_TEST(result.statistics.events == 1);
}

BOOST_AUTO_TEST_CASE(BounceSequenceUnderConstantPushIsGeometricThenHeld) {
  // Closed form for k = 0.5: first contact at t₁ = √(2d/A) with v₀ = A t₁; the n-th flight lasts
  // 2 kⁿ v₀ / A, so contacts accumulate at t∞ = t₁ + 2 v₀ k /(A (1 − k)). The bounce whose
  // separation would fall below 1 mm/s is held instead.
  const Pressed pressed;
  const double k = 0.5, a = Pressed::accel;
  solvers::EventOptions options;
  options.restitution = k;
  const auto result = solvers::run_event_driven(pressed.system, options, cvode(1e-11, 1e-13), "cvode-bdf");
  BOOST_TEST(solvers::to_string(result.status) == "completed");

  const double t1 = std::sqrt(2 * pressed.effective_gap() / a), v0 = a * t1;
  double t_expected = t1, v_expected = v0;
  std::size_t bounces = 0;
  for (const auto& impact : result.impacts) {
    BOOST_TEST(std::abs(impact.t_s - t_expected) < 1e-8);
    BOOST_TEST(impact.approach_velocity_mps == v_expected, tt::tolerance(1e-5));
    ++bounces;
    if (impact.starts_hold) break;
    BOOST_TEST(impact.separation_velocity_mps == k * v_expected, tt::tolerance(1e-6));
    t_expected += 2 * k * v_expected / a;
    v_expected *= k;
  }
  // Bounces until k·v falls below the 1 mm/s hold velocity: v₀ kⁿ⁺¹ < 10⁻³.
  const auto expected_bounces = static_cast<std::size_t>(std::ceil(std::log(1e-3 / v0) / std::log(k)));
  BOOST_TEST(bounces == expected_bounces);
  BOOST_TEST(result.impacts.size() == bounces);
  BOOST_TEST(result.impacts.back().starts_hold);
  const double t_infinity = t1 + 2 * v0 * k / (a * (1 - k));
  const double remaining = 2 * v_expected * k / (a * (1 - k));  // flights cut off by the hold
  BOOST_TEST(std::abs((t_infinity - result.sustained_contacts.at(0).start_s) - remaining) < 1e-8);
  // Each contact is handled once: one event per impact, none repeated at the same instant.
  BOOST_TEST(result.statistics.events == static_cast<long>(result.impacts.size()));
}

BOOST_AUTO_TEST_CASE(EventCapEndsAnUnresolvedAccumulation) {
  const Pressed pressed;
  solvers::EventOptions options;
  options.restitution = 0.5;
  options.hold_velocity_mps = 1e-12;  // practically never hold: bounces accumulate at t∞ ≈ 0.42 s
  options.hold_height_m = 1e-30;
  options.max_events_per_s = 20;
  const auto result = solvers::run_event_driven(pressed.system, options, cvode(1e-10, 1e-12), "cvode-bdf");
  BOOST_TEST(solvers::to_string(result.status) == "event_limit");
  BOOST_TEST(result.status_detail.find("events") != std::string::npos);
  BOOST_TEST(result.end_s < 1.0);
}

BOOST_AUTO_TEST_CASE(PaperSceneHasNoImpactAtHalfAMetre) {
  const auto scene = io::read_scene(POUNDING_EXAMPLES_DIR "/paper/paper.toml", {.gap_m = 0.5});
  const auto report = analysis::run_scene(scene);
  BOOST_TEST(solvers::to_string(report.result.status) == "completed");
  BOOST_TEST(report.result.impacts.empty());
  BOOST_TEST(std::abs(report.result.energy.residual_kJ()) < 1e-6 * report.result.energy.input_kJ);
}

BOOST_AUTO_TEST_CASE(PaperSceneAtTwentyCentimetresPoundsOnTheUpperFloorsAndBalancesEnergy) {
  const auto scene = io::read_scene(POUNDING_EXAMPLES_DIR "/paper/paper.toml");
  const auto report = analysis::run_scene(scene);
  const auto& r = report.result;
  BOOST_TEST(solvers::to_string(r.status) == "completed");
  BOOST_TEST(report.candidates.size() == 14u);
  BOOST_TEST_REQUIRE(!r.impacts.empty());
  for (const auto& impact : r.impacts) BOOST_TEST(impact.floors[0] >= 5);
  const auto& e = r.energy;
  BOOST_TEST(e.impact_loss_kJ > 0.0);
  BOOST_TEST(std::abs(e.residual_kJ()) < 1e-6 * e.input_kJ);
  double per_impact = 0.0;
  for (const auto& impact : r.impacts) per_impact += impact.energy_lost_kJ;
  BOOST_TEST(per_impact == e.impact_loss_kJ, tt::tolerance(1e-6));
}

BOOST_AUTO_TEST_CASE(ReducedAndDenseNewtonSolversGiveTheSameImpacts) {
  // The reduction solves the same Newton systems as SUNDIALS' dense LU, but refreshes its
  // matrix on its own schedule, so the iterates, and the runs, differ within the tolerance
  // (observed 2e-8 s at rtol 1e-10).
  const auto scene = io::read_scene(POUNDING_EXAMPLES_DIR "/paper/paper.toml");
  const auto system = analysis::build_system(scene);
  solvers::EventOptions options;
  options.restitution = scene.contact.restitution;
  auto with = [&](solvers::NewtonSolver newton) {
    auto make = [&](solvers::OdeFunctions& f, double t0, const Eigen::VectorXd& y0) {
      return std::make_unique<solvers::CvodeIntegrator>(
          f, solvers::CvodeSettings{solvers::CvodeMethod::bdf, 1e-10, 1e-12, newton}, t0, y0);
    };
    return solvers::run_event_driven(system, options, make, "cvode-bdf");
  };
  const auto reduced = with(solvers::NewtonSolver::second_order);
  const auto dense = with(solvers::NewtonSolver::dense);
  BOOST_TEST_REQUIRE(reduced.impacts.size() == dense.impacts.size());
  for (std::size_t i = 0; i < reduced.impacts.size(); ++i) {
    BOOST_TEST(std::abs(reduced.impacts[i].t_s - dense.impacts[i].t_s) < 1e-7);
  }
}

BOOST_AUTO_TEST_CASE(ArkodeExplicitAndImplicitReproduceTheCvodeImpactList) {
  // At rtol 1e-8 the paths agree on gaps to nanometres. An impact time is a gap divided by the
  // approach speed, so the slow last bounces of an accumulation (~1 mm/s) differ by ~1e-6 s
  // while every impact faster than 1 cm/s agrees to well under 1e-6 s.
  auto scene = io::read_scene(POUNDING_EXAMPLES_DIR "/paper/paper.toml");
  const auto reference = analysis::run_scene(scene).result;
  BOOST_TEST_REQUIRE(reference.impacts.size() > 10u);
  for (const char* method : {"arkode-erk", "arkode-dirk"}) {
    scene.solver.method = method;
    const auto other = analysis::run_scene(scene).result;
    BOOST_TEST_CONTEXT(method) {
      BOOST_TEST(solvers::to_string(other.status) == "completed");
      BOOST_TEST_REQUIRE(other.impacts.size() == reference.impacts.size());
      for (std::size_t i = 0; i < other.impacts.size(); ++i) {
        const auto& a = reference.impacts[i];
        const auto& b = other.impacts[i];
        BOOST_TEST(a.level == b.level);
        BOOST_TEST(a.striking_building == b.striking_building);
        const double dt = std::abs(a.t_s - b.t_s);
        if (a.approach_velocity_mps >= 0.01) BOOST_TEST(dt < 1e-6);
        BOOST_TEST(dt * a.approach_velocity_mps < 1e-8);
      }
    }
  }
}
