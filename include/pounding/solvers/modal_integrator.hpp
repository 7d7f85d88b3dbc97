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
#include "pounding/solvers/event_driven.hpp"
#include "pounding/solvers/integrator.hpp"

namespace pounding::solvers {

class ModalIntegrator final : public Integrator {
 public:
  /// `modes`, `physical` and `inner` must outlive the integrator; `inner` is called once, with
  /// the modal functions and z₀ = T⁻¹ y₀ (its tolerances apply to z: ModalSystem::atol).
  ModalIntegrator(const dynamics::ModalSystem& modes, OdeFunctions& physical, const IntegratorFactory& inner,
                  double t0, const Eigen::VectorXd& y0);

  void restart(double t, const Eigen::VectorXd& y) override;
  void set_max_step(double h_s) override { inner_->set_max_step(h_s); }
  void set_stop_time(double t_s) override { inner_->set_stop_time(t_s); }
  StepOutcome step(double t_final) override;
  const Eigen::VectorXd& state() const override { return state_; }
  void interpolate(double t, Eigen::Ref<Eigen::VectorXd> y) override;
  std::vector<int> roots_found() override { return inner_->roots_found(); }
  IntegratorCounters counters() override { return inner_->counters(); }

 private:
  /// The loop's functions seen in modal coordinates.
  class Functions final : public OdeFunctions {
   public:
    Functions(const dynamics::ModalSystem& modes, OdeFunctions& physical);
    int state_size() const override { return physical_.state_size(); }
    int root_count() const override { return physical_.root_count(); }
    bool is_linear() const override { return physical_.is_linear(); }
    bool is_free_motion() const override { return physical_.is_free_motion(); }
    void rhs(double t, const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> z_dot) override;
    void jacobian(double t, const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::MatrixXd> jac) override;
    void roots(double t, const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g) override;

   private:
    const dynamics::ModalSystem& modes_;
    OdeFunctions& physical_;
    Eigen::VectorXd y_, y_dot_;      // scratch: the physical state and rate
    Eigen::MatrixXd jacobian_;       // scratch: the physical Jacobian (contact phases only)
  };

  const dynamics::ModalSystem& modes_;
  Functions functions_;
  std::unique_ptr<Integrator> inner_;
  Eigen::VectorXd state_;  // y at the last step's end
  Eigen::VectorXd z_;      // scratch
};

}  // namespace pounding::solvers
