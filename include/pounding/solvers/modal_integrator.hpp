#pragma once
// An integrator of the modal coordinates z = T⁻¹ y (dynamics::ModalSystem) behind the same seam as
// the physical one: the event loop hands it and reads from it physical states, so it needs to know
// nothing of the form. While the loop's functions are the free motion (OdeFunctions::
// is_free_motion), the inner integrator steps the decoupled modal rhs and its diagonal Jacobian;
// while a contact force acts (a hold, a compliant contact) it steps the loop's physical rhs mapped
// through T, so impulses, hold forces and compliant forces are projected on the modes as
// Δż = T⁻¹ Δẏ (Φᵀ M Δq̈ for the accelerations). Root functions are the loop's, on y = T z.

#include <memory>

#include "pounding/dynamics/modal_system.hpp"
#include "pounding/solvers/mapped_integrator.hpp"

namespace pounding::solvers {

class ModalIntegrator final : public MappedIntegrator {
 public:
  /// `modes`, `physical` and `inner` must outlive the integrator; `inner` is called once, with
  /// the modal functions and z₀ = T⁻¹ y₀ (its tolerances apply to z: ModalSystem::atol).
  ModalIntegrator(const dynamics::ModalSystem& modes, OdeFunctions& physical, const IntegratorFactory& inner, double t0,
                  const Eigen::VectorXd& y0);

 private:
  /// The loop's functions seen in modal coordinates.
  class Functions final : public MappedFunctions {
   public:
    Functions(const dynamics::ModalSystem& modes, OdeFunctions& physical);
    void rhs(double t, const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> z_dot) override;
    void jacobian(double t, const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::MatrixXd> jac) override;
    void roots(double t, const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g) override;

   private:
    const dynamics::ModalSystem& modes_;
    Eigen::VectorXd y_, y_dot_;  // scratch: the physical state and rate
    Eigen::MatrixXd jacobian_;   // scratch: the physical Jacobian (contact phases only)
  };

  void to_inner(double, const Eigen::VectorXd& y, Eigen::VectorXd& z) override { modes_.to_modal(y, z); }
  void to_physical(double, const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> y) override {
    modes_.to_physical(z, y);
  }

  const dynamics::ModalSystem& modes_;
  Functions functions_;
};

}  // namespace pounding::solvers
