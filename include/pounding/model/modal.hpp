#pragma once
// Undamped modes of one building: K φ = ω² M φ with M diagonal.

#include <Eigen/Core>
#include <string_view>
#include <vector>

#include "pounding/model/building.hpp"

namespace pounding::model {

enum class ModeComponent { x, y, torsion };
std::string_view to_string(ModeComponent component);

struct Mode {
  double omega_rad_s = 0.0;
  double period_s = 0.0;
  Eigen::VectorXd shape;      // mass-normalised: φᵀ M φ = 1
  ModeComponent dominant = ModeComponent::x;  // largest share of φᵀ M φ among u, v, φ DOFs
  // Effective modal mass as a fraction of the total: (φᵀ M r)² / Σ M_rr for r along x, y, rz.
  double effective_mass_ratio_x = 0.0;
  double effective_mass_ratio_y = 0.0;
  double effective_mass_ratio_rz = 0.0;
};

/// All 3N modes, longest period first. @pre mass_diagonal > 0, stiffness SPD.
/// @throws std::runtime_error if the eigensolver fails.
std::vector<Mode> modal_analysis(const Eigen::VectorXd& mass_diagonal,
                                 const Eigen::MatrixXd& stiffness);

inline std::vector<Mode> modal_analysis(const Building& building) {
  return modal_analysis(building.mass_diagonal, building.stiffness);
}

}  // namespace pounding::model
