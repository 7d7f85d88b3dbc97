#pragma once
// Undamped modes of one building: K φ = ω² M φ with M diagonal.

#include <Eigen/Core>
#include <vector>

#include "pounding/model/mode.hpp"

namespace pounding::model {

/// All 3N modes, longest period first. A built model::Building keeps its own (Building::modes):
/// read those rather than solve the eigenproblem again. @pre mass_diagonal > 0, stiffness SPD.
/// @throws std::runtime_error if the eigensolver fails.
std::vector<Mode> modal_analysis(const Eigen::VectorXd& mass_diagonal, const Eigen::MatrixXd& stiffness);

}  // namespace pounding::model
