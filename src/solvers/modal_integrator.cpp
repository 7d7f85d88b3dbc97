#include "pounding/solvers/modal_integrator.hpp"

namespace pounding::solvers {

ModalIntegrator::Functions::Functions(const dynamics::ModalSystem& modes, OdeFunctions& physical)
    : MappedFunctions(physical), modes_(modes), y_(physical.state_size()), y_dot_(physical.state_size()) {}

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
    : MappedIntegrator(y0), modes_(modes), functions_(modes, physical) {
  Eigen::VectorXd z0(y0.size());
  modes_.to_modal(y0, z0);
  start(inner, functions_, t0, z0);
}

}  // namespace pounding::solvers
