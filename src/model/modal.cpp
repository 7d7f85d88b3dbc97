#include "pounding/model/modal.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace pounding::model {

std::string_view to_string(ModeComponent component) {
  switch (component) {
    case ModeComponent::x: return "x";
    case ModeComponent::y: return "y";
    case ModeComponent::torsion: return "torsion";
  }
  return "?";
}

std::vector<Mode> modal_analysis(const Eigen::VectorXd& mass_diagonal, const Eigen::MatrixXd& stiffness) {
  // With M diagonal, K φ = ω² M φ becomes the standard symmetric problem
  // (M^-½ K M^-½) ψ = ω² ψ with φ = M^-½ ψ, which is mass-normalised when ψ is unit.
  const Eigen::VectorXd inv_sqrt_mass = mass_diagonal.cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd scaled = inv_sqrt_mass.asDiagonal() * stiffness * inv_sqrt_mass.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(scaled);
  if (solver.info() != Eigen::Success) throw std::runtime_error("modal analysis: eigensolver failed");

  const Eigen::Index n = mass_diagonal.size();
  Eigen::Vector3d total_mass = Eigen::Vector3d::Zero();  // Σ m (x), Σ m (y), Σ J (rz)
  for (Eigen::Index dof = 0; dof < n; ++dof) total_mass[dof % 3] += mass_diagonal[dof];

  std::vector<Mode> modes;
  modes.reserve(n);
  for (Eigen::Index k = 0; k < n; ++k) {  // eigenvalues come ascending: longest period first
    Mode mode;
    const double omega_squared = solver.eigenvalues()[k];
    mode.omega_rad_s = std::sqrt(std::max(omega_squared, 0.0));
    mode.period_s = 2.0 * std::numbers::pi / mode.omega_rad_s;
    mode.shape = inv_sqrt_mass.asDiagonal() * solver.eigenvectors().col(k);

    Eigen::Vector3d participation = Eigen::Vector3d::Zero();  // φᵀ M r per direction
    Eigen::Vector3d kinetic_share = Eigen::Vector3d::Zero();  // Σ M_dd φ_d² per component
    for (Eigen::Index dof = 0; dof < n; ++dof) {
      participation[dof % 3] += mass_diagonal[dof] * mode.shape[dof];
      kinetic_share[dof % 3] += mass_diagonal[dof] * mode.shape[dof] * mode.shape[dof];
    }
    Eigen::Index largest = 0;
    kinetic_share.maxCoeff(&largest);
    mode.dominant = static_cast<ModeComponent>(largest);
    const Eigen::Vector3d ratio = participation.cwiseAbs2().cwiseQuotient(total_mass);
    mode.effective_mass_ratio_x = ratio[0];
    mode.effective_mass_ratio_y = ratio[1];
    mode.effective_mass_ratio_rz = ratio[2];
    modes.push_back(std::move(mode));
  }
  return modes;
}

}  // namespace pounding::model
