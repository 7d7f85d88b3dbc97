#define BOOST_TEST_MODULE candidates
#include <boost/test/unit_test.hpp>

#include "pounding/contact/candidates.hpp"

using namespace pounding::contact;
using pounding::model::Point2;
using pounding::model::Polygon;

namespace {
PairGeometry paper_pair(double d) {
  return {{Polygon({{-24, 0}, {0, 0}, {0, 20}, {-24, 20}}), Polygon({{d, 8}, {d + 28, 8}, {d + 28, 33}, {d, 33}})},
          {Point2(-10.8, 11.0), Point2(d + 12.6, 19.25)}};
}
}  // namespace

BOOST_AUTO_TEST_CASE(PaperSceneHasTwoCandidatesPerCommonFloor) {
  const auto candidates = find_candidates(paper_pair(0.2), 7, {.margin_m = 1.0, .gap_m = 0.2});
  BOOST_TEST_REQUIRE(candidates.size() == 14u);
  for (int floor = 1; floor <= 7; ++floor) {
    const Candidate& b1_corner = candidates[2 * (floor - 1)];
    const Candidate& b2_corner = candidates[2 * (floor - 1) + 1];
    BOOST_TEST(b1_corner.floor == floor);
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
  // Two 10 × 10 slabs face to face: each slab's two facing corners against the other's edge.
  const PairGeometry pair{{Polygon({{-10, 0}, {0, 0}, {0, 10}, {-10, 10}}), Polygon({{0.1, 0}, {10.1, 0}, {10.1, 10}, {0.1, 10}})},
                          {Point2(-5, 5), Point2(5.1, 5)}};
  BOOST_TEST(find_candidates(pair, 1, {.margin_m = 1.0, .gap_m = 0.1}).size() == 4u);
}

BOOST_AUTO_TEST_CASE(DistantVerticesAreLeftOut) {
  // With a 20 m margin the far corners of the paper slabs would come in; 1 m keeps them out.
  BOOST_TEST(find_candidates(paper_pair(0.2), 1, {.margin_m = 20.0, .gap_m = 0.2}).size() > 2u);
}
