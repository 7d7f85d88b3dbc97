// The run-level contract, for every method of the registry (analysis::methods(), hht among them,
// so that a method added there is checked here without a line of this file changing): each runs
// the paper scene up to just before its first sustained contact (two lone impacts on level 7,
// B2's vertex 1 on B1's edge 2) at its default settings, and its RunResult must keep what every
// writer and reader of a run relies on, whatever the method:
//   - the run completes where the record was cut, and names its method;
//   - the same impacts as the ground truth (the exact path), in time order, each within the
//     method's own accuracy of the exact time: 1e-7 s for the event-driven methods at their
//     default tolerances (7e-9 s at most, measured), a tenth of HHT's step Δt (2.1e-3 s at its
//     0.05 s: it applies an impact at a step end, the instant interpolated);
//   - each impact's contact identity (level, floors, striking and struck building, vertex, edge)
//     the exact path's, the approach velocity positive and Newton's law holding exactly for a lone
//     contact (separation = k · approach, to round-off: the reset is algebraic on every path);
//   - the energy audit closes within 1e-6 of the input (7e-8 measured; HHT 1e-2, 4.1e-3 measured:
//     its quadrature against the scheme's discrete work at its 0.05 s step, its numerical damping
//     counted), and the impact loss it books is the impacts' own sum;
//   - one set of peaks per building, one row per floor.
// The method suites (test_method_conformance, test_integrator_conformance) check the integrators
// behind the seam on closed forms; this one checks what a user receives from a whole run.

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>

#include "pounding/analysis/methods.hpp"
#include "pounding/analysis/run_scene.hpp"
#include "pounding/io/scene_reader.hpp"

using namespace pounding;

namespace {

constexpr double kDuration_s = 5.74;  // the first impacts at 5.7008 and 5.7280 s; the first hold at 5.7518 s

analysis::Scene paper_up_to_first_hold(std::string_view method) {
  auto scene = io::read_scene(POUNDING_EXAMPLES_DIR "/paper/paper.toml");
  scene.excitation.duration_s = kDuration_s;
  scene.solver = analysis::with_method(scene.solver, method);
  return scene;
}

/// How far a method's impact time may be from the exact path's at its default settings.
double time_tolerance_s(const analysis::MethodInfo& method, const analysis::RunReport& report) {
  return method.event_driven ? 1e-7 : 0.1 * report.used.dt_s;
}

/// How far a method's energy audit may be from closing, relative to the input: HHT's audit
/// integrates along each step's interpolant against the scheme's discrete work, 6e-3 of the input
/// on this scene at its 0.05 s step (docs/guide/methods.md); the event-driven ones to their tolerances.
double energy_tolerance(const analysis::MethodInfo& method) { return method.event_driven ? 1e-6 : 1e-2; }

void check_identity(const solvers::ImpactRecord& got, const solvers::ImpactRecord& want) {
  BOOST_TEST(got.candidate == want.candidate);
  BOOST_TEST(got.level == want.level);
  BOOST_TEST((got.floors == want.floors));
  BOOST_TEST((got.buildings == want.buildings));
  BOOST_TEST(got.striking_building == want.striking_building);
  BOOST_TEST(got.struck_building == want.struck_building);
  BOOST_TEST(got.vertex == want.vertex);
  BOOST_TEST(got.edge == want.edge);
}

}  // namespace

BOOST_AUTO_TEST_CASE(EveryMethodKeepsTheRunContractOnThePaperScene) {
  const auto truth = analysis::run_scene(paper_up_to_first_hold(analysis::reference_method().name));
  BOOST_TEST_REQUIRE(truth.result.impacts.size() == 2u);
  BOOST_TEST_REQUIRE(truth.result.sustained_contacts.empty());
  for (const analysis::MethodInfo& method : analysis::methods()) {
    BOOST_TEST_CONTEXT("method " << method.name) {
      const auto report = analysis::run_scene(paper_up_to_first_hold(method.name));
      const auto& result = report.result;
      BOOST_TEST((result.status == solvers::RunStatus::completed), result.status_detail);
      BOOST_TEST(result.method == method.name);
      BOOST_TEST(std::abs(result.end_s - kDuration_s) <= 1e-9);

      BOOST_TEST_REQUIRE(result.impacts.size() == truth.result.impacts.size());
      const double tolerance_s = time_tolerance_s(method, report);
      double previous_t_s = result.start_s, loss_kJ = 0.0;
      for (std::size_t i = 0; i < result.impacts.size(); ++i) {
        BOOST_TEST_CONTEXT("impact " << i + 1) {
          const auto& impact = result.impacts[i];
          const auto& exact = truth.result.impacts[i];
          BOOST_TEST(impact.t_s >= previous_t_s);
          BOOST_TEST(impact.t_s <= result.end_s);
          BOOST_TEST(std::abs(impact.t_s - exact.t_s) <= tolerance_s);
          check_identity(impact, exact);
          BOOST_TEST(impact.approach_velocity_mps > 0.0);
          BOOST_TEST(std::abs(impact.separation_velocity_mps - report.restitution * impact.approach_velocity_mps) <=
                     1e-9 * impact.approach_velocity_mps);
          BOOST_TEST(impact.impulse_kNs > 0.0);
          BOOST_TEST(impact.energy_lost_kJ > 0.0);
          previous_t_s = impact.t_s;
          loss_kJ += impact.energy_lost_kJ;
        }
      }
      const auto& energy = result.energy;
      BOOST_TEST_MESSAGE(method.name << ": first impact " << result.impacts[0].t_s - truth.result.impacts[0].t_s
                                     << " s from the exact one; energy residual "
                                     << energy.residual_kJ() / energy.input_kJ << " of the input");
      BOOST_TEST(energy.input_kJ > 0.0);
      BOOST_TEST(std::abs(energy.residual_kJ()) <= energy_tolerance(method) * energy.input_kJ);
      BOOST_TEST(std::abs(energy.impact_loss_kJ - loss_kJ) <= 1e-9 * loss_kJ);

      BOOST_TEST_REQUIRE(result.peaks.size() == 2u);
      BOOST_TEST(result.peaks[0].floors.size() == 7u);
      BOOST_TEST(result.peaks[1].floors.size() == 10u);
      BOOST_TEST(result.statistics.steps > 0);
    }
  }
}
