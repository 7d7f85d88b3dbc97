#include "pounding/solvers/sundials_integrator.hpp"

#include <sunmatrix/sunmatrix_dense.h>

namespace pounding::solvers {

SundialsIntegrator::SundialsIntegrator(OdeFunctions& functions, const Eigen::VectorXd& y0)
    : functions_(functions),
      context_(sundials::make_context()),
      y_(sundials::make_vector(functions.state_size(), context_.get())),
      scratch_(sundials::make_vector(functions.state_size(), context_.get())),
      state_(y0),
      root_directions_(functions.root_count(), -1) {
  view(y_.get()) = y0;
}

StepOutcome SundialsIntegrator::outcome(int flag, double t, int root_flag, int stop_flag, char* (*name)(long)) {
  state_ = view(y_.get());
  if (flag == root_flag) return {StepKind::root, t, {}};
  if (flag == stop_flag) return {StepKind::stop_time, t, {}};
  if (flag >= 0) return {StepKind::step, t, {}};
  std::string failure = sundials::take_flag_name(name(flag));
  if (!last_error_.empty()) failure += ": " + last_error_;
  return {StepKind::failure, t, failure};
}

int SundialsIntegrator::rhs_callback(double t, N_Vector y, N_Vector y_dot, void* self) {
  auto* me = static_cast<SundialsIntegrator*>(self);
  try {
    me->functions_.rhs(t, view(y), view(y_dot));
    return 0;
  } catch (const std::exception& error) {
    me->last_error_ = error.what();
    return -1;
  }
}

int SundialsIntegrator::root_callback(double t, N_Vector y, double* g, void* self) {
  auto* me = static_cast<SundialsIntegrator*>(self);
  try {
    me->functions_.roots(t, view(y), Eigen::Map<Eigen::VectorXd>(g, me->functions_.root_count()));
    return 0;
  } catch (const std::exception& error) {
    me->last_error_ = error.what();
    return -1;
  }
}

int SundialsIntegrator::jacobian_callback(double t, N_Vector y, N_Vector, SUNMatrix jac, void* self, N_Vector, N_Vector,
                                          N_Vector) {
  auto* me = static_cast<SundialsIntegrator*>(self);
  try {
    const Eigen::Index n = static_cast<Eigen::Index>(SUNDenseMatrix_Rows(jac));
    Eigen::Map<Eigen::MatrixXd> matrix(SUNDenseMatrix_Data(jac), n, n);  // column-major
    me->functions_.jacobian(t, view(y), matrix);
    return 0;
  } catch (const std::exception& error) {
    me->last_error_ = error.what();
    return -1;
  }
}

void SundialsIntegrator::error_callback(int, const char*, const char* function, char* message, void* self) {
  auto* me = static_cast<SundialsIntegrator*>(self);
  if (me->last_error_.empty()) me->last_error_ = std::string(function) + ": " + message;
}

}  // namespace pounding::solvers
