#pragma once
// The exact propagator (ground truth for the linear model) behind the Integrator seam.
//
// At every (re)start it freezes the current phase as the linear system ẏ = J y + b(t) with
// J = OdeFunctions::jacobian(t₀, y₀) and b(t) = f(t, y₀) − J y₀. In free flight this *is* the
// model (f is affine in y, and b is piecewise linear in t like a_g). While contacts are held,
// it is the constraint linearised at the instant of the restart (rows of G frozen, curvature
// term frozen): the linear model the exact path integrates exactly, whose cost the study
// measures against CVODE's nonlinear hold.
//
// Method: the state-space eigendecomposition J = V Λ V⁻¹, done once per phase. It handles the
// coupled, non-classically damped held phases (the two buildings have different Rayleigh
// coefficients) as well as free flight, and each modal coordinate has a closed form under
// forcing linear in time:  η(τ) = e^{λτ} η₀ + β₀ (e^{λτ} − 1)/λ + β₁ (e^{λτ} − 1 − λτ)/λ².
// So the state is exact at any instant (round-off and the conditioning of V aside), and roots
// are located on the exact trajectory: each step of at most the maximum step (the loop sets a
// fraction of the shortest period) is checked for sign changes, the crossing is polished to
// round-off, and the loop examines every interior minimum through interpolate().

#include <Eigen/Dense>
#include <complex>
#include <memory>

#include "pounding/solvers/integrator.hpp"

namespace pounding::solvers {

class ExactIntegrator final : public Integrator {
 public:
  /// `functions` must outlive the integrator. With `relinearize`, a phase whose Jacobian depends
  /// on the state (a held contact) is linearised again at the start of every step instead of
  /// only at its first instant; free flight, whose Jacobian is constant, is unaffected.
  /// @throws std::runtime_error if J cannot be diagonalised.
  ExactIntegrator(OdeFunctions& functions, double t0, const Eigen::VectorXd& y0, bool relinearize = false);

  void restart(double t, const Eigen::VectorXd& y) override;
  void set_max_step(double h_s) override { max_step_s_ = h_s; }
  void set_stop_time(double t_s) override { stop_time_s_ = t_s; }
  StepOutcome step(double t_final) override;
  const Eigen::VectorXd& state() const override { return state_; }
  void interpolate(double t, Eigen::Ref<Eigen::VectorXd> y) override;
  std::vector<int> roots_found() override { return roots_found_; }
  IntegratorCounters counters() override { return counters_; }

 private:
  using ComplexVector = Eigen::VectorXcd;

  /// The linear forcing over the current step, in modal coordinates: b(t_start + τ) = b₀ + b₁ τ.
  struct Segment {
    double t_start_s = 0.0;
    ComplexVector eta_start, beta0, beta1;
  };

  /// Linearises at (t, y) and diagonalises. @throws std::runtime_error if J is not diagonalisable.
  void freeze_phase(double t, const Eigen::VectorXd& y);
  Eigen::VectorXd forcing(double t);   // b(t) = f(t, y_phase) − J y_phase
  Segment segment_from(double t, const ComplexVector& eta, double t_end);
  ComplexVector modal(const Segment& segment, double t) const;
  Eigen::VectorXd physical(const ComplexVector& eta) const { return (vectors_ * eta).real(); }
  Eigen::VectorXd roots_at(double t, const Eigen::VectorXd& y);

  OdeFunctions& functions_;
  bool relinearize_ = false;
  Eigen::MatrixXd jacobian_, jacobian_now_;
  Eigen::VectorXd y_phase_;           // the linearisation point of this phase
  Eigen::VectorXcd eigenvalues_;
  Eigen::MatrixXcd vectors_;
  Eigen::PartialPivLU<Eigen::MatrixXcd> inverse_;
  Segment segment_;                   // the last step's forcing, for interpolation inside it
  Eigen::VectorXd state_;
  Eigen::VectorXd roots_start_;       // root functions at the current time
  std::vector<int> roots_found_;
  double t_s_ = 0.0;
  double max_step_s_ = 0.01;
  double stop_time_s_ = std::numeric_limits<double>::infinity();
  IntegratorCounters counters_;
};

}  // namespace pounding::solvers
