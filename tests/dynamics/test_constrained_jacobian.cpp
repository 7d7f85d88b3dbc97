// CoupledSystem::jacobian() and constrained_jacobian() against central differences of rhs()
// and constrained_rhs(), with contacts held between two rotating two-storey slabs.
//
// constrained_jacobian() freezes the constraint rows G at y (coupled_system.hpp). So it must
// equal the difference quotients exactly (up to the differencing's round-off) wherever G does
// not move: the velocity rows and the columns of the floors outside the held contacts. In the
// contact floors' columns the turning of G is left out; that error must vanish at rest and grow
// linearly with the motion, which is checked by scaling one state down.

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "pounding/contact/candidates.hpp"
#include "pounding/dynamics/coupled_system.hpp"

using namespace pounding;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

model::Polygon box(double x0, double y0, double x1, double y1) {
  return model::Polygon({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}});
}

/// Two storeys, each floor 100 t (building 2: 60 t), storeys with coupled stiffness matrices so
/// translation and torsion interact; the CM off the slab's centroid.
model::Building building(const char* name, const model::Polygon& slab, const model::Point2& cm, double mass_t) {
  model::BuildingDefinition b;
  b.name = name;
  b.storeys = 2;
  b.storey_height_m = {3.0, 3.0};
  b.slab = slab;
  b.centre_of_mass = cm;
  b.mass_t = {mass_t, mass_t};
  b.polar_moment_tm2 = {model::uniform_polar_moment(slab, mass_t), model::uniform_polar_moment(slab, mass_t)};
  Eigen::Matrix3d k;
  k << 4.0e5, 2.0e4, 1.0e5, 2.0e4, 6.0e5, -8.0e4, 1.0e5, -8.0e4, 9.0e6;  // kN/m, kN, kN·m
  b.storey_stiffness = {k, 0.7 * k};
  b.damping = {0.05, {1, 3}};
  return model::make_building(b);
}

/// Building 1 on [−10, 0] × [0, 10], building 2 on [0, 8] × [1, 7], touching at rest (no gap);
/// a_g zero at t = 0 and 2 m/s² at t = 1, at 0.3 rad from x.
dynamics::CoupledSystem touching_slabs() {
  const model::Polygon left = box(-10, 0, 0, 10), right = box(0, 1, 8, 7);
  const model::Point2 left_cm(-5.5, 4.6), right_cm(4.4, 4.3);
  std::vector<model::Building> buildings{building("A", left, left_cm, 100.0), building("B", right, right_cm, 60.0)};
  const std::vector<contact::Level> levels{{.index = 1, .floors = {1, 1}, .elevation_m = 3.0},
                                           {.index = 2, .floors = {2, 2}, .elevation_m = 6.0}};
  auto candidates =
      contact::find_candidates({{left, right}, {left_cm, right_cm}}, levels, {.margin_m = 1.0, .gap_m = 0.0});
  return dynamics::CoupledSystem(std::move(buildings), excitation::GroundMotion({0.0, 1.0, 2.0}, {0.0, 2.0, 0.0}, 0.3),
                                 levels, std::move(candidates));
}

/// The held contacts: building 2's two corners on building 1's face, at the upper level.
std::vector<std::size_t> held_at_level_2(const dynamics::CoupledSystem& system) {
  std::vector<std::size_t> held;
  for (std::size_t i = 0; i < system.candidates().size(); ++i) {
    const contact::Candidate& c = system.candidates()[i];
    if (c.level == 2 && c.striking_building == 1 && !c.corner) held.push_back(i);
  }
  return held;
}

/// Typical magnitude of each state component: 5 cm, 5 mrad, 0.5 m/s, 0.05 rad/s.
VectorXd typical_scale(const dynamics::CoupledSystem& system) {
  VectorXd scale(system.state_size());
  for (int i = 0; i < system.dof(); ++i) {
    const bool rotation = i % 3 == 2;
    scale[i] = rotation ? 5e-3 : 5e-2;
    scale[system.dof() + i] = rotation ? 5e-2 : 0.5;
  }
  return scale;
}

/// A random state of that magnitude (a rotating slab: every φ and φ̇ non-zero).
VectorXd random_state(const dynamics::CoupledSystem& system, unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  VectorXd y = typical_scale(system);
  for (Eigen::Index i = 0; i < y.size(); ++i) y[i] *= unit(generator);
  return y;
}

struct Differences {
  MatrixXd jacobian;
  VectorXd round_off;  // per column: bound on the round-off of the quotient, 100 ε max|f| / h
};

/// Central differences of f with step h_j = 1e-6 · scale_j. For a column in which f is affine
/// the quotient is exact but for round-off; elsewhere its truncation error is ~h²|f'''|/6.
template <typename F>
Differences central_differences(F f, const VectorXd& y, const VectorXd& scale) {
  const Eigen::Index n = y.size();
  Differences d{MatrixXd(n, n), VectorXd(n)};
  VectorXd plus(n), minus(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const double h = 1e-6 * scale[j];
    VectorXd y_plus = y, y_minus = y;
    y_plus[j] += h;
    y_minus[j] -= h;
    f(y_plus, plus);
    f(y_minus, minus);
    d.jacobian.col(j) = (plus - minus) / (y_plus[j] - y_minus[j]);
    d.round_off[j] = 100.0 * kEps * std::max(plus.cwiseAbs().maxCoeff(), minus.cwiseAbs().maxCoeff()) / h;
  }
  return d;
}

/// Indices in y of the floors' displacements and velocities of floors `floor` of both buildings.
std::vector<int> floor_columns(const dynamics::CoupledSystem& system, int floor) {
  std::vector<int> columns;
  for (int b = 0; b < 2; ++b) {
    for (int k = 0; k < 3; ++k) {
      columns.push_back(system.floor_index(b, floor) + k);
      columns.push_back(system.dof() + system.floor_index(b, floor) + k);
    }
  }
  return columns;
}

}  // namespace

BOOST_AUTO_TEST_CASE(TheFreeJacobianIsTheDerivativeOfTheFreeMotion) {
  const auto system = touching_slabs();
  const VectorXd scale = typical_scale(system);
  for (unsigned seed : {1u, 2u, 3u}) {
    const VectorXd y = random_state(system, seed);
    const auto d = central_differences([&](const VectorXd& s, VectorXd& f) { system.rhs(1.0, s, f); }, y, scale);
    // rhs is affine in y: only round-off separates the quotients from A.
    for (Eigen::Index j = 0; j < y.size(); ++j) {
      const double error = (d.jacobian.col(j) - system.jacobian().col(j)).cwiseAbs().maxCoeff();
      BOOST_TEST(error <= d.round_off[j], "seed " << seed << ", column " << j);
    }
  }
}

BOOST_AUTO_TEST_CASE(TheConstrainedJacobianIsExactWhereTheRowsDoNotMove) {
  const auto system = touching_slabs();
  const std::vector<std::size_t> held = held_at_level_2(system);
  BOOST_TEST_REQUIRE(held.size() == 2u);
  const VectorXd scale = typical_scale(system);
  const int n = system.dof();
  for (unsigned seed : {1u, 2u, 3u, 4u}) {
    const VectorXd y = random_state(system, seed);
    VectorXd forces(held.size());
    const auto d = central_differences(
        [&](const VectorXd& s, VectorXd& f) { system.constrained_rhs(1.0, s, held, f, forces); }, y, scale);
    MatrixXd analytic(2 * n, 2 * n);
    system.constrained_jacobian(y, held, analytic);
    // The held contacts do act here: the projection changes the Jacobian.
    BOOST_TEST((analytic - system.jacobian()).norm() > 1e-3 * system.jacobian().norm());

    // ∂q/∂t = q̇: the upper half, all columns.
    for (Eigen::Index j = 0; j < 2 * n; ++j) {
      const double error = (d.jacobian.col(j).head(n) - analytic.col(j).head(n)).cwiseAbs().maxCoeff();
      BOOST_TEST(error <= d.round_off[j], "seed " << seed << ", velocity rows, column " << j);
    }
    // Floor 1 of both buildings holds no contact: there constrained_rhs is affine in y and the
    // frozen rows are the true ones; all rows.
    for (int j : floor_columns(system, 1)) {
      const double error = (d.jacobian.col(j) - analytic.col(j)).cwiseAbs().maxCoeff();
      BOOST_TEST(error <= d.round_off[j], "seed " << seed << ", floor-1 column " << j << ": error " << error
                                                  << ", column size " << analytic.col(j).cwiseAbs().maxCoeff());
    }
  }
}

BOOST_AUTO_TEST_CASE(TheFrozenRowsErrorVanishesAtRestAndIsFirstOrderInTheMotion) {
  // At s · y (a_g = 0 at t = 0, the slabs touching at rest) every term the frozen rows leave
  // out carries a force, an acceleration or a velocity, each O(s): the error D(s) of the
  // contact floors' columns is s D₁ + O(s²). A mistake in the terms that are kept (projection,
  // Baumgarte gains) would leave D(0) ≠ 0 and the ratio D(s)/D(s/2) near 1 instead of 2.
  const auto system = touching_slabs();
  const std::vector<std::size_t> held = held_at_level_2(system);
  const VectorXd scale = typical_scale(system);
  const int n = system.dof();
  for (unsigned seed : {5u, 6u, 7u}) {
    const VectorXd y = random_state(system, seed);
    const auto frozen_rows_error = [&](double s) {
      const VectorXd ys = s * y;
      VectorXd forces(held.size());
      const auto d = central_differences(
          [&](const VectorXd& state, VectorXd& f) { system.constrained_rhs(0.0, state, held, f, forces); }, ys, scale);
      MatrixXd analytic(2 * n, 2 * n);
      system.constrained_jacobian(ys, held, analytic);
      // Columns in units of the typical state, so metres and radians weigh alike.
      return ((d.jacobian - analytic) * scale.asDiagonal()).norm() / (analytic * scale.asDiagonal()).norm();
    };
    const double full = frozen_rows_error(1.0), small = frozen_rows_error(1e-2), half = frozen_rows_error(5e-3);
    BOOST_TEST_MESSAGE("seed " << seed << ": relative error of the frozen rows " << full << " at the typical motion, "
                               << small << " at 1 % of it");
    BOOST_TEST(full > 0.0);
    BOOST_TEST(small / half == 2.0, boost::test_tools::tolerance(0.05));
    BOOST_TEST(small <= 2e-2 * full);
  }
}
