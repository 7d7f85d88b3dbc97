#pragma once
// The seam between the event-driven loop and an ODE integrator (CVODE, ARKODE): the loop supplies
// the functions of the current contact phase; the integrator steps, finds roots, interpolates.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <memory>
#include <optional>
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
  /// For a second-order system, jacobian() = [[0, I], [A21, A22]]: writes its lower half
  /// [A21, A22] (n × 2n) sparse and returns true, so that a linear solver can use the sparsity;
  /// false (the default): not available, use jacobian(). With extra states (extra_state_count)
  /// these are the rows' (q, q̇) columns, the rest coming from extra_state_jacobian().
  virtual bool acceleration_jacobian(double /*t*/, const Eigen::Ref<const Eigen::VectorXd>& /*y*/,
                                     Eigen::SparseMatrix<double>& /*rows*/) {
    return false;
  }
  /// First-order states w after (q, q̇) (Bouc–Wen's z): y = (q, q̇, w), their rates depending on
  /// q̇ and w only, each w_j on itself alone. 0 (the default): none.
  virtual int extra_state_count() const { return 0; }
  /// Their blocks of jacobian(): ∂q̈/∂w (n × m), ∂ẇ/∂q̇ (m × n) and the diagonal ∂ẇ/∂w (m), sparse,
  /// for a linear solver that eliminates w (SecondOrderLinearSolver).
  /// @pre extra_state_count() > 0.
  virtual void extra_state_jacobian(double /*t*/, const Eigen::Ref<const Eigen::VectorXd>& /*y*/,
                                    Eigen::SparseMatrix<double>& /*accel_by_w*/,
                                    Eigen::SparseMatrix<double>& /*w_rate_by_velocity*/,
                                    Eigen::VectorXd& /*w_rate_by_w*/) {}
  /// True when rhs is affine in y with a constant jacobian() (free flight); false when it may
  /// depend on y nonlinearly (a held contact's rotating geometry).
  virtual bool is_linear() const { return false; }
  /// True when rhs is the coupled system's free motion ẏ = A y + B a_g(t) (no contact force
  /// acts): a modal form may then step it mode by mode without calling rhs (ModalIntegrator).
  virtual bool is_free_motion() const { return false; }
};

enum class StepKind { step, root, stop_time, failure };

struct StepOutcome {
  StepKind kind = StepKind::step;
  double t_s = 0.0;
  std::string failure;  // the integrator's flag name and message when kind == failure
};

struct IntegratorCounters {
  long steps = 0, rhs_evaluations = 0, root_evaluations = 0, jacobian_evaluations = 0, error_test_failures = 0;
};

/// Work on the relative motion over a stretch of a step (kJ).
struct StretchEnergy {
  double input_kJ = 0.0;    // ∫ −q̇ᵀ M r a_g dt
  double damping_kJ = 0.0;  // ∫ q̇ᵀ C q̇ dt
};

/// The contract below is checked for every implementation by tests/solvers/
/// test_integrator_conformance.cpp.
class Integrator {
 public:
  virtual ~Integrator() = default;
  /// (Re)starts at t from y: at the beginning and after every event. The loop then sets the
  /// stop time and the maximum step, in that order.
  virtual void restart(double t, const Eigen::VectorXd& y) = 0;
  virtual void set_max_step(double h_s) = 0;
  /// step() will end exactly (bit for bit) at t_s with StepKind::stop_time, never past it. A
  /// stop time applies once: after it is reached, steps are bounded only by the next one set.
  virtual void set_stop_time(double t_s) = 0;
  /// One internal step, never past the stop time; a root inside the step ends it at the root.
  /// `t_final` is the end of the run; only a stop time bounds a step for certain (the loop
  /// makes the end of the record one).
  virtual StepOutcome step(double t_final) = 0;
  /// The state at the time step() returned.
  virtual const Eigen::VectorXd& state() const = 0;
  /// The state at t within the last step, from the integrator's own interpolant; at the step's
  /// end it is state(). @pre t within the last step: outside it CVODE and ARKODE throw
  /// std::runtime_error (their BAD_T flag), the exact path's free flight extends its closed form.
  virtual void interpolate(double t, Eigen::Ref<Eigen::VectorXd> y) = 0;
  /// interpolate() where only the components `indices` of y are needed (the others may be
  /// overwritten or left as they are). An integrator that evaluates part of its state for less
  /// overrides it (the exact path: O(modes) a component instead of O(n²) for the whole state).
  virtual void interpolate_components(double t, const std::vector<int>& /*indices*/, Eigen::Ref<Eigen::VectorXd> y) {
    interpolate(t, y);
  }
  /// Per root component: −1 if it went from > 0 to ≤ 0 at the last root return, else 0. Only
  /// such closing crossings end a step (an opening one never does). Crossings are listed
  /// together only when they coincide to the root finder's round-off; two that coincide only
  /// in exact arithmetic (computed differently) come as consecutive root returns, each at its
  /// own crossing within the integration tolerance.
  virtual std::vector<int> roots_found() = 0;
  /// The work since the last restart() (or construction), including what restart() itself
  /// evaluated (the exact path diagonalises J and evaluates the forcing there): right after
  /// restart() no step and no error test failure is counted.
  virtual IntegratorCounters counters() = 0;
  /// The ground motion's input and the damping's dissipation over [t_a, t_b] within the last
  /// step, where the integrator has them in closed form (the exact path's free flight, in which
  /// no contact force acts); empty: the caller integrates them on the interpolant.
  virtual std::optional<StretchEnergy> energy_between(double /*t_a*/, double /*t_b*/) { return std::nullopt; }
  /// True if the integrator carries the record's forcing itself, so its steps stay accurate
  /// across the kink of a_g at a record sample (the deviation form): the loop then stops it only
  /// at the record's end instead of at every sample.
  virtual bool steps_across_samples() const { return false; }
};

/// Makes the integrator of a run: for `functions`, from (t0, y0).
using IntegratorFactory =
    std::function<std::unique_ptr<Integrator>(OdeFunctions& functions, double t0, const Eigen::VectorXd& y0)>;

}  // namespace pounding::solvers
