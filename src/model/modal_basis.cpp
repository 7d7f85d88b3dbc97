#include "pounding/model/modal_basis.hpp"

#include <numbers>
#include <stdexcept>

namespace pounding::model {

ModalBasis modal_basis(const Building& building, const Eigen::Ref<const Eigen::MatrixXd>& influence) {
  const std::vector<Mode>& modes = building.modes;
  const auto n = static_cast<Eigen::Index>(modes.size());
  ModalBasis basis;
  basis.omega_rad_s.resize(n);
  basis.shapes.resize(n, n);
  for (Eigen::Index k = 0; k < n; ++k) {
    basis.omega_rad_s[k] = modes[static_cast<std::size_t>(k)].omega_rad_s;
    basis.shapes.col(k) = modes[static_cast<std::size_t>(k)].shape;
  }
  basis.projection = basis.shapes.transpose() * building.mass_diagonal.asDiagonal();
  // Column by column: a matrix-vector product each, as for one component.
  basis.participation.resize(n, influence.cols());
  for (Eigen::Index c = 0; c < influence.cols(); ++c) basis.participation.col(c) = basis.projection * influence.col(c);
  basis.dropped_static_s2 = Eigen::MatrixXd::Zero(n, influence.cols());
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

ModalBasis keep_modes_below(const ModalBasis& full, double cutoff_hz) {
  if (cutoff_hz == 0.0) return full;
  Eigen::Index kept = 0;  // ascending ω: the kept modes are the first ones
  while (kept < full.size() && full.omega_rad_s[kept] / (2.0 * std::numbers::pi) < cutoff_hz) ++kept;
  ModalBasis basis;
  basis.omega_rad_s = full.omega_rad_s.head(kept);
  basis.damping_ratio = full.damping_ratio.head(kept);
  basis.shapes = full.shapes.leftCols(kept);
  basis.projection = full.projection.topRows(kept);
  basis.participation = full.participation.topRows(kept);
  const Eigen::Index dropped = full.size() - kept;
  // η_s = −Γ a_g / ω² solves each dropped oscillator with η̈ and η̇ neglected.
  basis.dropped_static_s2.resize(full.shapes.rows(), full.participation.cols());
  for (Eigen::Index c = 0; c < full.participation.cols(); ++c) {
    basis.dropped_static_s2.col(c) =
        -full.shapes.rightCols(dropped) *
        (full.participation.col(c).tail(dropped).array() / full.omega_rad_s.tail(dropped).array().square()).matrix();
  }
  return basis;
}

}  // namespace pounding::model
