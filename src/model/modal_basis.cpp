#include "pounding/model/modal_basis.hpp"

#include <stdexcept>

#include "pounding/model/modal.hpp"

namespace pounding::model {

ModalBasis modal_basis(const Building& building, const Eigen::Ref<const Eigen::VectorXd>& influence) {
  const std::vector<Mode> modes = modal_analysis(building);
  const auto n = static_cast<Eigen::Index>(modes.size());
  ModalBasis basis;
  basis.omega_rad_s.resize(n);
  basis.shapes.resize(n, n);
  for (Eigen::Index k = 0; k < n; ++k) {
    basis.omega_rad_s[k] = modes[static_cast<std::size_t>(k)].omega_rad_s;
    basis.shapes.col(k) = modes[static_cast<std::size_t>(k)].shape;
  }
  basis.projection = basis.shapes.transpose() * building.mass_diagonal.asDiagonal();
  basis.participation = basis.projection * influence;
  // ζ from the Rayleigh coefficients themselves (exact for the model as defined); Φᵀ C Φ only
  // checks that C is what they say and that the modes decouple it, rather than drop its
  // coupling terms silently.
  basis.damping_ratio = building.rayleigh.a0_per_s / 2.0 * basis.omega_rad_s.cwiseInverse() +
                        building.rayleigh.a1_s / 2.0 * basis.omega_rad_s;
  const Eigen::MatrixXd modal_damping = basis.shapes.transpose() * building.damping * basis.shapes;
  const Eigen::VectorXd expected = 2.0 * basis.damping_ratio.cwiseProduct(basis.omega_rad_s);
  const Eigen::MatrixXd departure = modal_damping - Eigen::MatrixXd(expected.asDiagonal());
  if (departure.cwiseAbs().maxCoeff() > kClassicalDampingTolerance * expected.cwiseAbs().maxCoeff()) {
    throw std::runtime_error("modal basis of " + building.definition.name +
                             ": the damping is not the classical a0 M + a1 K the modes decouple");
  }
  return basis;
}

}  // namespace pounding::model
