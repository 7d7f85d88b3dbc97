#include "pounding/solvers/deviation_integrator.hpp"

#include <algorithm>

#include "pounding/solvers/modal_propagator.hpp"

namespace pounding::solvers {

FreeResponse::FreeResponse(const dynamics::ModalSystem& modes, double t0, const Eigen::VectorXd& y0)
    : modes_(modes), z_(y0.size()), z_dot_(y0.size()) {
  const int n = modes.dof();
  damping_ratio_ = modes.damping_per_s().cwiseQuotient(2.0 * modes.omega_rad_s());
  const excitation::GroundMotion& motion = modes.system().ground_motion();
  Eigen::VectorXd z(y0.size());
  modes.to_modal(y0, z);
  times_.push_back(t0);
  states_.push_back(z);
  for (double t : motion.time_s()) {
    if (t <= t0) continue;
    // Over [t_a, t]: η̈ + 2ζωη̇ + ω²η = −Σ_c Γ_c a_c, each a_c linear.
    const double t_a = times_.back(), tau = t - t_a;
    const Eigen::Vector2d a_start = ground_accel(t_a), slope = (ground_accel(t) - a_start) / tau;
    const Eigen::VectorXd& from = states_.back();
    Eigen::VectorXd next(y0.size());
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d moved = advance(i, from, tau, a_start, slope);
      next[i] = moved[0];
      next[n + i] = moved[1];
    }
    times_.push_back(t);
    states_.push_back(std::move(next));
  }
}

Eigen::Vector2d FreeResponse::ground_accel(double t) const {
  const excitation::GroundMotion& motion = modes_.system().ground_motion();
  return {motion.accel_at(t), motion.is_pair() ? motion.accel_at(t, 1) : 0.0};
}

double FreeResponse::modal_load(int i, const Eigen::Vector2d& accel) const {
  double load = modes_.participation()(i, 0) * accel[0];
  for (int c = 1; c < modes_.participation().cols(); ++c) load += modes_.participation()(i, c) * accel[c];
  return load;
}

Eigen::Vector2d FreeResponse::advance(int i, const Eigen::VectorXd& from, double tau, const Eigen::Vector2d& a_start,
                                      const Eigen::Vector2d& slope) const {
  const int n = modes_.dof();
  const OscillatorStep step = oscillator_step(modes_.omega_rad_s()[i], damping_ratio_[i], tau);
  return step.free * Eigen::Vector2d(from[i], from[n + i]) + step.start * (-modal_load(i, a_start)) +
         step.slope * (-modal_load(i, slope));
}

void FreeResponse::modal_at(double t, Eigen::VectorXd& z, Eigen::VectorXd& z_dot) const {
  const int n = modes_.dof();
  // The piece [t_k, t_k+1] holding t (the last one for t at or past the end).
  const auto after = std::upper_bound(times_.begin(), times_.end(), t);
  const std::size_t k =
      after == times_.begin() ? 0 : std::min<std::size_t>(after - times_.begin() - 1, times_.size() - 2);
  const double t_a = times_[k], tau = t - t_a;
  const Eigen::Vector2d a_start = ground_accel(t_a),
                        slope = (ground_accel(times_[k + 1]) - a_start) / (times_[k + 1] - t_a);
  const Eigen::VectorXd& from = states_[k];
  const Eigen::Vector2d a_now = a_start + slope * tau;
  for (int i = 0; i < n; ++i) {
    const double omega = modes_.omega_rad_s()[i];
    const Eigen::Vector2d moved = advance(i, from, tau, a_start, slope);
    z[i] = moved[0];
    z[n + i] = moved[1];
    z_dot[i] = moved[1];
    z_dot[n + i] = -omega * omega * moved[0] - modes_.damping_per_s()[i] * moved[1] - modal_load(i, a_now);
  }
}

void FreeResponse::at(double t, Eigen::VectorXd& y) const {
  modal_at(t, z_, z_dot_);
  modes_.to_physical(z_, y);
}

void FreeResponse::at(double t, Eigen::VectorXd& y, Eigen::VectorXd& y_dot) const {
  modal_at(t, z_, z_dot_);
  modes_.to_physical(z_, y);
  modes_.to_physical(z_dot_, y_dot);
}

DeviationIntegrator::Functions::Functions(const FreeResponse& free, OdeFunctions& physical)
    : MappedFunctions(physical),
      free_(free),
      y_(physical.state_size()),
      yp_(physical.state_size()),
      yp_dot_(physical.state_size()),
      y_dot_(physical.state_size()) {}

void DeviationIntegrator::Functions::physical_state(double t, const Eigen::Ref<const Eigen::VectorXd>& z) {
  free_.at(t, yp_);
  y_ = yp_ + z;
}

void DeviationIntegrator::Functions::rhs(double t, const Eigen::Ref<const Eigen::VectorXd>& z,
                                         Eigen::Ref<Eigen::VectorXd> z_dot) {
  free_.at(t, yp_, yp_dot_);
  y_ = yp_ + z;
  physical_.rhs(t, y_, y_dot_);
  z_dot = y_dot_ - yp_dot_;
}

void DeviationIntegrator::Functions::jacobian(double t, const Eigen::Ref<const Eigen::VectorXd>& z,
                                              Eigen::Ref<Eigen::MatrixXd> jac) {
  physical_state(t, z);
  physical_.jacobian(t, y_, jac);
}

bool DeviationIntegrator::Functions::acceleration_jacobian(double t, const Eigen::Ref<const Eigen::VectorXd>& z,
                                                           Eigen::SparseMatrix<double>& rows) {
  physical_state(t, z);
  return physical_.acceleration_jacobian(t, y_, rows);
}

void DeviationIntegrator::Functions::roots(double t, const Eigen::Ref<const Eigen::VectorXd>& z,
                                           Eigen::Ref<Eigen::VectorXd> g) {
  physical_state(t, z);
  physical_.roots(t, y_, g);
}

DeviationIntegrator::DeviationIntegrator(const dynamics::ModalSystem& modes, OdeFunctions& physical,
                                         const IntegratorFactory& inner, double t0, const Eigen::VectorXd& y0)
    : MappedIntegrator(y0), free_(modes, t0, y0), functions_(free_, physical), yp_(y0.size()) {
  start(inner, functions_, t0, Eigen::VectorXd::Zero(y0.size()));  // y₀ is y_p(t₀) by construction
}

void DeviationIntegrator::to_inner(double t, const Eigen::VectorXd& y, Eigen::VectorXd& z) {
  free_.at(t, yp_);
  z = y - yp_;
}

void DeviationIntegrator::to_physical(double t, const Eigen::Ref<const Eigen::VectorXd>& z,
                                      Eigen::Ref<Eigen::VectorXd> y) {
  free_.at(t, yp_);
  y = yp_ + z;
}

}  // namespace pounding::solvers
