#pragma once
// ARKODE behind the Integrator seam: ERKStep (explicit Runge–Kutta, no linear algebra) or ARKStep
// with a fully implicit DIRK table and the analytic Jacobian (SecondOrderLinearSolver). Root
// finding, stop times, interpolation and the reset after events (ERKStepReset / ARKStepReset)
// work as for CVODE.

#include <memory>

#include "pounding/solvers/cvode_integrator.hpp"
#include "pounding/solvers/integrator.hpp"

namespace pounding::solvers {

enum class ArkodeMethod { erk, dirk };

struct ArkodeSettings {
  ArkodeMethod method = ArkodeMethod::erk;
  double rtol = 1e-8;
  double atol = 1e-10;  // every component (m, rad and their rates) unless atol_vector is set
  /// ERK: 5 (Dormand–Prince 7-4-5). DIRK: 4 (SDIRK 5-3-4, default) or 3 (Kvaerno 4-2-3).
  int order = 0;                                            // 0: the default of the method
  NewtonSolver newton_solver = NewtonSolver::second_order;  // DIRK only
  /// Per state component (ARKStepSVtolerances); empty: atol for every one. @pre size 0 or the state's.
  Eigen::VectorXd atol_vector{};
};

/// @pre order 0 or one the method offers (analysis::SolverSettings::validate() checks user input).
/// @throws std::runtime_error if SUNDIALS set-up fails.
std::unique_ptr<Integrator> make_arkode_integrator(OdeFunctions& functions, const ArkodeSettings& settings, double t0,
                                                   const Eigen::VectorXd& y0);

}  // namespace pounding::solvers
