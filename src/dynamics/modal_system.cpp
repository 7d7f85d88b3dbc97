#include "pounding/dynamics/modal_system.hpp"

#include <set>
#include <stdexcept>
#include <vector>

#include "pounding/model/mode.hpp"

namespace pounding::dynamics {
namespace {

// Off-diagonal terms of Φᵀ C Φ above this fraction of its largest entry mean the building is not
// classically damped; Rayleigh damping leaves round-off (≈1e-15).
constexpr double kClassicalDampingTolerance = 1e-9;

}  // namespace

ModalSystem::ModalSystem(const CoupledSystem& system) : system_(system) {
  const int n = system.dof();
  omega_rad_s_.resize(n);
  damping_per_s_.resize(n);
  participation_.resize(n, system.ground_motion().component_count());
  shape_full_ = MatrixXd::Zero(n, n);
  inverse_full_ = MatrixXd::Zero(n, n);
  shapes_.resize(static_cast<std::size_t>(system.building_count()));
  inverse_.resize(shapes_.size());
  for (int b = 0; b < system_.building_count(); ++b) {
    const model::Building& building = system.building(b);
    const int offset = system.floor_index(b, 1), size = building.dof();
    const std::vector<model::Mode>& modes = building.modes;
    MatrixXd& shapes = shapes_[b];
    shapes.resize(size, size);
    for (int i = 0; i < size; ++i) {
      shapes.col(i) = modes[i].shape;
      omega_rad_s_[offset + i] = modes[i].omega_rad_s;
    }
    inverse_[b] = shapes.transpose() * building.mass_diagonal.asDiagonal();
    const MatrixXd modal_damping = shapes.transpose() * building.damping * shapes;
    const double largest = modal_damping.cwiseAbs().maxCoeff();
    const MatrixXd off_diagonal = modal_damping - MatrixXd(modal_damping.diagonal().asDiagonal());
    if (off_diagonal.cwiseAbs().maxCoeff() > kClassicalDampingTolerance * largest) {
      throw std::invalid_argument("modal form: building " + std::to_string(b + 1) + " is not classically damped");
    }
    damping_per_s_.segment(offset, size) = modal_damping.diagonal();
    for (int c = 0; c < participation_.cols(); ++c) {
      participation_.col(c).segment(offset, size) = inverse_[b] * system.influence(c).segment(offset, size);
    }
    shape_full_.block(offset, offset, size, size) = shapes;
    inverse_full_.block(offset, offset, size, size) = inverse_[b];
  }
}

void ModalSystem::rhs(double t, ConstVectorRef z, Eigen::Ref<VectorXd> z_dot) const {
  const int n = dof();
  const excitation::GroundMotion& motion = system_.ground_motion();
  z_dot.head(n) = z.tail(n);
  z_dot.tail(n) = -(omega_rad_s_.array().square() * z.head(n).array() + damping_per_s_.array() * z.tail(n).array() +
                    participation_.col(0).array() * motion.accel_at(t));
  if (motion.is_pair()) z_dot.tail(n) -= participation_.col(1) * motion.accel_at(t, 1);
}

void ModalSystem::jacobian(Eigen::Ref<MatrixXd> jacobian) const {
  const int n = dof();
  jacobian.setZero();
  jacobian.topRightCorner(n, n).diagonal().setOnes();
  jacobian.bottomLeftCorner(n, n).diagonal() = -omega_rad_s_.cwiseAbs2();
  jacobian.bottomRightCorner(n, n).diagonal() = -damping_per_s_;
}

void ModalSystem::to_physical(ConstVectorRef z, Eigen::Ref<VectorXd> y) const {
  // Two products per building rather than one with two columns: Eigen's matrix-matrix kernel
  // packs Φ at every call, 2-3 times slower here (measured, 21 to 180 modes).
  const int n = dof();
  for (int b = 0; b < system_.building_count(); ++b) {
    const Eigen::Index offset = system_.floor_index(b, 1), size = shapes_[b].rows();
    y.segment(offset, size).noalias() = shapes_[b] * z.segment(offset, size);
    y.segment(n + offset, size).noalias() = shapes_[b] * z.segment(n + offset, size);
  }
}

void ModalSystem::to_modal(ConstVectorRef y, Eigen::Ref<VectorXd> z) const {
  const int n = dof();
  for (int b = 0; b < system_.building_count(); ++b) {
    const Eigen::Index offset = system_.floor_index(b, 1), size = inverse_[b].rows();
    z.segment(offset, size).noalias() = inverse_[b] * y.segment(offset, size);
    z.segment(n + offset, size).noalias() = inverse_[b] * y.segment(n + offset, size);
  }
}

void ModalSystem::jacobian_to_modal(const MatrixXd& physical, Eigen::Ref<MatrixXd> modal) const {
  // T⁻¹ J T = T⁻¹ A T + T⁻¹ (J − A) T with T⁻¹ A T = jacobian(). A contact force changes only
  // the accelerations of its floors (M⁻¹Gᵀ λ), so J − A has few nonzero rows R:
  // Φ⁻¹ D Φ = Φ⁻¹[:, R] (D[R, :] Φ) costs |R| n² instead of n³.
  const int n = dof();
  jacobian(modal);
  const MatrixXd& free = system_.jacobian();
  for (int row = 0; row < 2; ++row) {
    for (int col = 0; col < 2; ++col) {
      const MatrixXd change = physical.block(row * n, col * n, n, n) - free.block(row * n, col * n, n, n);
      std::vector<Eigen::Index> rows;
      for (Eigen::Index r = 0; r < n; ++r) {
        if (!change.row(r).isZero(0.0)) rows.push_back(r);
      }
      if (rows.empty()) continue;
      const MatrixXd moved = change(rows, Eigen::all) * shape_full_;  // D[R, :] Φ
      modal.block(row * n, col * n, n, n).noalias() += inverse_full_(Eigen::all, rows) * moved;
    }
  }
}

VectorXd ModalSystem::atol(const VectorXd& physical_atol) const {
  const int n = dof();
  VectorXd result(state_size());
  for (int b = 0; b < system_.building_count(); ++b) {
    std::set<int> floors;
    const VectorXd rest = VectorXd::Zero(system_.state_size());
    for (std::size_t i = 0; i < system_.candidates().size(); ++i) {
      for (const auto& block : system_.row_blocks(system_.candidates()[i], system_.gap(rest, i))) {
        if (block.building == b) floors.insert(block.floor);
      }
    }
    if (floors.empty()) {
      for (int floor = 1; floor <= system_.building(b).storeys(); ++floor) floors.insert(floor);
    }
    const int offset = system_.floor_index(b, 1);
    double largest = 0.0;  // max_j ‖Φ_j‖₂ / a_j
    for (int floor : floors) {
      for (int k = 0; k < 3; ++k) {
        const int j = system_.floor_index(b, floor) + k;
        largest = std::max(largest, shapes_[b].row(j - offset).norm() / physical_atol[j]);
      }
    }
    const Eigen::Index size = shapes_[b].rows();
    result.segment(offset, size).setConstant(1.0 / largest);
    result.segment(n + offset, size) = omega_rad_s_.segment(offset, size) / largest;
  }
  return result;
}

}  // namespace pounding::dynamics
