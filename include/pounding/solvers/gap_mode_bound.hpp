#pragma once
// The largest step an event-driven integrator may take without a gap dipping below zero and
// back unseen inside it. A gap is a sum of the buildings' modal responses; only a mode that
// oscillates (damping ratio below 1) and moves some candidate's gap by more than a resolution
// can make that gap's rate change sign twice within a step. So the bound is a fraction of the
// shortest damped period among the modes that, with their present amplitude, move a gap — not
// of the stiffest mode of the structure, whose amplitude under the ground motion can be
// nanometres and whose Rayleigh damping usually makes it overdamped. The drifts of yielding
// columns count as gaps: a yield and an unloading are roots too.

#include <Eigen/Core>
#include <vector>

#include "pounding/dynamics/coupled_system.hpp"

namespace pounding::solvers {

class GapModeBound {
 public:
  /// `resolution_m`: a mode moving no gap by more than this sets no bound (it can hide an
  /// overlap of at most about twice this). `steps_per_period`: the bound is the governing damped
  /// period divided by this. `modes_cutoff_hz` > 0: only modes below it count (a truncated run
  /// takes the others as quasi-static, ExactSettings::modes_cutoff_hz). @pre resolution_m > 0,
  /// steps_per_period ≥ 1, modes_cutoff_hz ≥ 0.
  GapModeBound(const dynamics::CoupledSystem& system, double resolution_m, double steps_per_period,
               double modes_cutoff_hz = 0.0);

  /// The bound (s) in state y = (q, q̇). Each mode's amplitude is its free-vibration amplitude
  /// √(η² + (η̇/ω)²) plus twice its static response to the record's peak acceleration (the most
  /// a step load of that size can add), so a mode quiet now but driven later is not missed
  /// between two evaluations. Never more than the longest period divided by steps_per_period.
  double max_step_s(const Eigen::Ref<const Eigen::VectorXd>& y) const;

  /// The damped period (s) of the mode that set the last bound, 0 when no mode did.
  double governing_period_s() const { return governing_period_s_; }

 private:
  struct OscillatingMode {
    int offset = 0;  // index in q of the building's first DOF
    double omega_rad_s = 0.0;
    double damped_period_s = 0.0;
    Eigen::VectorXd mass_shape;     // M φ over the building's DOFs: η = (Mφ)ᵀ q
    double gap_per_unit_m = 0.0;    // the largest |∂g/∂η| over the candidates and the yielding
                                    // columns' drifts (m per unit η): their roots too need the bound
    double forced_amplitude = 0.0;  // 2 |Γ| max|a_g| / ω² (units of η)
  };

  std::vector<OscillatingMode> modes_;  // shortest damped period first
  Eigen::Index dof_ = 0;                // n: the velocities start at y[n]
  double resolution_m_;
  double steps_per_period_;
  double longest_period_s_ = 0.0;  // of either building (the damped one where it oscillates)
  mutable double governing_period_s_ = 0.0;
};

}  // namespace pounding::solvers
