#include <boost/test/unit_test.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "../support/two_slabs.hpp"
#include "pounding/contact/column_contact.hpp"
#include "pounding/contact/compliant_law.hpp"
#include "pounding/contact/kelvin.hpp"

namespace tt = boost::test_tools;
using namespace pounding;
using namespace pounding::testing;
using model::Point2;

namespace {

constexpr double kPi = std::numbers::pi;

/// A fixed–fixed Euler–Bernoulli member of length L and bending stiffness EI as two beam
/// elements joined at a = ξL (cubic elements are exact for loads at nodes): written here, not
/// from the library. Unknowns: the joint's deflection w and slope θ, then the top's (w, θ).
struct TwoElementBeam {
  double length, ei, a;
  /// The element stiffness (w₁, θ₁, w₂, θ₂) of a member of length l.
  static Eigen::Matrix4d element(double l, double ei) {
    Eigen::Matrix4d k;
    k << 12, 6 * l, -12, 6 * l, 6 * l, 4 * l * l, -6 * l, 2 * l * l, -12, -6 * l, 12, -6 * l, 6 * l, 2 * l * l, -6 * l,
        4 * l * l;
    return k * ei / (l * l * l);
  }
  /// The stiffness over (w₀, θ₀, w_a, θ_a, w_L, θ_L).
  Eigen::Matrix<double, 6, 6> assembled() const {
    Eigen::Matrix<double, 6, 6> k = Eigen::Matrix<double, 6, 6>::Zero();
    k.block<4, 4>(0, 0) += element(a, ei);
    k.block<4, 4>(2, 2) += element(length - a, ei);
    return k;
  }
  /// Deflection at the joint under a unit load there, both ends fixed.
  double flexibility() const {
    const Eigen::Matrix2d k = assembled().block<2, 2>(2, 2);
    return k.inverse()(0, 0);
  }
  /// The joint's deflection when the top end moves by 1 without turning (bottom fixed).
  double shape_of_top_translation() const {
    const Eigen::Matrix<double, 6, 6> k = assembled();
    const Eigen::Vector2d rhs = -k.block<2, 1>(2, 4);  // the top's unit translation moves the joint
    return k.block<2, 2>(2, 2).lu().solve(rhs)[0];
  }
  /// The reactions (shear, moment) at both ends under a load P at the joint.
  Eigen::Matrix<double, 6, 1> end_forces(double p) const {
    const Eigen::Matrix<double, 6, 6> k = assembled();
    Eigen::Matrix<double, 6, 1> u = Eigen::Matrix<double, 6, 1>::Zero();
    u.segment<2>(2) = k.block<2, 2>(2, 2).lu().solve(Eigen::Vector2d(p, 0.0));
    return k * u;  // the forces the supports apply (and the load at the joint)
  }
};

}  // namespace

BOOST_AUTO_TEST_CASE(FlexibilityOfAFixedFixedColumnMatchesTwoBeamElements) {
  const model::Column column{{0, 0}, 0.4, 0.6};  // b along x, h along y
  const double e_kpa = 3e7, length = 3.5;
  for (double xi : {0.1, 0.3, 0.5, 0.77, 0.95}) {
    const double ix = 0.6 * std::pow(0.4, 3) / 12, iy = 0.4 * std::pow(0.6, 3) / 12;
    const TwoElementBeam along_x{length, e_kpa * ix, xi * length}, along_y{length, e_kpa * iy, xi * length};
    BOOST_TEST_CONTEXT("xi = " << xi) {
      BOOST_TEST(contact::column_flexibility(column, e_kpa, length, xi, {1, 0}) == along_x.flexibility(),
                 tt::tolerance(1e-12));
      BOOST_TEST(contact::column_flexibility(column, e_kpa, length, xi, {0, -1}) == along_y.flexibility(),
                 tt::tolerance(1e-12));
      // An oblique load: the two bending directions in series, weighted by n_x², n_y².
      const Point2 n = Point2(3, 4) / 5;
      BOOST_TEST(contact::column_flexibility(column, e_kpa, length, xi, n) ==
                     0.36 * along_x.flexibility() + 0.64 * along_y.flexibility(),
                 tt::tolerance(1e-12));
    }
  }
}

BOOST_AUTO_TEST_CASE(ColumnShapeIsTheDeflectionUnderEndTranslation) {
  for (double xi : {0.0, 0.2, 0.5, 0.6667, 1.0}) {
    const auto [lower, upper] = contact::column_shape(xi);
    BOOST_TEST(lower + upper == 1.0, tt::tolerance(1e-15));
    if (xi == 0.0 || xi == 1.0) {
      BOOST_TEST(upper == xi);
      continue;
    }
    const TwoElementBeam beam{3.0, 1e5, 3.0 * xi};
    BOOST_TEST(upper == beam.shape_of_top_translation(), tt::tolerance(1e-12));
  }
}

BOOST_AUTO_TEST_CASE(ColumnDemandIsTheLargestEndShearAndMoment) {
  const double p = 250.0, length = 4.0;
  for (double xi : {0.2, 0.5, 0.8}) {
    const TwoElementBeam beam{length, 1e5, xi * length};
    const Eigen::Matrix<double, 6, 1> f = beam.end_forces(p);
    const double a = xi * length;
    const double under_load = std::abs(f[0] * a - f[1]);  // the bottom's shear and moment carried to a
    const contact::ColumnDemand demand = contact::column_demand(p, length, xi);
    BOOST_TEST_CONTEXT("xi = " << xi) {
      BOOST_TEST(demand.shear_kN == std::max(std::abs(f[0]), std::abs(f[4])), tt::tolerance(1e-10));
      BOOST_TEST(demand.moment_kNm == std::max({std::abs(f[1]), std::abs(f[5]), under_load}), tt::tolerance(1e-10));
      BOOST_TEST(std::abs(f[0]) + std::abs(f[4]) == p, tt::tolerance(1e-12));  // equilibrium
    }
  }
}

BOOST_AUTO_TEST_CASE(ColumnLevelsAreTheFloorsBetweenTheOthersBelowTheirRoof) {
  // B1: 4.5 m, 9 m, 13.5 m; B2: 3, 6, 9 m. B1's 4.5 m faces B2's storey 2 at 0.5; its 9 m
  // floor is a common level; 13.5 m is above B2's roof. B2's 3 m faces B1's storey 1 at 2/3 and
  // its 6 m B1's storey 2 at 1/3.
  const auto levels = contact::column_levels({std::vector{4.5, 9.0, 13.5}, std::vector{3.0, 6.0, 9.0}}, 1e-3);
  BOOST_TEST_REQUIRE(levels.size() == 3u);
  BOOST_TEST(levels[0].slab_building == 0);
  BOOST_TEST(levels[0].slab_floor == 1);
  BOOST_TEST(levels[0].storey == 2);
  BOOST_TEST(levels[0].height_ratio == 0.5, tt::tolerance(1e-15));
  BOOST_TEST(levels[0].storey_height_m == 3.0, tt::tolerance(1e-15));
  BOOST_TEST(levels[1].slab_building == 1);
  BOOST_TEST(levels[1].storey == 1);
  BOOST_TEST(levels[1].height_ratio == 2.0 / 3.0, tt::tolerance(1e-15));
  BOOST_TEST(levels[2].slab_floor == 2);
  BOOST_TEST(levels[2].storey == 2);
  BOOST_TEST(levels[2].height_ratio == 1.5 / 4.5, tt::tolerance(1e-14));
  // Within the tolerance of a floor, a slab meets it face on instead.
  BOOST_TEST(contact::column_levels({std::vector{3.0005}, std::vector{3.0, 6.0}}, 1e-3).empty());
}

BOOST_AUTO_TEST_CASE(SeriesColumnSoftensEachLawAsTwoSpringsInSeries) {
  const double f = 4e-6;  // m/kN
  // kelvin: the pair's spring is 1/(1/k + f), and a lone undamped contact's force is k_s δ.
  const contact::CompliantContact kelvin(contact::ContactLaw::kelvin, 1e5, 1.0, 0.5, 0.01, f);
  BOOST_TEST(kelvin.force_kN(1e-3, 0.0) == 1e-3 / (1e-5 + f), tt::tolerance(1e-13));
  // The Hertz laws: the force F with δ = (F/k)^(2/3) + f F, the two springs' overlaps summed.
  const double k = 2e6;
  for (contact::ContactLaw law : {contact::ContactLaw::hertzdamp, contact::ContactLaw::jankowski}) {
    const contact::CompliantContact hertz(law, k, 0.6, 0.5, 0.01, f);
    for (double overlap : {1e-9, 1e-6, 1e-4, 3e-3, 0.05}) {
      const double force = hertz.force_kN(overlap, 0.0);
      BOOST_TEST(std::pow(force / k, 2.0 / 3.0) + f * force == overlap, tt::tolerance(1e-12));
      // The slope against a central difference.
      const double h = overlap * 1e-5;
      const double slope = (hertz.force_kN(overlap + h, 0.0) - hertz.force_kN(overlap - h, 0.0)) / (2 * h);
      BOOST_TEST(hertz.slopes(overlap, 0.0).per_overlap_kN_per_m == slope, tt::tolerance(1e-8));
    }
  }
}

namespace {

/// Building A: one free slab (T = 10⁴ s) on [−10, 0] × [0, 10]; building B: two free slabs
/// (m_lower, m_upper) on [gap, gap + 10] × [0, 10], storeys of 3 m. B's column point (gap, 5),
/// in line with every CM, at ξ up B's storey 2 (between its floors) or storey 1 (ground to
/// floor 1) strikes A's right face head on: no lever arms, so W = 1/m_A + N₁²/m_lower + N₂²/m_upper.
struct SlabAgainstColumn {
  static constexpr double gap = 0.02, v0 = 0.4, m_a = 120.0, m_lower = 150.0, m_upper = 250.0;
  int storey;
  double xi;
  dynamics::CoupledSystem system;

  SlabAgainstColumn(int struck_storey, double height_ratio, double flexibility)
      : storey(struck_storey), xi(height_ratio), system(make(struck_storey, height_ratio, flexibility)) {}

  static dynamics::CoupledSystem make(int storey, double xi, double flexibility) {
    const model::Polygon left = box(-10, 0, 0, 10), right = box(gap, 0, gap + 10, 10);
    model::BuildingDefinition b;
    b.name = "B";
    b.storeys = 2;
    b.storey_height_m = {3.0, 3.0};
    b.slab = right;
    b.centre_of_mass = right.centroid();
    b.mass_t = {m_lower, m_upper};
    b.polar_moment_tm2 = {model::uniform_polar_moment(right, m_lower), model::uniform_polar_moment(right, m_upper)};
    const double kx = m_lower * std::pow(2 * kPi / 1e4, 2);
    b.storey_stiffness.assign(2, Eigen::Vector3d(kx, 2 * kx, 3 * kx * b.polar_moment_tm2[0] / m_lower).asDiagonal());
    b.damping = {0.0, {1, 3}};
    std::vector<model::Building> buildings{slab_building("A", left, {m_a, 1e4, 0.0}), model::make_building(b)};
    contact::Candidate c{0,       {1, storey}, 3.0 * (storey - 1) + 3.0 * xi, 1, 0, 0, 1, {gap, 5.0}, {0, 0},
                         {0, 10}, {1, 0}};
    c.column = true;
    c.lower_floor = storey - 1;
    c.storey_height_m = 3.0;
    c.height_ratio = xi;
    c.flexibility_m_per_kN = flexibility;
    return dynamics::CoupledSystem(std::move(buildings), excitation::GroundMotion({0.0, 0.2}, {0.0, 0.0}, 0.0), {},
                                   {c});
  }
  double inverse_mass() const {
    const auto [lower, upper] = contact::column_shape(xi);
    return 1 / m_a + (storey > 1 ? lower * lower / m_lower : 0.0) + upper * upper / (storey > 1 ? m_upper : m_lower);
  }
  solvers::RunResult run(contact::ContactLaw law, double stiffness, double e) const {
    solvers::EventOptions options;
    options.restitution = e;
    options.law = law;
    options.contact_stiffness = stiffness;
    options.initial_state = pushed(system, v0);
    return solvers::run_event_driven(system, options, cvode(1e-11, 1e-13), "test");
  }
};

}  // namespace

BOOST_AUTO_TEST_CASE(UndampedSlabAgainstColumnReboundsAfterHalfAPeriod) {
  // One contact of an undamped kelvin spring k in series with the column's f: the gap is an
  // oscillator of ω² = k_s W, k_s = 1/(1/k + f), so it lasts π/ω, rebounds at v₀ (energy kept),
  // takes the impulse 2v₀/W (momentum: A loses what B's floors gain, shared N₁ : N₂) and peaks
  // at v₀ √(k_s/W).
  const double k = 1e5, f = 5e-6, stiffness = 1 / (1 / k + f);
  for (const auto& [storey, xi] : {std::pair{2, 0.3}, std::pair{2, 0.5}, std::pair{1, 0.75}}) {
    const SlabAgainstColumn scene(storey, xi, f);
    const double w = scene.inverse_mass(), omega = std::sqrt(stiffness * w), v0 = SlabAgainstColumn::v0;
    const solvers::RunResult r = scene.run(contact::ContactLaw::kelvin, k, 1.0);
    BOOST_TEST_CONTEXT("storey " << storey << ", xi = " << xi) {
      BOOST_TEST_REQUIRE(r.impacts.size() == 1u);
      const solvers::ImpactRecord& i = r.impacts.front();
      BOOST_TEST(i.level == 0);
      BOOST_TEST(i.column == 1);
      BOOST_TEST(i.t_s == SlabAgainstColumn::gap / v0, tt::tolerance(1e-8));
      BOOST_TEST(i.duration_s == kPi / omega, tt::tolerance(1e-7));
      BOOST_TEST(i.separation_velocity_mps == v0, tt::tolerance(1e-6));
      BOOST_TEST(i.impulse_kNs == 2 * v0 / w, tt::tolerance(1e-6));
      BOOST_TEST(i.peak_force_kN == v0 * std::sqrt(stiffness / w), tt::tolerance(1e-5));
      BOOST_TEST(std::abs(i.energy_lost_kJ) < 1e-6 * 0.5 * v0 * v0 / w);
      const contact::ColumnDemand demand = contact::column_demand(i.peak_force_kN, 3.0, xi);
      BOOST_TEST(i.column_shear_kN == demand.shear_kN, tt::tolerance(1e-12));
      BOOST_TEST(i.column_moment_kNm == demand.moment_kNm, tt::tolerance(1e-12));
    }
  }
}

BOOST_AUTO_TEST_CASE(DampedSlabAgainstColumnReboundsAtTheLawsRestitution) {
  // kelvin with e = 0.5: the closed-form release of a Kelvin–Voigt oscillator of ω² = k_s W.
  const double k = 2e5, f = 3e-6, e = 0.5;
  const SlabAgainstColumn scene(2, 0.4, f);
  const double w = scene.inverse_mass(), omega = std::sqrt(w / (1 / k + f)), v0 = SlabAgainstColumn::v0;
  const contact::KelvinRelease release = contact::kelvin_release(contact::kelvin_damping_ratio(e));
  const solvers::RunResult r = scene.run(contact::ContactLaw::kelvin, k, e);
  BOOST_TEST_REQUIRE(r.impacts.size() == 1u);
  BOOST_TEST(r.impacts[0].duration_s == release.omega_time / omega, tt::tolerance(1e-7));
  BOOST_TEST(r.impacts[0].separation_velocity_mps == release.rebound * v0, tt::tolerance(1e-6));
  // Energy: what the slabs lose is the contact's loss.
  const double lost = 0.5 * (v0 * v0 - std::pow(release.rebound * v0, 2)) / w;
  BOOST_TEST(r.impacts[0].energy_lost_kJ == lost, tt::tolerance(1e-5));
}

BOOST_AUTO_TEST_CASE(AColumnNearACornerStandsOnBothFaces) {
  // The paper's B2 faces B1 with its left edge (x = 0.2) and, below B1's slab, its bottom edge
  // (y = 8). A 0.5 m column inset 0.15 m from the left face and 0.2 m from the bottom one (both
  // within half its section) has a point on each face, (0.2, 8.2) and (0.35, 8); one centred on
  // the corner has the corner once; one on the top edge faces nothing.
  model::BuildingDefinition b2;
  b2.slab = model::Polygon({{0.2, 8}, {28.2, 8}, {28.2, 33}, {0.2, 33}});
  b2.columns = {{{0.35, 8.2}, 0.5, 0.5}, {{0.2, 8.0}, 0.5, 0.5}, {{14.2, 33.0}, 0.5, 0.5}};
  const model::Polygon b1({{-24, 0}, {0, 0}, {0, 20}, {-24, 20}});
  const std::vector<contact::FacadeColumn> facade = contact::facade_columns(b2, b1);
  BOOST_TEST_REQUIRE(facade.size() == 3u);
  const auto has = [&](std::size_t column, double x, double y) {
    return std::any_of(facade.begin(), facade.end(), [&](const contact::FacadeColumn& f) {
      return f.column == column && (f.point - Point2(x, y)).norm() < 1e-12;
    });
  };
  BOOST_TEST(has(0, 0.2, 8.2));
  BOOST_TEST(has(0, 0.35, 8.0));
  BOOST_TEST(has(1, 0.2, 8.0));
}
