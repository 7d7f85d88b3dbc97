#pragma once
// CVODE (BDF or Adams) behind the Integrator seam: dense direct linear solver with the
// analytic Jacobian from OdeFunctions, root finding on OdeFunctions::roots (direction −1).

#include <memory>

#include "pounding/solvers/second_order_solver.hpp"
#include "pounding/solvers/sundials_integrator.hpp"

namespace pounding::solvers {

enum class CvodeMethod { bdf, adams };

/// How the Newton systems are solved: `second_order` reduces them to the n×n structural system
/// (SecondOrderLinearSolver); `dense` is SUNDIALS' dense LU of the full 2n×2n matrix. Both are
/// direct solvers with the analytic Jacobian; they refresh the Newton matrix on different
/// schedules, so their runs agree to the integration tolerance.
enum class NewtonSolver { second_order, dense };

struct CvodeSettings {
  CvodeMethod method = CvodeMethod::bdf;
  double rtol = 1e-8;
  double atol = 1e-10;  // every component (m, rad and their rates) unless atol_vector is set
  NewtonSolver newton_solver = NewtonSolver::second_order;
  /// Per state component (CVodeSVtolerances); empty: atol for every one. @pre size 0 or the state's.
  Eigen::VectorXd atol_vector{};
};

class CvodeIntegrator final : public SundialsIntegrator {
 public:
  /// `functions` must outlive the integrator. @throws std::runtime_error if SUNDIALS set-up fails.
  CvodeIntegrator(OdeFunctions& functions, const CvodeSettings& settings, double t0, const Eigen::VectorXd& y0);
  ~CvodeIntegrator() override;
  CvodeIntegrator(const CvodeIntegrator&) = delete;
  CvodeIntegrator& operator=(const CvodeIntegrator&) = delete;

  void restart(double t, const Eigen::VectorXd& y) override;
  void set_max_step(double h_s) override;
  void set_stop_time(double t_s) override;
  StepOutcome step(double t_final) override;
  void interpolate(double t, Eigen::Ref<Eigen::VectorXd> y) override;
  std::vector<int> roots_found() override;
  /// Counts since the last restart (CVodeReInit resets CVODE's own counters).
  IntegratorCounters counters() override;

 private:
  sundials::Matrix matrix_;               // dense Newton solver only
  sundials::LinearSolver linear_solver_;  // dense Newton solver only
  std::unique_ptr<SecondOrderLinearSolver> second_order_;
  long factorizations_at_restart_ = 0;  // counters() counts from the last restart, like CVODE's
  bool stepped_since_restart_ = false;  // CVODE's linear-solver counters reset at the first step
  sundials::IntegratorMemory memory_;   // last: freed first, before the solvers it refers to
};

}  // namespace pounding::solvers
