#pragma once
// The state-space exact propagator, for tests: an independent reference for the exact path
// (ModalExactIntegrator, which propagates each building's real modes instead) and an exact
// integrator for any linear OdeFunctions, as the integrator conformance suite uses it. Not part
// of the library: every run's `exact` method is the modal form.
//
// Free flight (OdeFunctions::is_linear()) is linear with piecewise-linear forcing: at every
// (re)start the phase is frozen as ẏ = J y + b(t) with J = OdeFunctions::jacobian(t₀, y₀) and
// b(t) = f(t, y₀) − J y₀, which *is* the model there.
//
// Method: the state-space eigendecomposition J = V Λ V⁻¹, done once per distinct J (free flight
// has one). Each modal
// coordinate has a closed form under forcing linear in time:
//   η(τ) = e^{λτ} η₀ + β₀ (e^{λτ} − 1)/λ + β₁ (e^{λτ} − 1 − λτ)/λ².
// So the state is exact at any instant (round-off and the conditioning of V aside), and roots
// are located on the exact trajectory: each step of at most the maximum step (the loop sets a
// fraction of the shortest period that moves a gap) is checked for sign changes, the crossing is polished to
// round-off, and the loop examines every interior minimum through interpolate().
//
// A held contact is not linear: the contact geometry rotates with the slabs, and linearising it
// (once, or at every step) leaves errors of 1e−4 … 1e−6 s in the impact times after a hold. Held
// stretches are therefore integrated by CVODE (BDF: a stiff storey makes Adams crawl) at a tight
// tolerance (ExactSettings), the only part of the path that is not exact; its error is what the
// study's reference error estimate measures.

#include <Eigen/Dense>
#include <complex>
#include <memory>

#include "pounding/solvers/cvode_integrator.hpp"
#include "pounding/solvers/exact_settings.hpp"
#include "pounding/solvers/integrator.hpp"

namespace pounding::testing {

using solvers::ExactSettings;
using solvers::Integrator;
using solvers::IntegratorCounters;
using solvers::OdeFunctions;
using solvers::StepOutcome;

class StateSpaceExactIntegrator final : public Integrator {
 public:
  /// `functions` must outlive the integrator.
  /// @throws std::runtime_error if a free-flight J cannot be diagonalised.
  StateSpaceExactIntegrator(OdeFunctions& functions, double t0, const Eigen::VectorXd& y0, ExactSettings settings = {});

  void restart(double t, const Eigen::VectorXd& y) override;
  void set_max_step(double h_s) override;
  void set_stop_time(double t_s) override;
  StepOutcome step(double t_final) override;
  const Eigen::VectorXd& state() const override { return held_phase_ ? held_->state() : state_; }
  void interpolate(double t, Eigen::Ref<Eigen::VectorXd> y) override;
  std::vector<int> roots_found() override { return held_phase_ ? held_->roots_found() : roots_found_; }
  IntegratorCounters counters() override { return held_phase_ ? held_->counters() : counters_; }

 private:
  using ComplexVector = Eigen::VectorXcd;

  /// The linear forcing over the current step, in modal coordinates: b(t_start + τ) = b₀ + b₁ τ.
  struct Segment {
    double t_start_s = 0.0;
    ComplexVector eta_start, beta0, beta1;
  };

  /// Freezes the free-flight phase at (t, y) and diagonalises. @throws std::runtime_error if J
  /// is not diagonalisable.
  void freeze_phase(double t, const Eigen::VectorXd& y);
  void keep_one_of_each_pair(const Eigen::VectorXcd& eigenvalues, const Eigen::MatrixXcd& vectors,
                             const Eigen::MatrixXcd& inverse);
  Eigen::VectorXd forcing(double t);  // b(t) = f(t, y_phase) − J y_phase
  Segment segment_from(double t, const ComplexVector& eta, double t_end);
  ComplexVector modal(const Segment& segment, double t) const;
  Eigen::VectorXd physical(const ComplexVector& eta) const { return (vectors_ * eta).real(); }
  Eigen::VectorXd roots_at(double t, const Eigen::VectorXd& y);

  OdeFunctions& functions_;
  ExactSettings settings_;
  std::unique_ptr<Integrator> held_;  // integrates the held stretches
  bool held_phase_ = false;
  Eigen::MatrixXd jacobian_;
  Eigen::MatrixXd decomposed_jacobian_;  // the J that eigenvalues_ and vectors_ decompose
  Eigen::VectorXd y_phase_;              // the linearisation point of this phase
  // The modes advanced: one of each conjugate pair and the real ones (keep_one_of_each_pair).
  Eigen::VectorXcd eigenvalues_;
  Eigen::MatrixXcd vectors_;          // columns v_k scaled by their weight (2 for a pair), n × m
  Eigen::MatrixXcd inverse_rows_;     // the matching rows of V⁻¹, m × n
  Segment segment_;                   // the last step's forcing, for interpolation inside it
  double forcing_fitted_to_s_ = 0.0;  // segment_'s forcing holds up to this stop time (NaN: refit)
  Eigen::VectorXd state_;
  Eigen::VectorXd roots_start_;  // root functions at the current time
  std::vector<int> roots_found_;
  double t_s_ = 0.0;
  double max_step_s_ = 0.01;
  double stop_time_s_ = std::numeric_limits<double>::infinity();
  IntegratorCounters counters_;
};

}  // namespace pounding::testing
