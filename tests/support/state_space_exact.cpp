#include "state_space_exact.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "pounding/solvers/root_finding.hpp"

namespace pounding::testing {

using namespace pounding::solvers;
namespace {

using Complex = std::complex<double>;

/// φ₁(z) = (eᶻ − 1)/z and φ₂(z) = (eᶻ − 1 − z)/z², by their series where the closed form
/// would cancel. Returns (φ₁, φ₂); multiply by τ and τ² for the forced response.
std::pair<Complex, Complex> phi_functions(Complex z) {
  if (std::abs(z) < 0.1) {
    // Terms up to z¹⁰ leave a relative error below 1e-16 for |z| < 0.1.
    Complex phi1 = 0.0, phi2 = 0.0, term = 1.0;  // term = zᵏ / k!
    for (int k = 0; k <= 12; ++k) {
      phi1 += term / double(k + 1);
      phi2 += term / double((k + 1) * (k + 2));
      term *= z / double(k + 1);
    }
    return {phi1, phi2};
  }
  const Complex e = std::exp(z);
  return {(e - 1.0) / z, (e - 1.0 - z) / (z * z)};
}

}  // namespace

StateSpaceExactIntegrator::StateSpaceExactIntegrator(OdeFunctions& functions, double t0, const Eigen::VectorXd& y0,
                                                     ExactSettings settings)
    : functions_(functions), settings_(settings), jacobian_(functions.state_size(), functions.state_size()) {
  restart(t0, y0);
}

void StateSpaceExactIntegrator::restart(double t, const Eigen::VectorXd& y) {
  counters_ = {};  // like CVODE's, the counters run from the last restart
  held_phase_ = !functions_.is_linear();
  if (held_phase_) {
    start_held_stretch(held_, functions_, settings_, t, y, max_step_s_);
    return;
  }
  freeze_phase(t, y);
  state_ = y;
  t_s_ = t;
  segment_ = segment_from(t, inverse_rows_ * y.cast<Complex>(), t + max_step_s_);
  forcing_fitted_to_s_ = std::numeric_limits<double>::quiet_NaN();  // fitted past the stop time: refit
  roots_start_ = roots_at(t, y);
}

void StateSpaceExactIntegrator::set_max_step(double h_s) {
  max_step_s_ = h_s;
  if (held_phase_) held_->set_max_step(h_s);
}

void StateSpaceExactIntegrator::set_stop_time(double t_s) {
  stop_time_s_ = t_s;
  if (held_phase_) held_->set_stop_time(t_s);
}

void StateSpaceExactIntegrator::freeze_phase(double t, const Eigen::VectorXd& y) {
  functions_.jacobian(t, y, jacobian_);
  ++counters_.jacobian_evaluations;
  y_phase_ = y;
  // Free flight has one constant J, so every restart after an impact or a release would repeat
  // the same decomposition (a third of the path's run time on the paper scene): keep it while J
  // is bit-for-bit the one decomposed.
  if (decomposed_jacobian_.size() != 0 && jacobian_ == decomposed_jacobian_) return;
  const Eigen::EigenSolver<Eigen::MatrixXd> solver(jacobian_);
  if (solver.info() != Eigen::Success) throw std::runtime_error("exact path: eigendecomposition failed");
  const Eigen::VectorXcd eigenvalues = solver.eigenvalues();
  const Eigen::MatrixXcd vectors = solver.eigenvectors();
  const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(vectors);
  // A defective (non-diagonalisable) J would make V singular: refuse rather than be inexact.
  const double residual = (jacobian_.cast<Complex>() * vectors - vectors * eigenvalues.asDiagonal()).norm();
  if (!(residual <= 1e-8 * jacobian_.norm() * vectors.norm()) || !std::isfinite(lu.rcond()) || lu.rcond() < 1e-13) {
    throw std::runtime_error("exact path: the phase Jacobian is not safely diagonalisable");
  }
  keep_one_of_each_pair(eigenvalues, vectors, lu.inverse());
  decomposed_jacobian_ = jacobian_;
}

void StateSpaceExactIntegrator::keep_one_of_each_pair(const Eigen::VectorXcd& eigenvalues,
                                                      const Eigen::MatrixXcd& vectors,
                                                      const Eigen::MatrixXcd& inverse) {
  // J is real, so its complex eigenvalues come in conjugate pairs with conjugate eigenvectors
  // (Eigen stores them side by side), and a real state has conjugate modal coordinates on them:
  // y = Re(Σ w_k v_k η_k) over one member of each pair (w = 2) and the real eigenvalues (w = 1).
  // Half the modes to advance and half the products, exactly. Should a pair not be exactly
  // conjugate, every mode is kept (w = 1): the same formula.
  const Eigen::Index n = eigenvalues.size();
  std::vector<std::pair<Eigen::Index, double>> kept;  // (mode, weight)
  for (Eigen::Index k = 0; k < n; ++k) {
    if (eigenvalues[k].imag() == 0.0) {
      kept.emplace_back(k, 1.0);
    } else if (k + 1 < n && eigenvalues[k + 1] == std::conj(eigenvalues[k]) &&
               vectors.col(k + 1) == vectors.col(k).conjugate()) {
      kept.emplace_back(k++, 2.0);
    } else {
      kept.clear();
      for (Eigen::Index j = 0; j < n; ++j) kept.emplace_back(j, 1.0);
      break;
    }
  }
  const auto m = static_cast<Eigen::Index>(kept.size());
  eigenvalues_.resize(m);
  vectors_.resize(n, m);
  inverse_rows_.resize(m, n);
  for (Eigen::Index j = 0; j < m; ++j) {
    const auto [k, weight] = kept[static_cast<std::size_t>(j)];
    eigenvalues_[j] = eigenvalues[k];
    vectors_.col(j) = weight * vectors.col(k);
    inverse_rows_.row(j) = inverse.row(k);
  }
}

Eigen::VectorXd StateSpaceExactIntegrator::forcing(double t) {
  Eigen::VectorXd f(y_phase_.size());
  functions_.rhs(t, y_phase_, f);
  ++counters_.rhs_evaluations;
  return f - jacobian_ * y_phase_;
}

StateSpaceExactIntegrator::Segment StateSpaceExactIntegrator::segment_from(double t, const ComplexVector& eta,
                                                                           double t_end) {
  // b is linear between record samples and no step crosses one (they are stop times), so two
  // values inside the step fix it exactly.
  const Eigen::VectorXd b0 = forcing(t);
  const double h = std::max(t_end - t, 1e-12);
  const Eigen::VectorXd b1 = (forcing(t + h) - b0) / h;
  return {t, eta, inverse_rows_ * b0.cast<Complex>(), inverse_rows_ * b1.cast<Complex>()};
}

StateSpaceExactIntegrator::ComplexVector StateSpaceExactIntegrator::modal(const Segment& segment, double t) const {
  const double tau = t - segment.t_start_s;
  ComplexVector eta(eigenvalues_.size());
  for (Eigen::Index k = 0; k < eta.size(); ++k) {
    const Complex z = eigenvalues_[k] * tau;
    const auto [phi1, phi2] = phi_functions(z);
    eta[k] = std::exp(z) * segment.eta_start[k] + segment.beta0[k] * phi1 * tau + segment.beta1[k] * phi2 * tau * tau;
  }
  return eta;
}

Eigen::VectorXd StateSpaceExactIntegrator::roots_at(double t, const Eigen::VectorXd& y) {
  Eigen::VectorXd g(functions_.root_count());
  functions_.roots(t, y, g);
  ++counters_.root_evaluations;
  return g;
}

StepOutcome StateSpaceExactIntegrator::step(double t_final) {
  if (held_phase_) return held_->step(t_final);
  const double t_end = std::min({t_s_ + max_step_s_, stop_time_s_, t_final});
  if (forcing_fitted_to_s_ == stop_time_s_) {
    // Still before the same stop time (the next record sample), so the forcing is the same
    // linear function: shift it instead of evaluating and projecting it again.
    const double tau = t_s_ - segment_.t_start_s;
    segment_ = {t_s_, modal(segment_, t_s_), segment_.beta0 + tau * segment_.beta1, segment_.beta1};
  } else {
    segment_ = segment_from(t_s_, modal(segment_, t_s_), t_end);
    forcing_fitted_to_s_ = std::isfinite(stop_time_s_) ? stop_time_s_ : std::numeric_limits<double>::quiet_NaN();
  }
  ++counters_.steps;

  Eigen::VectorXd y_end = physical(modal(segment_, t_end));
  const Eigen::VectorXd roots_end = roots_at(t_end, y_end);
  // Closing crossings (+ to − or onto 0), the direction the loop asks for.
  double t_root = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < roots_end.size(); ++i) {
    if (!(roots_start_[i] > 0.0 && roots_end[i] <= 0.0)) continue;
    const double b = find_root([&](double t) { return roots_at(t, physical(modal(segment_, t)))[i]; }, t_s_, t_end,
                               roots_start_[i], roots_end[i]);
    t_root = std::min(t_root, b);  // the root function has reached ≤ 0 there
  }

  roots_found_.assign(roots_end.size(), 0);
  if (t_root < std::numeric_limits<double>::infinity()) {
    state_ = physical(modal(segment_, t_root));
    const Eigen::VectorXd roots_here = roots_at(t_root, state_);
    for (Eigen::Index i = 0; i < roots_here.size(); ++i) {
      if (roots_start_[i] > 0.0 && roots_here[i] <= 0.0) roots_found_[i] = -1;
    }
    t_s_ = t_root;
    roots_start_ = roots_here;
    return {StepKind::root, t_root, {}};
  }
  state_ = std::move(y_end);
  t_s_ = t_end;
  roots_start_ = roots_end;
  if (t_end != stop_time_s_) return {StepKind::step, t_end, {}};
  // Like SUNDIALS', a stop time applies once: kept, it would make every later step empty.
  stop_time_s_ = std::numeric_limits<double>::infinity();
  return {StepKind::stop_time, t_end, {}};
}

void StateSpaceExactIntegrator::interpolate(double t, Eigen::Ref<Eigen::VectorXd> y) {
  if (held_phase_) {
    held_->interpolate(t, y);
  } else {
    y = physical(modal(segment_, t));
  }
}

}  // namespace pounding::testing
