#define BOOST_TEST_MODULE impact
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "pounding/contact/gap.hpp"
#include "pounding/contact/impact.hpp"

namespace tt = boost::test_tools;
using namespace pounding::contact;
using pounding::model::Point2;

namespace {

// Two free 10 × 10 slabs (no storeys), A on the left moving +x, B on the right at rest.
// A's corner at (0, y_hit) strikes B's left edge x = 0.
struct FreePair {
  double m_a = 200, j_a = 200 * 200.0 / 12, m_b = 300, j_b = 300 * 200.0 / 12;
  Point2 centre_a{-5, 5}, centre_b{5, 3};
  Vector6d inverse() const { return inverse_mass(m_a, j_a, m_b, j_b); }

  Candidate corner(Point2 vertex) const {
    return {1, {1, 1}, 3.0, 0, 1, 1, 3, vertex, Point2(0, 8), Point2(0, -2), Point2(-1, 0)};
  }
  ContactRow row(const Candidate& c, const Vector6d& velocity, double k) const {
    const SlabMotion a{centre_a, Eigen::Vector3d::Zero(), velocity.head<3>()};
    const SlabMotion b{centre_b, Eigen::Vector3d::Zero(), velocity.tail<3>()};
    const GapState s = evaluate_gap(c, a, b);
    ContactRow r;
    r.jacobian << s.striking_row, s.struck_row;
    r.gap_rate_mps = s.gap_rate_mps;
    r.restitution = k;
    return r;
  }
  Eigen::Vector2d momentum(const Vector6d& v) const {
    return m_a * v.head<2>() + m_b * v.segment<2>(3);
  }
  // About the origin: Σ m (c × v) + J φ̇.
  double angular_momentum(const Vector6d& v) const {
    auto cross = [](Point2 r, Eigen::Vector2d w) { return r.x() * w.y() - r.y() * w.x(); };
    return m_a * cross(centre_a, v.head<2>()) + j_a * v[2] + m_b * cross(centre_b, v.segment<2>(3)) + j_b * v[5];
  }
};

void check_single_impact(Point2 vertex, double k) {
  const FreePair pair;
  Vector6d before;
  before << 1.2, 0.1, 0.05, -0.3, 0.0, 0.0;
  const ContactRow row = pair.row(pair.corner(vertex), before, k);
  BOOST_TEST_REQUIRE(row.gap_rate_mps < 0.0);

  const ImpulseSolution solution = solve_impulses({row}, pair.inverse());
  const Vector6d after = before + solution.velocity_change;
  const ContactRow row_after = pair.row(pair.corner(vertex), after, k);

  BOOST_TEST(solution.impulses_kNs[0] == single_impulse(row, pair.inverse()), tt::tolerance(1e-12));
  BOOST_TEST(row_after.gap_rate_mps == -k * row.gap_rate_mps, tt::tolerance(1e-12));
  BOOST_TEST((pair.momentum(after) - pair.momentum(before)).norm() <= 1e-12);
  BOOST_TEST(pair.angular_momentum(after) == pair.angular_momentum(before), tt::tolerance(1e-12));
  // Energy lost, closed form: ½ (1 − k²) ġ⁻² / a with a = Σ (1/m + h²/J).
  const double a = row.jacobian.cwiseAbs2().dot(pair.inverse().transpose());
  const double lost = kinetic_energy(before, pair.inverse()) - kinetic_energy(after, pair.inverse());
  BOOST_TEST(lost == 0.5 * (1 - k * k) * row.gap_rate_mps * row.gap_rate_mps / a, tt::tolerance(1e-10));
}

}  // namespace

BOOST_AUTO_TEST_CASE(HeadOnImpactConservesMomentumAndMeetsRestitution) {
  for (double k : {0.0, 0.5, 1.0}) check_single_impact(Point2(0, 3), k);  // in line with B's CM
}

BOOST_AUTO_TEST_CASE(OffCentreImpactConservesMomentumAndAngularMomentum) {
  for (double k : {0.0, 0.5, 1.0}) check_single_impact(Point2(0, 7.5), k);
}

BOOST_AUTO_TEST_CASE(HeadOnCentredImpactEqualsOneDimensionalCollision) {
  // Both CMs on the line of impact (y = 5) and pure translation: the textbook 1-D result.
  FreePair pair;
  pair.centre_b = Point2(5, 5);
  const double k = 0.5, v_a = 2.0, v_b = -0.5;
  Vector6d before;
  before << v_a, 0, 0, v_b, 0, 0;
  const auto solution = solve_impulses({pair.row(pair.corner(Point2(0, 5)), before, k)}, pair.inverse());
  const Vector6d after = before + solution.velocity_change;
  const double total = pair.m_a + pair.m_b;
  const double v_a_after = (pair.m_a * v_a + pair.m_b * v_b - pair.m_b * k * (v_a - v_b)) / total;
  BOOST_TEST(after[0] == v_a_after, tt::tolerance(1e-12));
  BOOST_TEST(after[2] == 0.0, tt::tolerance(1e-14));
}

BOOST_AUTO_TEST_CASE(SymmetricFaceImpactSolvedTogetherGivesNoRotation) {
  // A's two right corners (0, 0) and (0, 10) strike B's left edge at once; everything is
  // symmetric about y = 5, so the joint solution must not rotate either slab and must equal
  // the 1-D collision. Applying the two contacts one after the other does rotate them.
  FreePair pair;
  pair.centre_b = Point2(5, 5);
  const double k = 0.5, v_a = 1.0;
  Vector6d before;
  before << v_a, 0, 0, 0, 0, 0;
  const Candidate lower{1, {1, 1}, 3.0, 0, 1, 1, 3, Point2(0, 0), Point2(0, 10), Point2(0, 0), Point2(-1, 0)};
  const Candidate upper{1, {1, 1}, 3.0, 0, 1, 2, 3, Point2(0, 10), Point2(0, 10), Point2(0, 0), Point2(-1, 0)};

  const auto joint = solve_impulses({pair.row(lower, before, k), pair.row(upper, before, k)}, pair.inverse());
  const Vector6d after = before + joint.velocity_change;
  BOOST_TEST(std::abs(after[2]) <= 1e-14);
  BOOST_TEST(std::abs(after[5]) <= 1e-14);
  const double total = pair.m_a + pair.m_b;
  BOOST_TEST(after[0] == (pair.m_a - k * pair.m_b) * v_a / total, tt::tolerance(1e-12));
  BOOST_TEST(after[3] == pair.m_a * (1 + k) * v_a / total, tt::tolerance(1e-12));

  // One after the other: the lower corner first, then the upper one if it still approaches.
  Vector6d sequential = before;
  for (const Candidate* c : {&lower, &upper}) {
    const ContactRow row = pair.row(*c, sequential, k);
    if (row.gap_rate_mps < 0) sequential += solve_impulses({row}, pair.inverse()).velocity_change;
  }
  BOOST_TEST(std::abs(sequential[2]) > 1e-3);  // a spurious spin
  BOOST_TEST(std::abs(sequential[0] - after[0]) > 1e-3);
}

BOOST_AUTO_TEST_CASE(SeparatingContactTakesNoImpulse) {
  const FreePair pair;
  Vector6d before;
  before << -0.5, 0, 0, 0, 0, 0;  // A moving away
  const auto solution = solve_impulses({pair.row(pair.corner(Point2(0, 3)), before, 0.5)}, pair.inverse());
  BOOST_TEST(solution.impulses_kNs[0] == 0.0);
  BOOST_TEST(solution.velocity_change.norm() == 0.0);
}
