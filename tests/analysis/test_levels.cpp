#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <Eigen/Geometry>
#include <fmt/format.h>

#include "pounding/analysis/run_scene.hpp"
#include "pounding/io/scene_reader.hpp"

using namespace pounding;

namespace {

/// The example's floor elevations, by hand: B1 3 m storeys, B2 a 6 m ground storey then 3 m.
double elevation(int building, int floor) { return building == 0 ? 3.0 * floor : 6.0 + 3.0 * (floor - 1); }

/// A slab point given at rest, moved by the slab's (u, v, φ) about its CM (exact rotation).
model::Point2 moved(const model::Point2& rest, const model::Point2& centre, double u, double v, double phi) {
  const Eigen::Rotation2Dd rotation(phi);
  return centre + model::Point2(u, v) + rotation * (rest - centre);
}

/// The impact's gap recomputed from history.csv's row at the impact instant, with the slabs of
/// the floors the impact names: the striking vertex's distance in front of the struck edge (m).
/// Independent of the solver's gap code; fails if those floors' columns are missing.
double gap_from_history(const analysis::Scene& scene, const analysis::RunReport& report,
                        const solvers::ImpactRecord& impact) {
  const solvers::History& history = report.result.history;
  const auto row = std::find(history.time_s.begin(), history.time_s.end(), impact.t_s);
  BOOST_REQUIRE(row != history.time_s.end());
  const Eigen::VectorXd& values = history.rows[static_cast<std::size_t>(row - history.time_s.begin())];
  auto value = [&](int building, const char* quantity) {
    const std::string name = fmt::format("B{}_f{}_{}", building + 1, impact.floors[building], quantity);
    const auto column = std::find(history.columns.begin(), history.columns.end(), name);
    BOOST_REQUIRE_MESSAGE(column != history.columns.end(), "no history column " << name);
    return values[column - history.columns.begin() - 1];  // rows leave out t_s
  };
  auto place = [&](int building, const model::Point2& rest) {
    return moved(rest, scene.buildings[building].centre_of_mass, value(building, "u_m"), value(building, "v_m"),
                 value(building, "phi_rad"));
  };
  const contact::Candidate& c = report.candidates[impact.candidate];
  const model::Point2 vertex = place(c.striking_building, c.vertex_rest);
  const model::Point2 edge_start = place(c.struck_building, c.edge_start_rest);
  const model::Point2 normal = Eigen::Rotation2Dd(value(c.struck_building, "phi_rad")) * c.normal_rest;
  return (vertex - edge_start).dot(normal);
}

}  // namespace

BOOST_AUTO_TEST_CASE(ShiftedLevelsPoundOnlyBetweenFloorsAtOneElevation) {
  // examples/levels/unequal-storeys.toml: B1 floor j (3j m) meets B2 floor j − 1. Every impact,
  // touch and hold must name such a pair, and the slabs of exactly those floors must be in
  // contact at the impact instant (from the written history, at the solver's accuracy).
  analysis::Scene scene = io::read_scene(POUNDING_EXAMPLES_DIR "/levels/unequal-storeys.toml");
  struct Method {
    const char* name;
    double gap_tolerance_m;  // the contact accuracy of the method
  };
  for (const Method method : {Method{"cvode-bdf", 1e-8}, Method{"arkode-erk", 1e-8}, Method{"exact", 1e-8},
                              Method{"hht", 1e-4 * (1 + 1e-9)}}) {  // hht: its contact tolerance, to round-off
    scene.solver.method = method.name;
    const analysis::RunReport report = analysis::run_scene(scene);
    const solvers::RunResult& r = report.result;
    // hht may end unresolved_overlap: without sustained contact its pressed slabs sink past the
    // contact tolerance, where they still take impulses, no deeper than the overlap it reports.
    const bool hht = std::string(method.name) == "hht";
    const double deepest_m = hht ? std::max(method.gap_tolerance_m, r.statistics.max_interpenetration_m * (1 + 1e-9))
                                 : method.gap_tolerance_m;
    BOOST_TEST_CONTEXT(method.name) {
      const std::string status(solvers::to_string(r.status));
      BOOST_TEST((status == "completed" || (hht && status == "unresolved_overlap")), status);
      BOOST_TEST_REQUIRE(r.impacts.size() > 5u);
      std::set<int> levels;
      for (const auto& impact : r.impacts) {
        BOOST_TEST_CONTEXT("impact at " << impact.t_s << " s") {
          BOOST_TEST(impact.floors[1] == impact.floors[0] - 1);
          BOOST_TEST(elevation(0, impact.floors[0]) == elevation(1, impact.floors[1]));
          BOOST_TEST(impact.elevation_m == elevation(0, impact.floors[0]));
          BOOST_TEST(impact.level == impact.floors[0] - 1);
          const double gap = gap_from_history(scene, report, impact);
          BOOST_TEST(gap <= method.gap_tolerance_m);
          BOOST_TEST(gap >= -deepest_m);
        }
        levels.insert(impact.level);
      }
      BOOST_TEST(levels.size() >= 2u);  // several levels, so the floor mapping is exercised
      for (const auto& hold : r.sustained_contacts) BOOST_TEST(hold.floors[1] == hold.floors[0] - 1);
      for (const auto& touch : r.touches) BOOST_TEST(touch.floors[1] == touch.floors[0] - 1);
    }
  }
}

BOOST_AUTO_TEST_CASE(HistoryIsWrittenLevelByLevelWithEachBuildingsOwnFloor) {
  analysis::Scene scene = io::read_scene(POUNDING_EXAMPLES_DIR "/levels/unequal-storeys.toml");
  scene.output.history_floors = {6};  // level 6: B1 floor 7, B2 floor 6 (21 m)
  scene.excitation.duration_s = 1.0;
  const solvers::History history = analysis::run_scene(scene).result.history;
  BOOST_TEST(history.levels == std::vector<int>({6}), boost::test_tools::per_element());
  BOOST_TEST(history.columns[1] == "B1_f7_u_m");
  BOOST_TEST(std::count(history.columns.begin(), history.columns.end(), "B2_f6_u_m") == 1);
  BOOST_TEST(std::count(history.columns.begin(), history.columns.end(), "B2_f7_u_m") == 0);
}
