#include <boost/test/unit_test.hpp>

#include <cmath>
#include <numbers>

#include "../support/two_slabs.hpp"
#include "pounding/analysis/needed_gap.hpp"
#include "pounding/analysis/run_scene.hpp"
#include "pounding/input_error.hpp"
#include "pounding/io/scene_reader.hpp"

using namespace pounding;

namespace {

/// Whether a full event-driven run of `scene` at `gap_m` has any contact (impact, touch or hold).
bool contact_at(analysis::Scene scene, double gap_m) {
  scene.set_gap(gap_m);
  const analysis::RunReport report = analysis::run_scene(scene);
  BOOST_REQUIRE(report.result.status == solvers::RunStatus::completed);
  return !report.result.impacts.empty() || !report.result.touches.empty() || !report.result.sustained_contacts.empty();
}

analysis::Scene tight(const char* file) {
  analysis::Scene scene = io::read_scene(file);
  scene.solver.method = "cvode-bdf";
  scene.solver.rtol = 1e-10;
  scene.solver.atol = 1e-12;
  return scene;
}

}  // namespace

BOOST_AUTO_TEST_CASE(CqcCorrelationMatchesTheEqualDampingForm) {
  // Der Kiureghian's ρ for ζ₁ = ζ₂ = ζ reduces to 8ζ²(1 + r) r^1.5 / ((1 − r²)² + 4ζ² r (1 + r)²).
  const double zeta = 0.05;
  for (double r : {0.3, 0.7, 0.95, 1.0, 1.4}) {
    const double expected = 8 * zeta * zeta * (1 + r) * std::pow(r, 1.5) /
                            (std::pow(1 - r * r, 2) + 4 * zeta * zeta * r * std::pow(1 + r, 2));
    BOOST_TEST(analysis::cqc_correlation(1.0, zeta, 1.0 / r, zeta) == expected, boost::test_tools::tolerance(1e-12));
  }
  BOOST_TEST(analysis::cqc_correlation(0.8, 0.05, 0.8, 0.05) == 1.0, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(RulesCombineTheTwoPeaks) {
  const analysis::GapRules independent = analysis::gap_rules(0.3, 0.4, 0.0);
  BOOST_TEST(independent.abs_m == 0.7, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(independent.srss_m == 0.5, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(independent.ddc_m == 0.5, boost::test_tools::tolerance(1e-12));
  // In phase (ρ = 1) the slabs move together: only the difference of the peaks closes the gap.
  BOOST_TEST(analysis::gap_rules(0.3, 0.4, 1.0).ddc_m == 0.1, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(TwoSlabsUnderConstantGroundAccelerationMatchTheClosedForm) {
  // Undamped one-storey slabs, T₁ = 0.5 s, T₂ = 1 s, a_g = 2 m/s² along +x from rest: each slab
  // moves u_b = −(a/ω_b²)(1 − cos ω_b t), towards −x. The gap closes by u₁ − u₂ =
  // A₁[4(1 − cos θ) − (1 − cos 2θ)] = 2A₁(1 − cos θ)², θ = ω₂t, A₁ = a/ω₁²: largest 8A₁ at
  // t = T₂/2. Building 2 moves towards building 1 by 2A₂ = 8A₁ then; building 1 never moves towards 2.
  const double accel = 2.0, omega1 = 2 * std::numbers::pi / 0.5, a1 = accel / (omega1 * omega1);
  const double gap_m = 0.05;
  const auto system = testing::two_slabs({.period_x_s = 0.5}, testing::box(gap_m, 2, gap_m + 10, 12),
                                         {.period_x_s = 1.0}, gap_m, 0.9, accel);
  const analysis::NeededGap gap = analysis::needed_gap(system, gap_m, {.rtol = 1e-11, .atol = 1e-13});
  BOOST_TEST(std::abs(gap.needed_gap_m - 8 * a1) < 1e-9);
  BOOST_TEST(std::abs(gap.t_s - 0.5) < 1e-6);
  BOOST_REQUIRE(gap.levels.size() == 1u);
  BOOST_TEST(std::abs(gap.levels[0].peak_towards_m[1] - 8 * a1) < 1e-9);
  BOOST_TEST(gap.levels[0].peak_towards_m[0] == 0.0);
  BOOST_TEST(std::abs(gap.rules.abs_m - 8 * a1) < 1e-9);
  // The sampled history of the governing pair never exceeds the located maximum.
  double sampled = 0.0;
  for (double g : gap.history_touch_gap_m[0]) sampled = std::max(sampled, std::isnan(g) ? 0.0 : g);
  BOOST_TEST(sampled <= gap.needed_gap_m + 1e-12);
  BOOST_TEST(sampled > gap.needed_gap_m - 1e-3);
}

BOOST_AUTO_TEST_CASE(FullRunsJustAboveTheNeededGapHaveNoContactAndJustBelowOne) {
  // The needed gap is a property of the full (event-driven) model: at it + 1e-7 m not even a
  // touch, at it − 1e-7 m a contact. CVODE BDF at rtol 1e-10 for both, so both are far more
  // accurate than the tolerance. The torsion scene's governing pair is a corner on a rotating edge.
  for (const char* file :
       {POUNDING_EXAMPLES_DIR "/paper/paper.toml", POUNDING_EXAMPLES_DIR "/beyond-paper/torsion.toml"}) {
    BOOST_TEST_CONTEXT(file) {
      const analysis::Scene scene = tight(file);
      const analysis::NeededGap gap = analysis::needed_gap(scene);
      constexpr double kTolerance_m = 1e-7;
      BOOST_TEST(!contact_at(scene, gap.needed_gap_m + kTolerance_m));
      BOOST_TEST(contact_at(scene, gap.needed_gap_m - kTolerance_m));
    }
  }
}

BOOST_AUTO_TEST_CASE(PaperSceneAgreesWithABisectionOnFullRuns) {
  // Bisection on full runs from [0, 1] m (contact at 0, none at 1) to 1e-6 m.
  const analysis::Scene scene = tight(POUNDING_EXAMPLES_DIR "/paper/paper.toml");
  double touching = 0.0, clear = 1.0;
  BOOST_REQUIRE(contact_at(scene, touching));
  BOOST_REQUIRE(!contact_at(scene, clear));
  while (clear - touching > 1e-6) {
    const double middle = 0.5 * (touching + clear);
    (contact_at(scene, middle) ? touching : clear) = middle;
  }
  const analysis::NeededGap gap = analysis::needed_gap(scene);
  BOOST_TEST(gap.needed_gap_m >= touching);
  BOOST_TEST(gap.needed_gap_m <= clear);
}

BOOST_AUTO_TEST_CASE(ABudgetOrAnInterruptEndsTheRunWithANamedStatus) {
  const analysis::Scene scene = io::read_scene(POUNDING_EXAMPLES_DIR "/paper/paper.toml");
  const analysis::NeededGap whole = analysis::needed_gap(scene);
  BOOST_TEST(solvers::to_string(whole.status) == "completed");
  BOOST_TEST(whole.end_s == 12.2, boost::test_tools::tolerance(1e-12));

  const analysis::NeededGap spent = analysis::needed_gap(scene, {.max_wall_time_s = 1e-9});
  BOOST_TEST(solvers::to_string(spent.status) == "time_limit");
  BOOST_TEST(spent.end_s < whole.end_s);

  solvers::request_interrupt();
  const analysis::NeededGap interrupted = analysis::needed_gap(scene);
  solvers::clear_interrupt();
  BOOST_TEST(solvers::to_string(interrupted.status) == "interrupted");
  BOOST_TEST(interrupted.end_s == 0.0);
  // What was covered is a lower bound of the whole record's answer.
  BOOST_TEST(!(spent.needed_gap_m > whole.needed_gap_m));
}

BOOST_AUTO_TEST_CASE(BadOptionsNameTheField) {
  const auto system = testing::two_slabs({}, testing::box(0.1, 0, 10.1, 10), {}, 0.1, 1.0, 1.0);
  BOOST_CHECK_EXCEPTION(analysis::needed_gap(system, 0.1, {.rtol = -1.0}), InputError,
                        [](const InputError& e) { return e.key() == "rtol"; });
  const analysis::Scene scene = io::read_scene(POUNDING_EXAMPLES_DIR "/paper/paper.toml");
  BOOST_CHECK_EXCEPTION(analysis::severity_curve(scene, 0.3, 1), InputError,
                        [](const InputError& e) { return e.key() == "count"; });
}

BOOST_AUTO_TEST_CASE(SeverityCurveRunsEachGapOnItsOwn) {
  // Threads must not change the answers: the parallel curve equals runs made one at a time.
  const analysis::Scene scene = io::read_scene(POUNDING_EXAMPLES_DIR "/paper/paper.toml");
  const auto curve = analysis::severity_curve(scene, 0.36, 3, 3);
  BOOST_REQUIRE(curve.size() == 3u);
  for (const analysis::SeverityPoint& point : curve) {
    analysis::Scene alone = scene;
    alone.set_gap(point.gap_m);
    const analysis::RunReport report = analysis::run_scene(alone);
    BOOST_TEST(point.impacts == static_cast<long>(report.result.impacts.size()));
    BOOST_TEST(point.energy_lost_kJ == report.result.energy.impact_loss_kJ);
    BOOST_TEST(point.impacts > 0);
  }
  BOOST_TEST(curve[0].gap_m == 0.0);
  BOOST_TEST(curve[2].gap_m == 0.24, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(TheAnswerDoesNotDependOnTheScenesGap) {
  // Each pair is judged in the geometry where it touches (b = ∂g/∂G and on_segment there), so
  // moving building 2 before the run changes nothing but round-off and the solver's error.
  analysis::Scene scene = tight(POUNDING_EXAMPLES_DIR "/beyond-paper/torsion.toml");
  const double reference_m = analysis::needed_gap(scene).needed_gap_m;
  for (double gap_m : {0.0, 0.9}) {
    scene.set_gap(gap_m);
    BOOST_TEST(std::abs(analysis::needed_gap(scene).needed_gap_m - reference_m) < 1e-8, "scene gap " << gap_m);
  }
}
