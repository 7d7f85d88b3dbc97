#pragma once
// The form "deviation": an integrator of z = y − y_p(t), where y_p is the contact-free response
// from the run's start, propagated exactly over the record's linear pieces (FreeResponse). The
// record's kinks at every sample are in y_p, so what the inner integrator (CVODE, ARKODE) sees
// is smooth: z ≡ 0 until the first contact, afterwards the homogeneous motion the impacts and
// contact forces started, ż = A z (+ contact terms). BDF's steps then no longer shrink at every
// sample of a dense record, and the loop lets them cross the samples (steps_across_samples).
// The event loop hands it and reads from it physical states, as from the other forms. Needs
// classical damping (Rayleigh damping is), as the modal form does.

#include <memory>
#include <vector>

#include "pounding/dynamics/modal_system.hpp"
#include "pounding/solvers/mapped_integrator.hpp"

namespace pounding::solvers {

/// The free response y_p(t) of a system from (t0, y0) under its whole record, exact to
/// round-off at any t in the record: each mode advanced over each linear piece of a_g by
/// oscillator_step (modal_propagator.hpp), the modal state kept at every sample.
class FreeResponse {
 public:
  /// @pre `modes` outlives this; t0 is the record's start or later.
  FreeResponse(const dynamics::ModalSystem& modes, double t0, const Eigen::VectorXd& y0);
  /// y_p(t) (physical, as the system's state), t ∈ [t0, end of record].
  void at(double t, Eigen::VectorXd& y) const;
  /// y_p(t) and ẏ_p(t).
  void at(double t, Eigen::VectorXd& y, Eigen::VectorXd& y_dot) const;

 private:
  /// Each ground-motion component's acceleration at t (m/s²; the second 0 for one component).
  Eigen::Vector2d ground_accel(double t) const;
  /// Mode i's load Σ_c Γ_ic a_c (a_c: `accel`).
  double modal_load(int i, const Eigen::Vector2d& accel) const;
  /// Mode i's (η, η̇) advanced by tau from `from` (a modal state) under a_c = a_start_c + slope_c·s.
  Eigen::Vector2d advance(int i, const Eigen::VectorXd& from, double tau, const Eigen::Vector2d& a_start,
                          const Eigen::Vector2d& slope) const;
  /// The modal state (η, η̇) and its rate at t, into z and z_dot.
  void modal_at(double t, Eigen::VectorXd& z, Eigen::VectorXd& z_dot) const;

  const dynamics::ModalSystem& modes_;
  std::vector<double> times_;            // t0, then every record sample after it
  std::vector<Eigen::VectorXd> states_;  // (η, η̇) at each of times_
  Eigen::VectorXd damping_ratio_;
  mutable Eigen::VectorXd z_, z_dot_;  // scratch
};

class DeviationIntegrator final : public MappedIntegrator {
 public:
  /// `modes`, `physical` and `inner` must outlive the integrator; `inner` is called once, with
  /// the deviation's functions and z₀ = 0 (its tolerances apply to z, in the units of y).
  DeviationIntegrator(const dynamics::ModalSystem& modes, OdeFunctions& physical, const IntegratorFactory& inner,
                      double t0, const Eigen::VectorXd& y0);
  bool steps_across_samples() const override { return true; }

 private:
  /// The loop's functions seen through z = y − y_p(t).
  class Functions final : public MappedFunctions {
   public:
    Functions(const FreeResponse& free, OdeFunctions& physical);
    void rhs(double t, const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> z_dot) override;
    void jacobian(double t, const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::MatrixXd> jac) override;
    bool acceleration_jacobian(double t, const Eigen::Ref<const Eigen::VectorXd>& z,
                               Eigen::SparseMatrix<double>& rows) override;
    void roots(double t, const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g) override;

   private:
    /// y = y_p(t) + z into y_ (only roots, Jacobians and rhs need y; rhs also ẏ_p, in yp_dot_).
    void physical_state(double t, const Eigen::Ref<const Eigen::VectorXd>& z);
    const FreeResponse& free_;
    Eigen::VectorXd y_, yp_, yp_dot_, y_dot_;  // scratch
  };

  void to_inner(double t, const Eigen::VectorXd& y, Eigen::VectorXd& z) override;
  void to_physical(double t, const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> y) override;

  FreeResponse free_;
  Functions functions_;
  Eigen::VectorXd yp_;  // scratch
};

}  // namespace pounding::solvers
