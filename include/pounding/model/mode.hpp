#pragma once
// One undamped mode of a building (model::modal_analysis computes them): its own header so that
// model::Building can keep its modes.

#include <Eigen/Core>
#include <string_view>

namespace pounding::model {

enum class ModeComponent { x, y, torsion };
std::string_view to_string(ModeComponent component);

struct Mode {
  double omega_rad_s = 0.0;
  double period_s = 0.0;
  Eigen::VectorXd shape;                      // mass-normalised: φᵀ M φ = 1
  ModeComponent dominant = ModeComponent::x;  // largest share of φᵀ M φ among u, v, φ DOFs
  // Effective modal mass as a fraction of the total: (φᵀ M r)² / Σ M_rr for r along x, y, rz.
  double effective_mass_ratio_x = 0.0;
  double effective_mass_ratio_y = 0.0;
  double effective_mass_ratio_rz = 0.0;
};

}  // namespace pounding::model
