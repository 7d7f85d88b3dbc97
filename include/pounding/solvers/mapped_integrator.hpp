#pragma once
// What the modal and the deviation forms share: an Integrator that runs an inner one (CVODE,
// ARKODE) on other coordinates z of the physical state y, mapping y → z at a restart and z → y at
// every step's end and in the interpolant, so the event loop sees physical states only. A form
// says how it maps (to_inner, to_physical) and gives the inner integrator the loop's functions
// seen through the map (a MappedFunctions).

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "pounding/solvers/integrator.hpp"
#include "pounding/solvers/integrator.hpp"

namespace pounding::solvers {

/// The loop's functions in a form's coordinates: size, roots and the linear/free flags are the
/// physical ones'; a form maps rhs, Jacobian and roots.
class MappedFunctions : public OdeFunctions {
 public:
  /// @pre `physical` outlives this.
  explicit MappedFunctions(OdeFunctions& physical) : physical_(physical) {}
  int state_size() const override { return physical_.state_size(); }
  int root_count() const override { return physical_.root_count(); }
  bool is_linear() const override { return physical_.is_linear(); }
  bool is_free_motion() const override { return physical_.is_free_motion(); }

 protected:
  OdeFunctions& physical_;
};

class MappedIntegrator : public Integrator {
 public:
  void restart(double t, const Eigen::VectorXd& y) final;
  void set_max_step(double h_s) final { inner_->set_max_step(h_s); }
  void set_stop_time(double t_s) final { inner_->set_stop_time(t_s); }
  StepOutcome step(double t_final) final;
  const Eigen::VectorXd& state() const final { return state_; }
  void interpolate(double t, Eigen::Ref<Eigen::VectorXd> y) final;
  std::vector<int> roots_found() final { return inner_->roots_found(); }
  IntegratorCounters counters() final { return inner_->counters(); }

 protected:
  explicit MappedIntegrator(const Eigen::VectorXd& y0) : state_(y0), z_(y0.size()) {}
  /// Creates the inner integrator on `functions` (which must outlive it) from (t0, z0).
  void start(const IntegratorFactory& inner, OdeFunctions& functions, double t0, const Eigen::VectorXd& z0) {
    inner_ = inner(functions, t0, z0);
  }
  /// z of the physical state y at t, and y of z.
  virtual void to_inner(double t, const Eigen::VectorXd& y, Eigen::VectorXd& z) = 0;
  virtual void to_physical(double t, const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> y) = 0;

 private:
  std::unique_ptr<Integrator> inner_;
  Eigen::VectorXd state_;  // y at the last step's end
  Eigen::VectorXd z_;      // scratch
};

inline void MappedIntegrator::restart(double t, const Eigen::VectorXd& y) {
  to_inner(t, y, z_);
  inner_->restart(t, z_);
  state_ = y;
}

inline StepOutcome MappedIntegrator::step(double t_final) {
  const StepOutcome outcome = inner_->step(t_final);
  if (outcome.kind != StepKind::failure) to_physical(outcome.t_s, inner_->state(), state_);
  return outcome;
}

inline void MappedIntegrator::interpolate(double t, Eigen::Ref<Eigen::VectorXd> y) {
  inner_->interpolate(t, z_);
  to_physical(t, z_, y);
}

}  // namespace pounding::solvers
