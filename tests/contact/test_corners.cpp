// Corners (docs/model.md §4, §5a): corner candidates, their links, the inside test, and two
// squares meeting corner to corner against the closed form.
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "../support/two_slabs.hpp"
#include "pounding/contact/corners.hpp"
#include "pounding/contact/gap.hpp"
#include "pounding/contact/impact.hpp"
#include "pounding/analysis/run_scene.hpp"
#include "pounding/io/scene_reader.hpp"

namespace tt = boost::test_tools;
using namespace pounding;
using namespace pounding::contact;
using model::Point2;
using model::Polygon;

namespace {

const std::vector<Level> kOneLevel{{.index = 1, .floors = {1, 1}, .elevation_m = 3.0}};

/// A 16 × 12 slab at the origin and its neighbour `gap` further along x, its y shifted by `shift`.
PairGeometry in_line(double gap, double shift = 0.0) {
  const Polygon a({{0, 0}, {16, 0}, {16, 12}, {0, 12}});
  const Polygon b({{16 + gap, shift}, {32 + gap, shift}, {32 + gap, 12 + shift}, {16 + gap, 12 + shift}});
  return {{a, b}, {a.centroid(), b.centroid()}};
}

long find(const std::vector<Candidate>& candidates, int striking, std::size_t vertex, std::size_t edge) {
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const Candidate& c = candidates[i];
    if (c.striking_building == striking && c.vertex_index == vertex && c.edge_index == edge)
      return static_cast<long>(i);
  }
  return kNoCandidate;
}

}  // namespace

BOOST_AUTO_TEST_CASE(FacadesInLineAddTheSideEdgesAsCornerCandidates) {
  // Facing: each slab's two corners at the joint against the other's facing edge. Corner: the
  // same four corners against the other slab's top and bottom (side) edges, which face along y.
  for (double shift : {0.0, 1e-6, -1e-6}) {
    const std::vector<Candidate> candidates = find_candidates(in_line(0.05, shift), kOneLevel, {.gap_m = 0.05});
    long facing = 0, corner = 0;
    for (const Candidate& c : candidates) (c.corner ? corner : facing) += 1;
    BOOST_TEST(corner + facing == 8);
    // Facades in line to within a micrometre: a side edge may face a corner by a micrometre.
    BOOST_TEST(facing >= 4);
    // A's corner (16, 0) (vertex 2) against B's bottom edge (edge 1), wherever B stands.
    BOOST_TEST(find(candidates, 0, 1, 0) != kNoCandidate);
    BOOST_TEST(find(candidates, 1, 3, 2) != kNoCandidate);  // B's corner (16.05, 12) on A's top edge
  }
}

BOOST_AUTO_TEST_CASE(TheSlabsOfThePaperHaveNoCornerCandidates) {
  const Polygon a({{-24, 0}, {0, 0}, {0, 20}, {-24, 20}}), b({{0.2, 8}, {28.2, 8}, {28.2, 33}, {0.2, 33}});
  const auto candidates = find_candidates({{a, b}, {a.centroid(), b.centroid()}}, kOneLevel, {.gap_m = 0.2});
  BOOST_TEST(candidates.size() == 2u);
  BOOST_TEST(!candidates[0].corner);
  BOOST_TEST(!candidates[1].corner);
}

BOOST_AUTO_TEST_CASE(TwinsNextEdgesAndGroupsOfFacadesInLine) {
  const std::vector<Candidate> candidates = find_candidates(in_line(0.05), kOneLevel, {.gap_m = 0.05});
  const CornerLinks links = link_corners(candidates, {4, 4});
  // A's top corner (vertex 3) on B's left edge (edge 4, from B's top corner down to its bottom
  // one): its twin at the edge's start is B's top corner (vertex 4) on A's right edge (edge 2).
  const long a_top = find(candidates, 0, 2, 3), b_top = find(candidates, 1, 3, 1);
  BOOST_TEST_REQUIRE(a_top != kNoCandidate);
  BOOST_TEST_REQUIRE(b_top != kNoCandidate);
  BOOST_TEST(links.twin[a_top][0] == b_top);
  BOOST_TEST(links.twin[b_top][1] == a_top);  // and back, at the end of A's right edge
  // Round B's top corner the next edge is B's top edge (edge 3): a corner candidate.
  const long a_top_on_b_top = find(candidates, 0, 2, 2);
  BOOST_TEST(links.next[a_top][0] == a_top_on_b_top);
  BOOST_TEST(candidates[a_top_on_b_top].corner);
  // Perpendicular edges are no twins: A's top corner on B's top edge has none at B's top corner.
  BOOST_TEST(links.twin[a_top_on_b_top][1] == kNoCandidate);
  // One group per corner and struck slab: A's top corner on B's left and top edges.
  BOOST_TEST(links.group[a_top] == links.group[a_top_on_b_top]);
  BOOST_TEST(links.group[a_top] != links.group[b_top]);
  // A contact of A's top corner on B's left edge lies at B's top corner's group at its start.
  BOOST_TEST(links.edge_end_group[a_top][0] == static_cast<long>(links.group[b_top]));
}

BOOST_AUTO_TEST_CASE(DepthInsideIsTheDistanceToTheNearestEdgeAndZeroOutside) {
  const std::vector<Point2> square{{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  BOOST_TEST(depth_inside(square, Point2(0.003, 5)) == 0.003, tt::tolerance(1e-12));
  BOOST_TEST(depth_inside(square, Point2(0.003, 0.001)) == 0.001, tt::tolerance(1e-12));  // near a corner
  // Beside the square's corner, 5 mm behind the line of its left edge: outside.
  BOOST_TEST(depth_inside(square, Point2(0.005, -1e-8)) == 0.0);
  BOOST_TEST(depth_inside(square, Point2(-0.005, 5)) == 0.0);
}

BOOST_AUTO_TEST_CASE(SquaresMeetingCornerToCornerTakeTheImpulseAlongTheirDiagonal) {
  // A = [−10, 0]², B = [0, 10]² (equal 10 t slabs, J = m (10² + 10²)/12), corners at the origin,
  // approaching along the diagonal at v each. Closed form: the line of impact passes through both
  // centres of mass, so I = (1 + k) m v along the diagonal (equal masses), no spin, and each slab
  // leaves at k v back along it.
  const double m = 10.0, j = m * 200.0 / 12.0, v = 0.4;
  const Polygon a({{-10, -10}, {0, -10}, {0, 0}, {-10, 0}}), b({{0, 0}, {10, 0}, {10, 10}, {0, 10}});
  const std::vector<Candidate> candidates =
      find_candidates({{a, b}, {a.centroid(), b.centroid()}}, kOneLevel, {.margin_m = 1.0, .gap_m = 0.0});
  const double d = v / std::sqrt(2.0);
  Vector6d before;
  before << d, d, 0.0, -d, -d, 0.0;
  const Vector6d inverse = inverse_mass(m, j, m, j);
  std::vector<ContactRow> rows;
  for (const Candidate& c : candidates) {
    const bool a_strikes = c.striking_building == 0;
    const SlabMotion sa{a.centroid(), Eigen::Vector3d::Zero(), before.head<3>()};
    const SlabMotion sb{b.centroid(), Eigen::Vector3d::Zero(), before.tail<3>()};
    const GapState s = a_strikes ? evaluate_gap(c, sa, sb) : evaluate_gap(c, sb, sa);
    if (std::abs(s.gap_m) > 1e-12 || !s.on_segment() || !(s.gap_rate_mps < 0.0)) continue;
    ContactRow row;
    row.jacobian.resize(6);
    if (a_strikes) {
      row.jacobian << s.striking_row, s.struck_row;
    } else {
      row.jacobian << s.struck_row, s.striking_row;
    }
    row.gap_rate_mps = s.gap_rate_mps;
    row.restitution = 0.5;
    rows.push_back(row);
  }
  BOOST_TEST_REQUIRE(rows.size() == 4u);  // each corner against both edges of the other's corner
  const ImpulseSolution solution = solve_impulses(rows, inverse);
  const Vector6d after = before + solution.velocity_change;
  const double k = 0.5;
  BOOST_TEST(after[0] == -k * d, tt::tolerance(1e-12));
  BOOST_TEST(after[1] == -k * d, tt::tolerance(1e-12));
  BOOST_TEST(std::abs(after[2]) < 1e-14);
  BOOST_TEST(std::abs(after[5]) < 1e-14);
  double total = 0.0;
  for (double impulse : solution.impulses_kNs) total += impulse;
  // The x and y contacts take (1 + k) m v/√2 each (shared between a corner's two candidates on
  // that axis); their resultant, (1 + k) m v, lies along the diagonal.
  BOOST_TEST(total == (1.0 + k) * m * v * std::sqrt(2.0), tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(SquaresMeetingCornerToCornerInARun) {
  // The same meeting in the event loop: two one-storey buildings on nearly free storeys (T = 10⁴ s),
  // A's slab [−10, 0] × [0, 10], B's [g, 10 + g] × [10 + g, 20 + g], started along the diagonal
  // towards each other. One impact, on the four candidates at the corner, along the diagonal.
  const double g = 0.01, v = 0.4, d = v / std::sqrt(2.0);
  const testing::SlabSpec free{10.0, 1e4, 0.0};
  const auto system = testing::two_slabs(free, testing::box(g, 10 + g, 10 + g, 20 + g), free, g, 0.1);
  Eigen::VectorXd y0 = Eigen::VectorXd::Zero(system.state_size());
  y0.segment<2>(system.dof() + system.floor_index(0, 1)) << d, d;
  y0.segment<2>(system.dof() + system.floor_index(1, 1)) << -d, -d;
  solvers::EventOptions options;
  options.initial_state = y0;
  options.restitution = 0.5;
  const solvers::RunResult result =
      solvers::run_event_driven(system, options, testing::cvode(1e-12, 1e-14), "cvode-bdf");
  BOOST_TEST(solvers::to_string(result.status) == "completed");
  BOOST_TEST_REQUIRE(!result.impacts.empty());
  const double t_meet = g / (2.0 * d);  // each gap closes at 2d
  BOOST_TEST(result.impacts[0].t_s == t_meet, tt::tolerance(1e-6));
  double impulse = 0.0;
  for (const solvers::ImpactRecord& r : result.impacts) {
    if (std::abs(r.t_s - result.impacts[0].t_s) < 1e-9) impulse += r.impulse_kNs;
  }
  BOOST_TEST(impulse == 1.5 * 10.0 * v * std::sqrt(2.0), tt::tolerance(1e-6));
  BOOST_TEST(result.statistics.max_interpenetration_m < 1e-9);
}

namespace {

/// tests/data/street/`file` (two one-storey slabs in line, tests/solvers/test_street_scipy.py's
/// scene) run with `overrides` on cvode-bdf at the scene's default tolerances.
solvers::RunResult run_in_line(const std::string& file, const io::SceneOverrides& overrides = {}) {
  return analysis::run_scene(io::read_scene(POUNDING_TEST_DATA_DIR "/street/" + file, overrides)).result;
}

}  // namespace

// The corner rules end to end, short enough for the sanitizer pass (the scipy peer's comparison of
// the same scenes, tests/solvers/test_street_scipy.py, is left out there for its length).
BOOST_AUTO_TEST_CASE(AKelvinContactIsHandedRoundTheCornersOfFacadesInLine) {
  const solvers::RunResult result = run_in_line("in-line.toml");
  BOOST_TEST(solvers::to_string(result.status) == "completed");
  BOOST_TEST(result.statistics.corner_candidates == 4);
  BOOST_TEST(result.statistics.corner_handovers >= 1);  // the peer, at rtol 1e-12: 4
  BOOST_TEST(std::abs(result.energy.residual_kJ()) <= 1e-6 * result.energy.input_kJ);
}

BOOST_AUTO_TEST_CASE(AHoldIsHandedRoundTheCornerOfFacadesInLineToAMicrometre) {
  // B 1 um higher: B's side edges face A's corners by a micrometre (facing candidates), and a
  // vertex on the facade behind such an edge's line touches nothing there.
  const solvers::RunResult result = run_in_line("in-line-1um.toml");
  BOOST_TEST(solvers::to_string(result.status) == "completed");
  BOOST_TEST(result.statistics.corner_handovers >= 1);  // a hold passes to its twin (the peer: 1)
  BOOST_TEST(!result.sustained_contacts.empty());
  BOOST_TEST(result.statistics.max_interpenetration_m < 1e-9);
}
