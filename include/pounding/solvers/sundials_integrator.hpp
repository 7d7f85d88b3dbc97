#pragma once
// What CVODE and ARKODE integrators share: the SUNDIALS context, the state vectors, and the C
// callbacks into OdeFunctions, which get `this` through user_data and never let an exception
// cross into C (they record it and return a negative flag).

#include <string>

#include "pounding/solvers/integrator.hpp"
#include "pounding/solvers/sundials_handles.hpp"

namespace pounding::solvers {

class SundialsIntegrator : public Integrator {
 public:
  const Eigen::VectorXd& state() const override { return state_; }

 protected:
  SundialsIntegrator(OdeFunctions& functions, const Eigen::VectorXd& y0);

  static Eigen::Map<Eigen::VectorXd> view(N_Vector v) {
    return {N_VGetArrayPointer(v), static_cast<Eigen::Index>(N_VGetLength(v))};
  }
  /// The outcome of one step from the integrator's return flag (`name` maps a flag to its name).
  StepOutcome outcome(int flag, double t, int root_flag, int stop_flag, char* (*name)(long));

  static int rhs_callback(double t, N_Vector y, N_Vector y_dot, void* self);
  static int root_callback(double t, N_Vector y, double* g, void* self);
  /// Dense Jacobian for SUNDIALS' own dense Newton solver (CVLsJacFn / ARKLsJacFn).
  static int jacobian_callback(double t, N_Vector y, N_Vector f, SUNMatrix jac, void* self, N_Vector, N_Vector,
                               N_Vector);
  static void error_callback(int code, const char* module, const char* function, char* message, void* self);

  OdeFunctions& functions_;
  sundials::Context context_;
  sundials::Vector y_;
  sundials::Vector scratch_;
  Eigen::VectorXd state_;
  std::vector<int> root_directions_;  // −1 for every root: only closing gaps and falling forces
  std::string last_error_;            // from the error handler or a callback's exception
};

}  // namespace pounding::solvers
