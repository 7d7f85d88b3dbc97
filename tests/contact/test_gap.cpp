#include <boost/test/unit_test.hpp>

#include "pounding/contact/gap.hpp"

namespace tt = boost::test_tools;
using namespace pounding::contact;
using pounding::model::Point2;

namespace {

// B1 corner (0, 20) against B2's left edge x = 0.2 (from (0.2, 33) down to (0.2, 8)).
Candidate paper_candidate() {
  return {1, {1, 1}, 3.0, 0, 1, 2, 3, Point2(0, 20), Point2(0.2, 33), Point2(0.2, 8), Point2(-1, 0)};
}

SlabMotion slab(Point2 centre, Eigen::Vector3d q, Eigen::Vector3d q_dot = Eigen::Vector3d::Zero()) {
  return {centre, q, q_dot};
}

/// Motion with constant acceleration from (q, q̇) over time t.
SlabMotion advanced(const SlabMotion& s, const Eigen::Vector3d& accel, double t) {
  return {s.centre_rest, s.q + s.q_dot * t + 0.5 * accel * t * t, s.q_dot + accel * t};
}

}  // namespace

BOOST_AUTO_TEST_CASE(VertexOnEdgeHasZeroGap) {
  const Candidate c = paper_candidate();
  const SlabMotion a = slab(Point2(-10.8, 11), Eigen::Vector3d(0.2, 0, 0), Eigen::Vector3d::Zero());
  const SlabMotion b = slab(Point2(12.8, 19.25), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  const GapState s = evaluate_gap(c, a, b);
  BOOST_TEST(s.gap_m == 0.0, tt::tolerance(1e-15));
  BOOST_TEST(s.segment_param == 13.0 / 25.0, tt::tolerance(1e-14));
}

BOOST_AUTO_TEST_CASE(GapIsPositiveApartAndNegativeInOverlap) {
  const Candidate c = paper_candidate();
  const SlabMotion b = slab(Point2(12.8, 19.25), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  BOOST_TEST(evaluate_gap(c, slab(Point2(-10.8, 11), {0.05, 0, 0}), b).gap_m == 0.15, tt::tolerance(1e-14));
  BOOST_TEST(evaluate_gap(c, slab(Point2(-10.8, 11), {0.25, 0, 0}), b).gap_m == -0.05, tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(RotationMovesTheCornerByTheExactArc) {
  // Rotating B1 by φ about its CM moves (0, 20) to c + R(φ)(10.8, 9); x changes by the exact
  // 10.8 (cos φ − 1) − 9 sin φ, not by the small-angle −9 φ.
  const double phi = 0.05;
  const SlabMotion a = slab(Point2(-10.8, 11), {0, 0, phi});
  const SlabMotion b = slab(Point2(12.8, 19.25), Eigen::Vector3d::Zero());
  const double dx = 10.8 * (std::cos(phi) - 1) - 9 * std::sin(phi);
  BOOST_TEST(evaluate_gap(paper_candidate(), a, b).gap_m == 0.2 - dx, tt::tolerance(1e-14));
}

BOOST_AUTO_TEST_CASE(RatesMatchFiniteDifferencesOfAGeneralMotion) {
  const Candidate c = paper_candidate();
  const SlabMotion a0 = slab(Point2(-10.8, 11), {0.1, -0.03, 0.02}, {0.7, -0.4, 0.3});
  const SlabMotion b0 = slab(Point2(12.8, 19.25), {-0.05, 0.02, -0.015}, {-0.5, 0.6, -0.25});
  const Eigen::Vector3d acc_a(2.0, -1.0, 0.8), acc_b(-1.5, 0.5, -0.6);
  const double h = 1e-5;
  auto gap_at = [&](double t) { return evaluate_gap(c, advanced(a0, acc_a, t), advanced(b0, acc_b, t)); };

  const GapState s = gap_at(0.0);
  const double rate_fd = (gap_at(h).gap_m - gap_at(-h).gap_m) / (2 * h);
  BOOST_TEST(s.gap_rate_mps == rate_fd, tt::tolerance(1e-8));
  const double rate_from_rows = s.striking_row.dot(a0.q_dot) + s.struck_row.dot(b0.q_dot);
  BOOST_TEST(rate_from_rows == s.gap_rate_mps, tt::tolerance(1e-13));

  const double accel_fd = (gap_at(h).gap_m - 2 * s.gap_m + gap_at(-h).gap_m) / (h * h);
  const double accel = s.striking_row.dot(acc_a) + s.struck_row.dot(acc_b) + s.curvature_mps2;
  BOOST_TEST(accel == accel_fd, tt::tolerance(1e-5));
}
