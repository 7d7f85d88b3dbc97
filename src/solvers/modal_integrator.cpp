#include "pounding/solvers/modal_integrator.hpp"

namespace pounding::solvers {

ModalIntegrator::Functions::Functions(const dynamics::ModalSystem& modes, OdeFunctions& physical)
    : modes_(modes), physical_(physical), y_(physical.state_size()), y_dot_(physical.state_size()) {}

void ModalIntegrator::Functions::rhs(double t, const Eigen::Ref<const Eigen::VectorXd>& z,
                                     Eigen::Ref<Eigen::VectorXd> z_dot) {
  if (physical_.is_free_motion()) return modes_.rhs(t, z, z_dot);
  modes_.to_physical(z, y_);
  physical_.rhs(t, y_, y_dot_);
  modes_.to_modal(y_dot_, z_dot);
}

void ModalIntegrator::Functions::jacobian(double t, const Eigen::Ref<const Eigen::VectorXd>& z,
                                          Eigen::Ref<Eigen::MatrixXd> jac) {
  if (physical_.is_free_motion()) return modes_.jacobian(jac);
  modes_.to_physical(z, y_);
  jacobian_.resize(jac.rows(), jac.cols());
  physical_.jacobian(t, y_, jacobian_);
  modes_.jacobian_to_modal(jacobian_, jac);
}

void ModalIntegrator::Functions::roots(double t, const Eigen::Ref<const Eigen::VectorXd>& z,
                                       Eigen::Ref<Eigen::VectorXd> g) {
  modes_.to_physical(z, y_);
  physical_.roots(t, y_, g);
}

ModalIntegrator::ModalIntegrator(const dynamics::ModalSystem& modes, OdeFunctions& physical,
                                 const IntegratorFactory& inner, double t0, const Eigen::VectorXd& y0)
    : modes_(modes), functions_(modes, physical), state_(y0), z_(y0.size()) {
  modes_.to_modal(y0, z_);
  inner_ = inner(functions_, t0, z_);
}

void ModalIntegrator::restart(double t, const Eigen::VectorXd& y) {
  modes_.to_modal(y, z_);
  inner_->restart(t, z_);
  state_ = y;
}

StepOutcome ModalIntegrator::step(double t_final) {
  const StepOutcome outcome = inner_->step(t_final);
  modes_.to_physical(inner_->state(), state_);
  return outcome;
}

void ModalIntegrator::interpolate(double t, Eigen::Ref<Eigen::VectorXd> y) {
  inner_->interpolate(t, z_);
  modes_.to_physical(z_, y);
}

}  // namespace pounding::solvers
