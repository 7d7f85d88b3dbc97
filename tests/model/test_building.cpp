#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>
#include <numbers>

#include "../support/fixtures.hpp"
#include "pounding/input_error.hpp"
#include "pounding/model/building.hpp"
#include "pounding/model/modal.hpp"

namespace tt = boost::test_tools;
using namespace pounding::model;
using pounding::testing::square_building;

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// Column stiffnesses of a 0.3 (x) × 0.5 (y) column, by the textbook formula 12 E I / H³.
struct RectangularColumn {
  double b = 0.3, h = 0.5, E = 3.0e7, H = 3.0;
  double kx() const { return 12 * E * (h * b * b * b / 12) / (H * H * H); }
  double ky() const { return 12 * E * (b * h * h * h / 12) / (H * H * H); }
};

BuildingDefinition one_storey_rectangular_columns(Point2 cm) {
  BuildingDefinition b = square_building(1, 10.0, 100.0, 1000.0, cm);
  for (Column& column : b.columns) {
    column.b_m = 0.3;
    column.h_m = 0.5;
  }
  return b;
}

/// Share of the mode's φᵀMφ carried by component c (0 = u, 1 = v, 2 = φ).
double component_share(const Mode& mode, const Eigen::VectorXd& mass, int c) {
  double share = 0, total = 0;
  for (Eigen::Index d = 0; d < mode.shape.size(); ++d) {
    const double energy = mass[d] * mode.shape[d] * mode.shape[d];
    total += energy;
    if (d % 3 == c) share += energy;
  }
  return share / total;
}

}  // namespace

BOOST_AUTO_TEST_CASE(ColumnStiffnessFollowsTwelveEIOverHCubed) {
  const RectangularColumn c;
  const Eigen::Vector2d k = column_stiffness({Point2::Zero(), c.b, c.h}, c.E, c.H, 0.5);
  BOOST_TEST(k.x() == 0.5 * c.kx(), tt::tolerance(1e-14));
  BOOST_TEST(k.y() == 0.5 * c.ky(), tt::tolerance(1e-14));
}

BOOST_AUTO_TEST_CASE(OneStoreySymmetricBuildingHasPeriodTwoPiSqrtMOverK) {
  const Building building = make_building(one_storey_rectangular_columns(Point2::Zero()));
  const RectangularColumn c;
  const double kx = 4 * c.kx(), ky = 4 * c.ky();
  const double k_theta = 4 * (c.kx() * 25 + c.ky() * 25);  // Σ kx y² + ky x², corners at ±5 m
  const std::vector<Mode>& modes = building.modes;
  // Expected periods, longest first: x (soft direction), then torsion or y.
  std::vector<double> expected = {kTwoPi * std::sqrt(100 / kx), kTwoPi * std::sqrt(100 / ky),
                                  kTwoPi * std::sqrt(1000 / k_theta)};
  std::sort(expected.rbegin(), expected.rend());
  for (int k = 0; k < 3; ++k) BOOST_TEST(modes[k].period_s == expected[k], tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(SymmetricPlanHasUncoupledXYAndTorsionModes) {
  const Building building = make_building(one_storey_rectangular_columns(Point2::Zero()));
  for (const Mode& mode : building.modes) {
    const int c = static_cast<int>(mode.dominant);
    BOOST_TEST(component_share(mode, building.mass_diagonal, c) == 1.0, tt::tolerance(1e-12));
  }
}

BOOST_AUTO_TEST_CASE(OneStoreyEccentricMassMatchesClosedForm) {
  // Columns symmetric about the origin, CM at (e, 0). About the CM the storey stiffness is
  // [[Kx, 0, 0], [0, Ky, −e Ky], [0, −e Ky, Kθ,S + e² Ky]], so u stays uncoupled (ω² = Kx/m)
  // and v–φ satisfy m J ω⁴ − (m (Kθ,S + e² Ky) + J Ky) ω² + Ky Kθ,S = 0.
  const double e = 1.5, m = 100.0, J = 1000.0;
  const Building building = make_building(one_storey_rectangular_columns(Point2(e, 0.0)));
  const RectangularColumn c;
  const double kx = 4 * c.kx(), ky = 4 * c.ky(), k_theta_s = 4 * (c.kx() * 25 + c.ky() * 25);

  const double p = m * (k_theta_s + e * e * ky) + J * ky;
  const double disc = std::sqrt(p * p - 4 * m * J * ky * k_theta_s);
  std::vector<double> expected = {kTwoPi / std::sqrt(kx / m), kTwoPi / std::sqrt((p - disc) / (2 * m * J)),
                                  kTwoPi / std::sqrt((p + disc) / (2 * m * J))};
  std::sort(expected.rbegin(), expected.rend());
  const std::vector<Mode>& modes = building.modes;
  for (int k = 0; k < 3; ++k) BOOST_TEST(modes[k].period_s == expected[k], tt::tolerance(1e-12));

  // The coupled modes move both v and φ; the x mode moves u only.
  int coupled = 0;
  for (const Mode& mode : modes) {
    const double v_share = component_share(mode, building.mass_diagonal, 1);
    if (v_share > 1e-9 && v_share < 1 - 1e-9) ++coupled;
  }
  BOOST_TEST(coupled == 2);
}

BOOST_AUTO_TEST_CASE(TwoStoreyShearBuildingMatchesClosedFormFrequencies) {
  // Storey matrices given directly, uncoupled directions; x: k1 = 2000, k2 = 1500 kN/m,
  // m1 = 10 t, m2 = 8 t. m1 m2 ω⁴ − (m1 k2 + m2 (k1 + k2)) ω² + k1 k2 = 0.
  BuildingDefinition b = square_building(2, 10.0, 10.0, 100.0);
  b.mass_t = {10.0, 8.0};
  b.polar_moment_tm2 = {100.0, 80.0};
  b.columns.clear();
  b.storey_stiffness = {Eigen::Vector3d(2000, 9000, 5e5).asDiagonal(), Eigen::Vector3d(1500, 7000, 4e5).asDiagonal()};
  const Building building = make_building(b);

  const double m1 = 10, m2 = 8, k1 = 2000, k2 = 1500;
  const double p = m1 * k2 + m2 * (k1 + k2);
  const double disc = std::sqrt(p * p - 4 * m1 * m2 * k1 * k2);
  const double omega_low = std::sqrt((p - disc) / (2 * m1 * m2));
  const double omega_high = std::sqrt((p + disc) / (2 * m1 * m2));

  std::vector<double> x_omegas;
  for (const Mode& mode : building.modes) {
    if (mode.dominant == ModeComponent::x) x_omegas.push_back(mode.omega_rad_s);
  }
  BOOST_TEST_REQUIRE(x_omegas.size() == 2u);
  BOOST_TEST(x_omegas[0] == omega_low, tt::tolerance(1e-12));
  BOOST_TEST(x_omegas[1] == omega_high, tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(RayleighCoefficientsReproduceTheRatioAtBothChosenModes) {
  BuildingDefinition b = square_building(4, 12.0, 300.0, 7200.0, Point2(1.0, -0.5));
  b.damping = {0.05, {1, 3}};
  const Building building = make_building(b);
  const std::vector<Mode>& modes = building.modes;
  // Independent check through the assembled C: ζ_n = φₙᵀ C φₙ / (2 ωₙ) for mass-normalised φ.
  auto modal_ratio = [&](int n) {
    const Mode& mode = modes[n - 1];
    return mode.shape.dot(building.damping * mode.shape) / (2 * mode.omega_rad_s);
  };
  BOOST_TEST(modal_ratio(1) == 0.05, tt::tolerance(1e-10));
  BOOST_TEST(modal_ratio(3) == 0.05, tt::tolerance(1e-10));
  BOOST_TEST(modal_ratio(2) < 0.05);  // between the anchors Rayleigh damping dips
  BOOST_TEST(modal_ratio(6) > 0.05);  // and above them it grows
}

BOOST_AUTO_TEST_CASE(FrameFactorIsSolvedForTheTargetPeriod) {
  BuildingDefinition b = square_building(5, 15.0, 400.0, 15000.0, Point2(1.0, 0.5));
  b.target_period_s = 0.8;
  const Building building = make_building(b);
  BOOST_TEST(modal_analysis(building.mass_diagonal, building.stiffness).front().period_s == 0.8, tt::tolerance(1e-10));

  BuildingDefinition unit = b;
  unit.target_period_s.reset();
  const double period_unit = make_building(unit).modes.front().period_s;
  BOOST_TEST(building.frame_factor == std::pow(period_unit / 0.8, 2), tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(UniformPolarMomentOfRectangleIsMassTimesDiagonalSquaredOverTwelve) {
  const Polygon slab({{-24, 0}, {0, 0}, {0, 20}, {-24, 20}});
  BOOST_TEST(uniform_polar_moment(slab, 555.0) == 555.0 * (24.0 * 24 + 20 * 20) / 12, tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(ColumnsAtOnePointCannotResistTorsion) {
  // Two columns on one line still resist torsion by the couple of their x forces; a single column
  // (columns all at one point) does not.
  BuildingDefinition b = square_building(1, 10.0, 100.0, 1000.0);
  b.columns = {{Point2(0, -5), 0.4, 0.4}, {Point2(0, 5), 0.4, 0.4}};
  BOOST_CHECK_NO_THROW(make_building(b));
  b.columns = {{Point2(0, 0), 0.4, 0.4}};
  BOOST_CHECK_EXCEPTION(make_building(b), pounding::InputError, [](const pounding::InputError& e) {
    return e.key() == "columns" && std::string(e.what()).find("singular") != std::string::npos;
  });
  // A near repeat is found even when another column shares the first one's x (sorted by x alone,
  // (0, 5) stands between them).
  b.columns = {{Point2(0, -5), 0.4, 0.4}, {Point2(0, 5), 0.4, 0.4}, {Point2(1e-9, -5), 0.4, 0.4}};
  BOOST_CHECK_EXCEPTION(make_building(b), pounding::InputError, [](const pounding::InputError& e) {
    return e.key() == "columns[3]" && std::string(e.what()).find("stands where columns[1] stands") != std::string::npos;
  });
  // Two at one point are one column given twice (its stiffness counted twice): refused as such.
  b.columns = {{Point2(0, 0), 0.4, 0.4}, {Point2(0, 0), 0.5, 0.5}};
  BOOST_CHECK_EXCEPTION(make_building(b), pounding::InputError, [](const pounding::InputError& e) {
    return e.key() == "columns[2]" && std::string(e.what()).find("stands where columns[1] stands") != std::string::npos;
  });
}

BOOST_AUTO_TEST_CASE(EqualStoreyHeightsGiveTheStiffnessOfOneRepeatedStorey) {
  // The per-storey assembly must reduce to the uniform one: every storey the same 12 E I / H³.
  const BuildingDefinition b = square_building(4, 12.0, 300.0, 7200.0, Point2(1.0, -0.5));
  const Eigen::Matrix3d storey = storey_stiffness_from_columns(b.columns, b.centre_of_mass, b.E_kPa, 3.0, 1.0);
  const Eigen::MatrixXd uniform = assemble_stiffness(std::vector<Eigen::Matrix3d>(4, storey));
  const Eigen::MatrixXd k = make_building(b).stiffness;
  BOOST_TEST((k - uniform).cwiseAbs().maxCoeff() <= 1e-12 * uniform.cwiseAbs().maxCoeff());
}

BOOST_AUTO_TEST_CASE(EachStoreyStiffnessUsesItsOwnHeight) {
  // Two storeys, H = 4.5 m (ground) and 3 m, four 0.4 × 0.4 columns at (±5, ±5), CM at the
  // centre: per storey k = 4 · 12 E (b⁴/12) / H³ along x and y, and Σ k_c (x² + y²) = 50 k in
  // torsion, uncoupled. Assembled by hand: K = [[k1 + k2, −k2], [−k2, k2]] per direction.
  BuildingDefinition b = square_building(2, 10.0, 100.0, 1000.0);
  b.storey_height_m = {4.5, 3.0};
  const double e = b.E_kPa, side = 0.4;
  auto lateral = [&](double height) { return 4 * 12 * e * std::pow(side, 4) / 12 / std::pow(height, 3); };
  const double k1 = lateral(4.5), k2 = lateral(3.0);
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(6, 6);
  for (int d = 0; d < 3; ++d) {
    const double scale = d == 2 ? 50.0 : 1.0;  // torsion: lever arm² = 25 + 25 m² per column
    expected(d, d) = scale * (k1 + k2);
    expected(d, 3 + d) = expected(3 + d, d) = -scale * k2;
    expected(3 + d, 3 + d) = scale * k2;
  }
  const Eigen::MatrixXd k = make_building(b).stiffness;
  BOOST_TEST((k - expected).cwiseAbs().maxCoeff() <= 1e-12 * expected.cwiseAbs().maxCoeff());
  BOOST_TEST(k(0, 0) != 2 * k(3, 3));  // fails if both storeys took one height
}

BOOST_AUTO_TEST_CASE(BuildingKeepsTheModesOfItsFinalStiffness) {
  // With a target period make_building solves the modes of K at f = 1 first: the kept ones must
  // be those of the K it returns (the same decomposition, bit for bit, in the same order).
  BuildingDefinition b = square_building(5, 15.0, 400.0, 15000.0, Point2(1.0, 0.5));
  b.target_period_s = 0.8;
  const Building building = make_building(b);
  const std::vector<Mode> expected = modal_analysis(building.mass_diagonal, building.stiffness);
  BOOST_TEST_REQUIRE(building.modes.size() == expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) {
    BOOST_TEST(building.modes[k].omega_rad_s == expected[k].omega_rad_s);
    BOOST_TEST(building.modes[k].period_s == expected[k].period_s);
    BOOST_TEST((building.modes[k].shape.array() == expected[k].shape.array()).all());
    BOOST_TEST((building.modes[k].dominant == expected[k].dominant));
    BOOST_TEST(building.modes[k].effective_mass_ratio_x == expected[k].effective_mass_ratio_x);
  }
}

BOOST_AUTO_TEST_CASE(FrameFactorIsSolvedForTheTargetPeriodWithUnequalStoreys) {
  // K stays linear in f when each storey has its own height, so the closed-form solve holds.
  BuildingDefinition b = square_building(5, 15.0, 400.0, 15000.0, Point2(1.0, 0.5));
  b.storey_height_m = {4.5, 3.0, 3.0, 3.2, 3.0};
  b.target_period_s = 0.8;
  const Building building = make_building(b);
  BOOST_TEST(modal_analysis(building.mass_diagonal, building.stiffness).front().period_s == 0.8, tt::tolerance(1e-10));
}

BOOST_AUTO_TEST_CASE(FloorElevationsAreSumsOfStoreyHeights) {
  BuildingDefinition b = square_building(3, 10.0, 100.0, 1000.0);
  b.storey_height_m = {4.5, 3.0, 3.25};
  const std::vector<double> z = floor_elevations(b);
  BOOST_TEST_REQUIRE(z.size() == 3u);
  BOOST_TEST(z[0] == 4.5);
  BOOST_TEST(z[1] == 7.5);
  BOOST_TEST(z[2] == 10.75);
}

BOOST_AUTO_TEST_CASE(StoreyHeightsAreValidatedOneByOne) {
  BuildingDefinition b = square_building(3, 10.0, 100.0, 1000.0);
  b.storey_height_m = {4.5, 3.0};
  BOOST_CHECK_EXCEPTION(b.validate(), pounding::InputError, [](const pounding::InputError& e) {
    return e.key() == "storey_height_m" && e.value() == "2 values" &&
           e.reason().find("one value per storey (3)") != std::string::npos;
  });
  b.storey_height_m = {4.5, 3.0, -3.0};
  BOOST_CHECK_EXCEPTION(b.validate(), pounding::InputError, [](const pounding::InputError& e) {
    return e.key() == "storey_height_m[3]" && e.value() == "-3" && e.reason() == "must lie in [1, 20] m";
  });
  b.storey_height_m = {4.5, std::numeric_limits<double>::infinity(), 3.0};
  BOOST_CHECK_EXCEPTION(b.validate(), pounding::InputError, [](const pounding::InputError& e) {
    return e.key() == "storey_height_m[2]" && e.value() == "inf" && e.reason() == "must lie in [1, 20] m";
  });
}

BOOST_AUTO_TEST_CASE(SlabAxialStiffnessIsETimesTheSectionOverTheLength) {
  BuildingDefinition b = square_building(1, 10.0, 100.0, 1000.0);
  b.slab_thickness_m = 2.5;
  BOOST_CHECK_EXCEPTION(b.validate(), pounding::InputError, [](const pounding::InputError& e) {
    return std::string(e.what()).find("slab_thickness_m") != std::string::npos;
  });
  b.slab_thickness_m = 0.2;
  b.validate();
  b.slab = Polygon({{0.0, 0.0}, {16.0, 0.0}, {16.0, 10.0}, {0.0, 10.0}});
  const double e_kPa = b.E_kPa;
  // Along x: the section across is 10 m wide, the length 16 m; along y the other way round.
  BOOST_TEST(slab_axial_stiffness_kN_per_m(b, Point2(1.0, 0.0)) == e_kPa * 0.2 * 10.0 / 16.0, tt::tolerance(1e-14));
  BOOST_TEST(slab_axial_stiffness_kN_per_m(b, Point2(0.0, -1.0)) == e_kPa * 0.2 * 16.0 / 10.0, tt::tolerance(1e-14));
  // Along (0.6, 0.8): the outline's extents, 16·0.8 + 10·0.6 = 18.8 m across and 16·0.6 + 10·0.8 = 17.6 m along.
  BOOST_TEST(slab_axial_stiffness_kN_per_m(b, Point2(0.6, 0.8)) == e_kPa * 0.2 * 18.8 / 17.6, tt::tolerance(1e-14));
}
