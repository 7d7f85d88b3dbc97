#pragma once
// The seam between the event-driven loop and an ODE integrator (CVODE, ARKODE): the loop supplies
// the functions of the current contact phase; the integrator steps, finds roots, interpolates.

#include <Eigen/Core>
#include <string>
#include <vector>

namespace pounding::solvers {

/// The ODE of the current phase as the integrator sees it. Implementations may throw; the
/// integrator's callbacks catch and turn that into a failed step.
class OdeFunctions {
 public:
  virtual ~OdeFunctions() = default;
  virtual int state_size() const = 0;
  virtual int root_count() const = 0;
  virtual void rhs(double t, const Eigen::Ref<const Eigen::VectorXd>& y, Eigen::Ref<Eigen::VectorXd> y_dot) = 0;
  virtual void jacobian(double t, const Eigen::Ref<const Eigen::VectorXd>& y, Eigen::Ref<Eigen::MatrixXd> jac) = 0;
  virtual void roots(double t, const Eigen::Ref<const Eigen::VectorXd>& y, Eigen::Ref<Eigen::VectorXd> g) = 0;
  /// True when rhs is affine in y with a constant jacobian() (free flight); false when it may
  /// depend on y nonlinearly (a held contact's rotating geometry).
  virtual bool is_linear() const { return false; }
};

enum class StepKind { step, root, stop_time, failure };

struct StepOutcome {
  StepKind kind = StepKind::step;
  double t_s = 0.0;
  std::string failure;  // the integrator's flag name and message when kind == failure
};

struct IntegratorCounters {
  long steps = 0, rhs_evaluations = 0, root_evaluations = 0, jacobian_evaluations = 0,
       error_test_failures = 0;
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  /// (Re)starts at t from y: at the beginning and after every event.
  virtual void restart(double t, const Eigen::VectorXd& y) = 0;
  virtual void set_max_step(double h_s) = 0;
  virtual void set_stop_time(double t_s) = 0;
  /// One internal step, never past the stop time; a root inside the step ends it at the root.
  virtual StepOutcome step(double t_final) = 0;
  /// The state at the time step() returned.
  virtual const Eigen::VectorXd& state() const = 0;
  /// The state at t within the last step, from the integrator's own interpolant.
  virtual void interpolate(double t, Eigen::Ref<Eigen::VectorXd> y) = 0;
  /// Components of the root vector that changed sign at the last root return.
  virtual std::vector<int> roots_found() = 0;
  virtual IntegratorCounters counters() = 0;
};

}  // namespace pounding::solvers
