#pragma once
// The exact path's settings (analysis: the `exact` method's hold_rtol and modes_cutoff_hz) and its
// held stretches. Free flight is exact (modal_exact_integrator.hpp). A held contact is not
// linear: the contact geometry rotates with the slabs, and linearising it (once, or at every
// step) leaves errors of 1e−4 … 1e−6 s in the impact times after a hold. Held stretches are
// therefore integrated by CVODE (BDF: a stiff storey makes Adams crawl) at a tight tolerance, the
// only part of the path that is not exact; its error is what the study's reference error estimate
// measures.

#include <Eigen/Core>
#include <memory>

#include "pounding/solvers/integrator.hpp"

namespace pounding::solvers {

/// Tolerances of the held stretches, the part of the exact path that is integrated numerically,
/// and the modal form's truncation.
struct ExactSettings {
  double hold_rtol = 1e-12;
  double hold_atol = 1e-14;            // every component (m, rad and their rates) unless hold_atol_vector is set
  Eigen::VectorXd hold_atol_vector{};  // per state component; empty: hold_atol for every one
  /// ModalExactIntegrator only: keep each building's modes below this frequency (Hz), the rest as
  /// their quasi-static response (model::keep_modes_below). 0: every mode, the exact path.
  double modes_cutoff_hz = 0.0;
};

/// Starts a held stretch at (t, y) with at most `max_step_s` per step: restarts `held`, or first
/// creates it as CVODE BDF at `settings`' tolerances. Both forms of the exact path call it.
void start_held_stretch(std::unique_ptr<Integrator>& held, OdeFunctions& functions, const ExactSettings& settings,
                        double t, const Eigen::VectorXd& y, double max_step_s);

}  // namespace pounding::solvers
