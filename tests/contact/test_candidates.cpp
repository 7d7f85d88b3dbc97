#include <boost/test/unit_test.hpp>

#include "pounding/contact/candidates.hpp"

using namespace pounding::contact;
using pounding::model::Point2;
using pounding::model::Polygon;

namespace {
/// `count` levels with floor j of both buildings at j · 3 m, as in the paper scene.
std::vector<Level> matching_floors(int count) {
  std::vector<Level> levels;
  for (int j = 1; j <= count; ++j) levels.push_back({j, {j, j}, 3.0 * j});
  return levels;
}

PairGeometry paper_pair(double d) {
  return {{Polygon({{-24, 0}, {0, 0}, {0, 20}, {-24, 20}}), Polygon({{d, 8}, {d + 28, 8}, {d + 28, 33}, {d, 33}})},
          {Point2(-10.8, 11.0), Point2(d + 12.6, 19.25)}};
}
}  // namespace

BOOST_AUTO_TEST_CASE(PaperSceneHasTwoCandidatesPerCommonFloor) {
  const auto candidates = find_candidates(paper_pair(0.2), matching_floors(7), {.margin_m = 1.0, .gap_m = 0.2});
  BOOST_TEST_REQUIRE(candidates.size() == 14u);
  for (int floor = 1; floor <= 7; ++floor) {
    const Candidate& b1_corner = candidates[2 * (floor - 1)];
    const Candidate& b2_corner = candidates[2 * (floor - 1) + 1];
    BOOST_TEST(b1_corner.level == floor);
    BOOST_TEST(b2_corner.level == floor);
    BOOST_TEST((b1_corner.floors == std::array<int, 2>{floor, floor}));
    BOOST_TEST(b1_corner.striking_building == 0);
    BOOST_TEST(b1_corner.vertex_rest == Point2(0, 20));
    BOOST_TEST(b1_corner.normal_rest == Point2(-1, 0));  // B2's left edge faces −x
    BOOST_TEST(b1_corner.edge_start_rest == Point2(0.2, 33));
    BOOST_TEST(b2_corner.striking_building == 1);
    BOOST_TEST(b2_corner.vertex_rest == Point2(0.2, 8));
    BOOST_TEST(b2_corner.normal_rest == Point2(1, 0));
  }
}

BOOST_AUTO_TEST_CASE(AlignedEqualSlabsGiveFourFaceCandidates) {
  // Two 10 × 10 slabs face to face: each slab's two facing corners against the other's edge, and
  // the same four corners against the other's side edges, which they reach round its corners.
  const PairGeometry pair{
      {Polygon({{-10, 0}, {0, 0}, {0, 10}, {-10, 10}}), Polygon({{0.1, 0}, {10.1, 0}, {10.1, 10}, {0.1, 10}})},
      {Point2(-5, 5), Point2(5.1, 5)}};
  const auto candidates = find_candidates(pair, matching_floors(1), {.margin_m = 1.0, .gap_m = 0.1});
  BOOST_TEST_REQUIRE(candidates.size() == 8u);
  for (std::size_t i = 0; i < 8; ++i) BOOST_TEST(candidates[i].corner == (i >= 4));
}

BOOST_AUTO_TEST_CASE(DistantVerticesAreLeftOut) {
  // With a 20 m margin the far corners of the paper slabs would come in; 1 m keeps them out.
  BOOST_TEST(find_candidates(paper_pair(0.2), matching_floors(1), {.margin_m = 20.0, .gap_m = 0.2}).size() > 2u);
}

namespace {
std::vector<double> elevations(const std::vector<double>& storey_heights) {
  std::vector<double> z;
  double sum = 0.0;
  for (double h : storey_heights) z.push_back(sum += h);
  return z;
}
}  // namespace

BOOST_AUTO_TEST_CASE(OnlyFloorsAtOneElevationFormLevels) {
  // B1: six 3 m storeys, floors at 3, 6, 9, 12, 15, 18 m. B2: storeys 6, 3, 4.5, 4.5, 3 m,
  // floors at 6, 9, 13.5, 18, 21 m. By hand: 6 m (B1 2, B2 1), 9 m (B1 3, B2 2), 18 m (B1 6, B2 4).
  const auto levels = common_levels({elevations({3, 3, 3, 3, 3, 3}), elevations({6, 3, 4.5, 4.5, 3})}, 1e-3);
  BOOST_TEST_REQUIRE(levels.size() == 3u);
  const std::array<std::array<int, 2>, 3> floors{{{2, 1}, {3, 2}, {6, 4}}};
  const std::array<double, 3> heights{6.0, 9.0, 18.0};
  for (std::size_t k = 0; k < 3; ++k) {
    BOOST_TEST(levels[k].index == static_cast<int>(k) + 1);
    BOOST_TEST((levels[k].floors == floors[k]));
    BOOST_TEST(levels[k].elevation_m == heights[k]);
  }
}

BOOST_AUTO_TEST_CASE(TallerGroundStoreyShiftsEveryFloorOffTheOtherBuildingsLevels) {
  // B2 4.5 m ground storey then 3 m: floors at 4.5 + 3k m never meet B1's multiples of 3 m.
  BOOST_TEST(common_levels({elevations({3, 3, 3, 3, 3, 3}), elevations({4.5, 3, 3, 3, 3})}, 1e-3).empty());
}

BOOST_AUTO_TEST_CASE(LevelToleranceAbsorbsRoundOffButNotRealOffsets) {
  // 3.3 + 3.3 + 3.3 and 4.95 + 4.95 are both 9.9 m up to round-off: one level.
  const auto round_off = common_levels({elevations({3.3, 3.3, 3.3}), elevations({4.95, 4.95})}, 1e-3);
  BOOST_TEST_REQUIRE(round_off.size() == 1u);
  BOOST_TEST((round_off[0].floors == std::array<int, 2>{3, 2}));
  // 2 mm apart is a real offset at the default 1 mm tolerance, and a level at 5 mm.
  const std::array<std::vector<double>, 2> apart{std::vector<double>{3.0}, std::vector<double>{3.002}};
  BOOST_TEST(common_levels(apart, 1e-3).empty());
  BOOST_TEST(common_levels(apart, 5e-3).size() == 1u);
}

BOOST_AUTO_TEST_CASE(CandidatesCarryEachLevelsFloorsAndElevation) {
  const std::vector<Level> levels{{1, {2, 1}, 6.0}, {2, {6, 4}, 18.0}};
  const auto candidates = find_candidates(paper_pair(0.2), levels, {.margin_m = 1.0, .gap_m = 0.2});
  BOOST_TEST_REQUIRE(candidates.size() == 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    const Level& level = levels[k / 2];
    BOOST_TEST(candidates[k].level == level.index);
    BOOST_TEST((candidates[k].floors == level.floors));
    BOOST_TEST(candidates[k].elevation_m == level.elevation_m);
  }
}

BOOST_AUTO_TEST_CASE(UniformTallerStoreysMeetOnlyWhereTheirSumsAgree) {
  // Issue 8's case: B1 seven 3 m storeys, B2 ten 4.5 m storeys. Floors meet where 3 i = 4.5 j:
  // 9 m (B1 3, B2 2) and 18 m (B1 6, B2 4); floor 7 (21 m) and floor 7 (31.5 m) do not.
  const auto levels =
      common_levels({elevations(std::vector<double>(7, 3.0)), elevations(std::vector<double>(10, 4.5))}, 1e-3);
  BOOST_TEST_REQUIRE(levels.size() == 2u);
  BOOST_TEST((levels[0].floors == std::array<int, 2>{3, 2}));
  BOOST_TEST(levels[0].elevation_m == 9.0);
  BOOST_TEST((levels[1].floors == std::array<int, 2>{6, 4}));
  BOOST_TEST(levels[1].elevation_m == 18.0);
}
