#pragma once
// The energy audit's part of the recorder: the work and dissipation integrals of a run (kJ),
// accumulated stretch by stretch and impact by impact, and closed with the final state's
// energies. Shared by every solution path, so their audits compare term by term.

#include <array>
#include <functional>
#include <optional>
#include <vector>

#include "pounding/dynamics/coupled_system.hpp"
#include "pounding/solvers/integrator.hpp"
#include "pounding/solvers/run_result.hpp"

namespace pounding::solvers {

/// 3-point Gauss–Legendre on [−1, 1]: exact for the input power of a degree-5 interpolant times
/// the linear a_g of one record interval.
inline constexpr std::array<double, 3> kGaussNodes{-0.7745966692414834, 0.0, 0.7745966692414834};
inline constexpr std::array<double, 3> kGaussWeights{5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};

class EnergyBalance {
 public:
  /// @pre `system` outlives the balance.
  explicit EnergyBalance(const dynamics::CoupledSystem& system)
      : system_(system), smooth_dissipated_kJ_(system.springs().size(), 0.0) {}

  /// Adds the smooth stretch (t_a, t_b] whose states `at(t)` returns: input and damping from
  /// `closed_form` when given (the integrator's own, for a stretch without contact forces), else
  /// by 3-point Gauss–Legendre on `at`, as is the work of the sustained-contact forces whose
  /// power (kW) `constraint_power(t, y)` gives. @pre t_b > t_a.
  /// The record samples inside (t_a, t_b) of a stretch are where a_g kinks: the quadrature is
  /// split there if the stretches may span samples (the deviation form's steps). Off by default,
  /// as every other path's stretches end at samples or treat a_g as linear between step ends.
  void split_at_samples(bool on) { split_at_samples_ = on; }
  void add_stretch(double t_a, double t_b, const std::function<dynamics::VectorXd(double)>& at,
                   const std::function<double(double, const dynamics::VectorXd&)>& constraint_power,
                   const std::optional<StretchEnergy>& closed_form);
  void add_impact_loss(double energy_kJ) { audit_.impact_loss_kJ += energy_kJ; }
  /// HHT: energy a step's update removed (kJ), see HhtStepper::algorithmic_dissipation.
  void add_algorithmic_dissipation(double energy_kJ) { audit_.algorithmic_dissipation_kJ += energy_kJ; }

  /// Per yielding spring, the energy (kJ) a smooth (Bouc–Wen) one dissipated so far, by the same
  /// quadrature as the damping (YieldingSprings::dissipation_power); 0 for a bilinear one.
  const std::vector<double>& smooth_dissipated_kJ() const { return smooth_dissipated_kJ_; }

  /// The audit, with the kinetic and strain energy of `final_state` (with its yielding springs'
  /// `springs`, CoupledSystem::strain_energy).
  EnergyAudit close(const dynamics::VectorXd& final_state, const dynamics::SpringStates* springs = nullptr) const;

 private:
  /// The Gauss–Legendre sums over [t_a, t_b], on which a_g is linear.
  void add_piece(double t_a, double t_b, const std::function<dynamics::VectorXd(double)>& at,
                 const std::function<double(double, const dynamics::VectorXd&)>& constraint_power);

  const dynamics::CoupledSystem& system_;
  EnergyAudit audit_;
  std::vector<double> smooth_dissipated_kJ_;
  bool split_at_samples_ = false;
};

}  // namespace pounding::solvers
