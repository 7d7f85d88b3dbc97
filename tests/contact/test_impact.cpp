#include <boost/test/unit_test.hpp>

#include <cmath>

#include <Eigen/LU>

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
    r.jacobian.resize(6);
    r.jacobian << s.striking_row, s.struck_row;
    r.gap_rate_mps = s.gap_rate_mps;
    r.restitution = k;
    return r;
  }
  Eigen::Vector2d momentum(const Vector6d& v) const { return m_a * v.head<2>() + m_b * v.segment<2>(3); }
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

BOOST_AUTO_TEST_CASE(HoldingOneCornerDoesNotCloseTheOtherAgain) {
  // A's right edge against B's left one at two corners (as at a zero gap): the upper one, to be
  // held, separates slowly (1e-4 m/s) and spins A; the lower one has just been struck to rest
  // (k = 0: ġ = 0). Closing the upper one alone pulls A's edge round and leaves the lower one
  // closing again; keeping the lower one, both end at ġ = 0 exactly (the 2 x 2 closed form), the
  // lower one by a push (impulse > 0). Radii of gyration of 10 m (slabs long along the facade, as
  // at a street): a pull at one corner moves the slab more than it turns it.
  FreePair pair;
  pair.j_a = pair.m_a * 100.0;
  pair.j_b = pair.m_b * 100.0;
  const Candidate lower{1, {1, 1}, 3.0, 0, 1, 1, 3, Point2(0, 0), Point2(0, 10), Point2(0, 0), Point2(-1, 0)};
  const Candidate upper{1, {1, 1}, 3.0, 0, 1, 2, 3, Point2(0, 10), Point2(0, 10), Point2(0, 0), Point2(-1, 0)};
  Vector6d before;  // A backing off at 5e-5 m/s while it turns anticlockwise at 1e-5 rad/s about (-5, 5)
  before << -5e-5, 0, 1e-5, 0, 0, 0;
  const ContactRow low0 = pair.row(lower, before, 0.0), up0 = pair.row(upper, before, 0.0);
  BOOST_TEST_REQUIRE(std::abs(low0.gap_rate_mps) <= 1e-12);
  BOOST_TEST_REQUIRE(up0.gap_rate_mps == 1e-4, tt::tolerance(1e-9));

  const ImpulseSolution plain = closing_impulses({up0.jacobian}, pair.inverse(), before);
  BOOST_TEST(pair.row(lower, before + plain.velocity_change, 0.0).gap_rate_mps < -1e-5);  // closing again

  const ImpulseSolution kept = closing_impulses_keeping({up0.jacobian}, {{low0.jacobian, 0.0}}, pair.inverse(), before);
  const Vector6d after = before + kept.velocity_change;
  BOOST_TEST(std::abs(pair.row(upper, after, 0.0).gap_rate_mps) <= 1e-15);
  BOOST_TEST(std::abs(pair.row(lower, after, 0.0).gap_rate_mps) <= 1e-15);
  BOOST_TEST_REQUIRE(kept.impulses_kNs.size() == 2u);
  BOOST_TEST(kept.impulses_kNs[1] > 0.0);
  Eigen::Matrix<double, 2, 6> g;
  g << up0.jacobian, low0.jacobian;
  const Eigen::Matrix2d w = g * pair.inverse().asDiagonal() * g.transpose();
  const Eigen::Vector2d closed_form = w.inverse() * -(g * before);
  BOOST_TEST(kept.impulses_kNs[0] == closed_form[0], tt::tolerance(1e-10));
  BOOST_TEST(kept.impulses_kNs[1] == closed_form[1], tt::tolerance(1e-10));
  BOOST_TEST((pair.momentum(after) - pair.momentum(before)).norm() <= 1e-12);

  // A neighbour the closing leaves open is not touched: the held rows' own closing, bit for bit.
  const ImpulseSolution open =
      closing_impulses_keeping({up0.jacobian}, {{low0.jacobian, -1.0}}, pair.inverse(), before);
  BOOST_TEST(open.impulses_kNs[0] == plain.impulses_kNs[0]);
  BOOST_TEST(open.impulses_kNs[1] == 0.0);
  BOOST_TEST((open.velocity_change - plain.velocity_change).norm() == 0.0);
}

BOOST_AUTO_TEST_CASE(SeparatingContactTakesNoImpulse) {
  const FreePair pair;
  Vector6d before;
  before << -0.5, 0, 0, 0, 0, 0;  // A moving away
  const auto solution = solve_impulses({pair.row(pair.corner(Point2(0, 3)), before, 0.5)}, pair.inverse());
  BOOST_TEST(solution.impulses_kNs[0] == 0.0);
  BOOST_TEST(solution.velocity_change.norm() == 0.0);
}

namespace {

// Three free slabs in a line along x, A | B | C, the contacts A:B and B:C head-on through every
// CM (rows over the nine velocities (u̇, v̇, φ̇) of A, B, C): ġ_AB = u̇_B − u̇_A, ġ_BC = u̇_C − u̇_B.
struct FreeChain {
  Eigen::VectorXd inverse(double m_a, double m_b, double m_c) const {
    Eigen::VectorXd inv(9);
    inv << 1 / m_a, 1 / m_a, 1 / (m_a * 10), 1 / m_b, 1 / m_b, 1 / (m_b * 10), 1 / m_c, 1 / m_c, 1 / (m_c * 10);
    return inv;
  }
  static ContactRow contact(int left, const Eigen::VectorXd& velocity, double k) {
    ContactRow row;
    row.jacobian = Eigen::RowVectorXd::Zero(9);
    row.jacobian[3 * left] = -1.0;
    row.jacobian[3 * left + 3] = 1.0;
    row.gap_rate_mps = row.jacobian.dot(velocity);
    row.restitution = k;
    return row;
  }
};

}  // namespace

BOOST_AUTO_TEST_CASE(MiddleSlabStruckFromBothSidesAtOnceIsOneProblem) {
  // A and C (equal masses) close on B at rest with equal speeds: by symmetry B stays at rest,
  // each contact separates at k times its approach and takes I = m (1 + k) v.
  const double m = 200, k = 0.5, v = 1.5;
  Eigen::VectorXd before = Eigen::VectorXd::Zero(9);
  before[0] = v;
  before[6] = -v;
  const FreeChain chain;
  const auto solution =
      solve_impulses({chain.contact(0, before, k), chain.contact(1, before, k)}, chain.inverse(m, 300, m));
  const Eigen::VectorXd after = before + solution.velocity_change;
  BOOST_TEST(after[3] == 0.0, tt::tolerance(1e-14));
  BOOST_TEST(after[0] == -k * v, tt::tolerance(1e-12));
  BOOST_TEST(after[6] == k * v, tt::tolerance(1e-12));
  for (double impulse : solution.impulses_kNs) BOOST_TEST(impulse == m * (1 + k) * v, tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(PlasticStrikeOnSlabsInContactMovesThemAllTogether) {
  // B rests against C (ġ_BC = 0) when A strikes B with k = 0: the one problem over the three
  // slabs leaves all three with the common velocity m_A v / (m_A + m_B + m_C). Solving A:B alone
  // would drive B into C.
  const double m_a = 200, m_b = 300, m_c = 150, v = 1.2;
  Eigen::VectorXd before = Eigen::VectorXd::Zero(9);
  before[0] = v;
  const FreeChain chain;
  const Eigen::VectorXd inverse = chain.inverse(m_a, m_b, m_c);
  const auto joint = solve_impulses({chain.contact(0, before, 0.0), chain.contact(1, before, 0.0)}, inverse);
  const Eigen::VectorXd after = before + joint.velocity_change;
  const double common = m_a * v / (m_a + m_b + m_c);
  for (int slab = 0; slab < 3; ++slab) BOOST_TEST(after[3 * slab] == common, tt::tolerance(1e-12));
  BOOST_TEST(joint.impulses_kNs[1] == m_c * common, tt::tolerance(1e-12));

  const auto alone = solve_impulses({chain.contact(0, before, 0.0)}, inverse);
  const Eigen::VectorXd after_alone = before + alone.velocity_change;
  BOOST_TEST(chain.contact(1, after_alone, 0.0).gap_rate_mps < -0.1);  // B would close on C
}

namespace {

// A plastic strike on `rows` independent rows of `slabs` free slabs at rest in contact along x (in
// each row the first slab strikes the rest, every contact head-on through the CMs and given
// `copies` times, as coincident corners give it): the closed form is one common velocity
// m_A v / Σm per row, the contact behind slab j taking the momentum of the slabs beyond it,
// (Σ_{i>j} m_i) times that velocity. Solved exactly when every row has at most 12 contact rows
// (independent rows are separate problems), else iteratively.
void check_plastic_strikes(int rows, int slabs, int copies) {
  const double v = 0.8;
  const int total = rows * slabs;
  Eigen::VectorXd inverse(3 * total);
  std::vector<double> mass;
  for (int j = 0; j < total; ++j) {
    mass.push_back(150.0 + 37.0 * (j % 5));
    inverse.segment(3 * j, 3) << 1 / mass.back(), 1 / mass.back(), 1 / (10 * mass.back());
  }
  Eigen::VectorXd before = Eigen::VectorXd::Zero(3 * total);
  std::vector<ContactRow> contacts;
  for (int row = 0; row < rows; ++row) {
    before[3 * row * slabs] = v;
    for (int j = row * slabs; j + 1 < (row + 1) * slabs; ++j) {
      for (int c = 0; c < copies; ++c) {
        ContactRow contact;
        contact.jacobian = Eigen::RowVectorXd::Zero(3 * total);
        contact.jacobian[3 * j] = -1.0;
        contact.jacobian[3 * j + 3] = 1.0;
        contact.gap_rate_mps = contact.jacobian.dot(before);
        contact.restitution = 0.0;
        contacts.push_back(contact);
      }
    }
  }
  const ImpulseSolution solution = solve_impulses(contacts, inverse);
  BOOST_TEST(solution.exact == ((slabs - 1) * copies <= 12));
  BOOST_TEST(solution.lcp_residual <= 1e-12);
  const Eigen::VectorXd after = before + solution.velocity_change;
  std::size_t next = 0;
  for (int row = 0; row < rows; ++row) {
    const auto first = static_cast<std::size_t>(row * slabs);
    double beyond = 0.0;
    for (int j = 0; j < slabs; ++j) beyond += mass[first + static_cast<std::size_t>(j)];
    const double common = mass[first] * v / beyond;
    for (int j = 0; j < slabs; ++j) BOOST_TEST(after[3 * (row * slabs + j)] == common, tt::tolerance(1e-10));
    for (int j = 0; j + 1 < slabs; ++j) {
      beyond -= mass[first + static_cast<std::size_t>(j)];
      double impulse = 0.0;  // the copies share it in some way; their sum is determined
      for (int c = 0; c < copies; ++c) impulse += solution.impulses_kNs[next++];
      BOOST_TEST(impulse == beyond * common, tt::tolerance(1e-9));
    }
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(PlasticStrikeOnARowOfSeventeenSlabsBeyondTheEnumeratedSize) {
  check_plastic_strikes(1, 17, 1);  // 16 contacts, one coupled problem: Gauss–Seidel
}

BOOST_AUTO_TEST_CASE(PlasticStrikeOnARowWithCoincidentContacts) {
  check_plastic_strikes(1, 8, 2);  // 14 contacts, pairwise identical rows
}

BOOST_AUTO_TEST_CASE(IndependentRowsBeyondTheEnumeratedSizeAreSolvedExactly) {
  check_plastic_strikes(4, 5, 1);  // 16 contacts in four independent problems of 4
}

BOOST_AUTO_TEST_CASE(GapRateOfAFloorPairIsTheDotProduct) {
  Eigen::RowVectorXd row(6);
  row << 0.3, -1.0, 2.5, -0.3, 1.0, -7.25;
  Eigen::VectorXd velocity(6);
  velocity << 1.0, 0.5, -0.02, 0.25, -0.75, 0.01;
  BOOST_TEST(gap_rate(row, velocity) == row.dot(velocity), tt::tolerance(1e-15));
  BOOST_TEST(gap_rate(row.head(3), velocity.head(3)) == row.head(3).dot(velocity.head(3)));
}
