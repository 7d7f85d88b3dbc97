#include <boost/test/unit_test.hpp>

#include "pounding/model/polygon.hpp"

using pounding::model::Point2;
using pounding::model::Polygon;

namespace {
Polygon rectangle(double x0, double y0, double x1, double y1) {
  return Polygon({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}});
}
}  // namespace

BOOST_AUTO_TEST_CASE(RectangleAreaCentroidAndPolarMomentMatchClosedForm) {
  const Polygon slab = rectangle(-24, 0, 0, 20);
  BOOST_TEST(slab.signed_area() == 480.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(slab.centroid().x() == -12.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(slab.centroid().y() == 10.0, boost::test_tools::tolerance(1e-12));
  // (Ix + Iy) about the centroid = A (a² + b²)/12.
  BOOST_TEST(slab.polar_area_moment_about_centroid() == 480.0 * (24.0 * 24 + 20 * 20) / 12,
             boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(TriangleCentroidIsMeanOfVertices) {
  const Polygon triangle({{0, 0}, {6, 0}, {0, 3}});
  BOOST_TEST(triangle.centroid().x() == 2.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(triangle.centroid().y() == 1.0, boost::test_tools::tolerance(1e-12));
  // Right triangle legs a, b: Ix + Iy about the centroid = a b (a² + b²)/36.
  BOOST_TEST(triangle.polar_area_moment_about_centroid() == 6.0 * 3 * (36.0 + 9) / 36,
             boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(ClockwiseOrderGivesNegativeArea) {
  const Polygon clockwise({{0, 0}, {0, 1}, {1, 1}, {1, 0}});
  BOOST_TEST(clockwise.signed_area() == -1.0);
  BOOST_TEST(clockwise.is_simple());
}

BOOST_AUTO_TEST_CASE(BowTieAndRepeatedVertexAreNotSimple) {
  BOOST_TEST(!Polygon({{0, 0}, {1, 1}, {1, 0}, {0, 1}}).is_simple());
  BOOST_TEST(!Polygon({{0, 0}, {1, 0}, {1, 0}, {0, 1}}).is_simple());
  BOOST_TEST(!Polygon({{0, 0}, {1, 0}}).is_simple());
  BOOST_TEST(!Polygon({{0, 0}, {2, 0}, {1, 0}}).is_simple());  // folds back on itself
}

BOOST_AUTO_TEST_CASE(LShapeIsSimpleAndContainsOnlyItsOwnPoints) {
  const Polygon l_shape({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}});
  BOOST_TEST(l_shape.is_simple());
  BOOST_TEST(l_shape.contains_strictly(Point2(0.5, 1.5)));
  BOOST_TEST(!l_shape.contains_strictly(Point2(1.5, 1.5)));
  BOOST_TEST(!l_shape.contains_strictly(Point2(2.0, 0.5)));  // on the boundary
  BOOST_TEST(l_shape.contains(Point2(2.0, 0.5)));
}

BOOST_AUTO_TEST_CASE(TouchingSlabsDoNotOverlapButNestedOrCrossingOnesDo) {
  const Polygon left = rectangle(-24, 0, 0, 20);
  BOOST_TEST(!pounding::model::interiors_overlap(left, rectangle(0, 8, 28, 33)));
  BOOST_TEST(!pounding::model::interiors_overlap(left, rectangle(0.2, 8, 28.2, 33)));
  BOOST_TEST(pounding::model::interiors_overlap(left, rectangle(-0.1, 8, 28, 33)));
  BOOST_TEST(pounding::model::interiors_overlap(left, rectangle(-10, 5, -5, 10)));  // nested
  BOOST_TEST(pounding::model::interiors_overlap(left, left));
}

BOOST_AUTO_TEST_CASE(HorizontalClearanceOfThePaperSlabsIsTheGap) {
  const Polygon left = rectangle(-24, 0, 0, 20);
  const auto clearance = pounding::model::horizontal_clearance(left, rectangle(0.37, 8, 28.37, 33));
  BOOST_TEST_REQUIRE(clearance.has_value());
  BOOST_TEST(*clearance == 0.37, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(HorizontalClearanceUsesTheNearestPointsOfSlantedEdges) {
  // Right slab's left edge slants from (1, 0) to (3, 10): nearest at y = 0, distance 1.
  const Polygon left = rectangle(-5, 0, 0, 10);
  const Polygon right({{1, 0}, {6, 0}, {6, 10}, {3, 10}});
  const auto clearance = pounding::model::horizontal_clearance(left, right);
  BOOST_TEST_REQUIRE(clearance.has_value());
  BOOST_TEST(*clearance == 1.0, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(SlabsAtDifferentHeightsHaveNoClearance) {
  const auto clearance = pounding::model::horizontal_clearance(rectangle(-5, 0, 0, 10), rectangle(1, 11, 5, 20));
  BOOST_TEST(!clearance.has_value());
}
