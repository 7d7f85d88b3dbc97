#include "pounding/solvers/energy_balance.hpp"

namespace pounding::solvers {

void EnergyBalance::add_stretch(double t_a, double t_b, const std::function<dynamics::VectorXd(double)>& at,
                                const std::function<double(double, const dynamics::VectorXd&)>& constraint_power,
                                const std::optional<StretchEnergy>& closed_form) {
  if (closed_form) {
    audit_.input_kJ += closed_form->input_kJ;
    audit_.damping_kJ += closed_form->damping_kJ;
    return;
  }
  double piece_start_s = t_a;
  if (split_at_samples_) {
    const excitation::GroundMotion& motion = system_.ground_motion();
    for (auto sample = motion.next_sample_after(t_a); sample && *sample < t_b;
         sample = motion.next_sample_after(*sample)) {
      add_piece(piece_start_s, *sample, at, constraint_power);
      piece_start_s = *sample;
    }
  }
  add_piece(piece_start_s, t_b, at, constraint_power);
}

void EnergyBalance::add_piece(double t_a, double t_b, const std::function<dynamics::VectorXd(double)>& at,
                              const std::function<double(double, const dynamics::VectorXd&)>& constraint_power) {
  const double half = 0.5 * (t_b - t_a), mid = 0.5 * (t_a + t_b);
  for (int k = 0; k < 3; ++k) {
    const double t = mid + half * kGaussNodes[k];
    const dynamics::VectorXd y = at(t);
    audit_.input_kJ += half * kGaussWeights[k] * system_.input_power(t, y);
    audit_.damping_kJ += half * kGaussWeights[k] * system_.damping_power(y);
    audit_.constraint_work_kJ += half * kGaussWeights[k] * constraint_power(t, y);
    if (system_.springs().smooth_count() == 0) continue;
    for (std::size_t j = 0; j < smooth_dissipated_kJ_.size(); ++j) {
      smooth_dissipated_kJ_[j] += half * kGaussWeights[k] * system_.springs().dissipation_power(y, j);
    }
  }
}

EnergyAudit EnergyBalance::close(const dynamics::VectorXd& final_state, const dynamics::SpringStates* springs) const {
  EnergyAudit audit = audit_;
  audit.kinetic_kJ = system_.kinetic_energy(final_state);
  audit.strain_kJ = system_.strain_energy(final_state, springs);
  return audit;
}

}  // namespace pounding::solvers
