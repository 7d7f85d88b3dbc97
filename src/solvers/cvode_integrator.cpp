#include "pounding/solvers/cvode_integrator.hpp"

#include <cassert>
#include <cvode/cvode.h>
#include <cvode/cvode_ls.h>
#include <sunmatrix/sunmatrix_dense.h>

namespace pounding::solvers {
namespace {

void check(int flag, const char* call) { sundials::check(flag, call, CVodeGetReturnFlagName); }

}  // namespace

CvodeIntegrator::CvodeIntegrator(OdeFunctions& functions, const CvodeSettings& settings, double t0,
                                 const Eigen::VectorXd& y0)
    : SundialsIntegrator(functions, y0) {
  const long n = functions.state_size();
  memory_ = sundials::IntegratorMemory(
      CVodeCreate(settings.method == CvodeMethod::bdf ? CV_BDF : CV_ADAMS, context_.get()), {CVodeFree});
  if (!memory_) throw std::runtime_error("CVodeCreate failed");
  check(CVodeSetErrHandlerFn(memory_.get(), error_callback, this), "CVodeSetErrHandlerFn");
  check(CVodeInit(memory_.get(), rhs_callback, t0, y_.get()), "CVodeInit");
  check(CVodeSetUserData(memory_.get(), this), "CVodeSetUserData");
  if (settings.atol_vector.size() == 0) {
    check(CVodeSStolerances(memory_.get(), settings.rtol, settings.atol), "CVodeSStolerances");
  } else {
    assert(settings.atol_vector.size() == functions.state_size());
    const sundials::Vector atol = sundials::make_vector(functions.state_size(), context_.get());
    view(atol.get()) = settings.atol_vector;
    check(CVodeSVtolerances(memory_.get(), settings.rtol, atol.get()), "CVodeSVtolerances");  // CVODE keeps a copy
  }
  if (settings.newton_solver == NewtonSolver::dense) {
    matrix_ = sundials::make_dense_matrix(n, context_.get());
    linear_solver_ = sundials::make_dense_solver(y_.get(), matrix_.get(), context_.get());
    check(CVodeSetLinearSolver(memory_.get(), linear_solver_.get(), matrix_.get()), "CVodeSetLinearSolver");
    check(CVodeSetJacFn(memory_.get(), jacobian_callback), "CVodeSetJacFn");
  } else {
    auto newton_data = [this] {
      NewtonData data;
      N_Vector yn = nullptr, fn = nullptr, zn1 = nullptr;
      double rl1 = 0.0;
      void* user_data = nullptr;
      check(CVodeGetNonlinearSystemData(memory_.get(), &data.t_s, &data.prediction, &yn, &fn, &data.gamma, &rl1, &zn1,
                                        &user_data),
            "CVodeGetNonlinearSystemData");
      return data;
    };
    second_order_ = std::make_unique<SecondOrderLinearSolver>(functions, newton_data, context_.get(), last_error_);
    check(CVodeSetLinearSolver(memory_.get(), second_order_->get(), nullptr), "CVodeSetLinearSolver");
  }
  if (functions.root_count() > 0) {  // a system without candidates or yielding columns has none
    check(CVodeRootInit(memory_.get(), functions.root_count(), root_callback), "CVodeRootInit");
    check(CVodeSetRootDirection(memory_.get(), root_directions_.data()), "CVodeSetRootDirection");
    check(CVodeSetNoInactiveRootWarn(memory_.get()), "CVodeSetNoInactiveRootWarn");
  }
  check(CVodeSetMaxNumSteps(memory_.get(), -1), "CVodeSetMaxNumSteps");  // the loop caps steps itself
}

CvodeIntegrator::~CvodeIntegrator() = default;

void CvodeIntegrator::restart(double t, const Eigen::VectorXd& y) {
  view(y_.get()) = y;
  state_ = y;
  check(CVodeReInit(memory_.get(), t, y_.get()), "CVodeReInit");
  stepped_since_restart_ = false;
  if (second_order_) {
    second_order_->invalidate();                                   // the contact phase, so the Jacobian, changed
    factorizations_at_restart_ = second_order_->factorizations();  // CVODE's counters restart too
  }
}

void CvodeIntegrator::set_max_step(double h_s) { check(CVodeSetMaxStep(memory_.get(), h_s), "CVodeSetMaxStep"); }

void CvodeIntegrator::set_stop_time(double t_s) { check(CVodeSetStopTime(memory_.get(), t_s), "CVodeSetStopTime"); }

StepOutcome CvodeIntegrator::step(double t_final) {
  double t = 0.0;
  last_error_.clear();
  const int flag = CVode(memory_.get(), t_final, y_.get(), &t, CV_ONE_STEP);
  stepped_since_restart_ = true;
  return outcome(flag, t, CV_ROOT_RETURN, CV_TSTOP_RETURN, CVodeGetReturnFlagName);
}

void CvodeIntegrator::interpolate(double t, Eigen::Ref<Eigen::VectorXd> y) {
  check(CVodeGetDky(memory_.get(), t, 0, scratch_.get()), "CVodeGetDky");
  y = view(scratch_.get());
}

std::vector<int> CvodeIntegrator::roots_found() {
  std::vector<int> found(root_directions_.size(), 0);
  check(CVodeGetRootInfo(memory_.get(), found.data()), "CVodeGetRootInfo");
  return found;
}

IntegratorCounters CvodeIntegrator::counters() {
  IntegratorCounters c;
  check(CVodeGetNumSteps(memory_.get(), &c.steps), "CVodeGetNumSteps");
  check(CVodeGetNumRhsEvals(memory_.get(), &c.rhs_evaluations), "CVodeGetNumRhsEvals");
  check(CVodeGetNumGEvals(memory_.get(), &c.root_evaluations), "CVodeGetNumGEvals");
  if (second_order_) {
    c.jacobian_evaluations = second_order_->factorizations() - factorizations_at_restart_;
  } else if (stepped_since_restart_) {
    // CVodeReInit resets the linear solver's counters only at the first step after it: until
    // then CVodeGetNumJacEvals still holds the previous stretch's count.
    check(CVodeGetNumJacEvals(memory_.get(), &c.jacobian_evaluations), "CVodeGetNumJacEvals");
  }
  check(CVodeGetNumErrTestFails(memory_.get(), &c.error_test_failures), "CVodeGetNumErrTestFails");
  return c;
}

}  // namespace pounding::solvers
