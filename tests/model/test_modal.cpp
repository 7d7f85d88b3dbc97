#include <boost/test/unit_test.hpp>

#include "../support/fixtures.hpp"
#include "pounding/model/modal.hpp"

namespace tt = boost::test_tools;
using namespace pounding::model;

BOOST_AUTO_TEST_CASE(ModesAreMassNormalisedAndSolveTheEigenproblem) {
  const Building building = make_building(pounding::testing::square_building(3, 10.0, 200.0, 3000.0, Point2(1.2, 0.8)));
  const Eigen::MatrixXd mass = building.mass_diagonal.asDiagonal();
  for (const Mode& mode : modal_analysis(building.mass_diagonal, building.stiffness)) {
    BOOST_TEST(mode.shape.dot(mass * mode.shape) == 1.0, tt::tolerance(1e-12));
    const Eigen::VectorXd residual =
        building.stiffness * mode.shape - mode.omega_rad_s * mode.omega_rad_s * mass * mode.shape;
    BOOST_TEST(residual.norm() <= 1e-9 * (building.stiffness * mode.shape).norm());
  }
}

BOOST_AUTO_TEST_CASE(EffectiveMassRatiosOfAllModesSumToOne) {
  const Building building =
      make_building(pounding::testing::square_building(4, 10.0, 200.0, 3000.0, Point2(-1.0, 2.0)));
  double x = 0, y = 0, rz = 0;
  for (const Mode& mode : modal_analysis(building.mass_diagonal, building.stiffness)) {
    x += mode.effective_mass_ratio_x;
    y += mode.effective_mass_ratio_y;
    rz += mode.effective_mass_ratio_rz;
  }
  BOOST_TEST(x == 1.0, tt::tolerance(1e-10));
  BOOST_TEST(y == 1.0, tt::tolerance(1e-10));
  BOOST_TEST(rz == 1.0, tt::tolerance(1e-10));
}

BOOST_AUTO_TEST_CASE(PeriodsComeLongestFirst) {
  const Building building = make_building(pounding::testing::square_building(5, 10.0, 200.0, 3000.0, Point2(1.0, 1.0)));
  const auto modes = modal_analysis(building.mass_diagonal, building.stiffness);
  for (std::size_t k = 1; k < modes.size(); ++k) BOOST_TEST(modes[k].period_s <= modes[k - 1].period_s);
}
