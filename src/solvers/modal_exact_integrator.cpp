#include "pounding/solvers/modal_exact_integrator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "pounding/solvers/cvode_integrator.hpp"
#include "pounding/solvers/root_finding.hpp"

namespace pounding::solvers {

void start_held_stretch(std::unique_ptr<Integrator>& held, OdeFunctions& functions, const ExactSettings& settings,
                        double t, const Eigen::VectorXd& y, double max_step_s) {
  if (held) {
    held->restart(t, y);
  } else {
    CvodeSettings tight;
    tight.method = CvodeMethod::bdf;  // a stiff storey makes Adams crawl
    tight.rtol = settings.hold_rtol;
    tight.atol = settings.hold_atol;
    tight.atol_vector = settings.hold_atol_vector;
    held = std::make_unique<CvodeIntegrator>(functions, tight, t, y);
  }
  held->set_max_step(max_step_s);
}

ModalExactIntegrator::ModalExactIntegrator(OdeFunctions& functions, const dynamics::CoupledSystem& system, double t0,
                                           const Eigen::VectorXd& y0, ExactSettings settings)
    : functions_(functions), system_(system), settings_(std::move(settings)) {
  const auto count = static_cast<std::size_t>(system.building_count());
  bases_.resize(count);
  mode_offset_.resize(count);
  dof_offset_.resize(count);
  every_building_.assign(count, true);
  needed_.resize(count);
  contact_dofs_.resize(count);
  contact_shapes_.resize(count);
  contact_static_.resize(count);
  contact_q_.resize(count);
  contact_q_rate_.resize(count);
  for (CachedSteps& entry : step_cache_) entry.filled.resize(count);
  for (CachedSteps& entry : probe_cache_) entry.filled.resize(count);
  int modes = 0;
  for (int b = 0; b < system.building_count(); ++b) {
    const int n = system.building(b).dof();
    dof_offset_[b] = system.floor_index(b, 1);
    mode_offset_[b] = modes;
    bases_[b] = model::keep_modes_below(system.modal_basis(b), settings_.modes_cutoff_hz);
    modes += bases_[b].size();
    truncated_ = truncated_ || bases_[b].size() < n;
  }
  omega_.resize(modes);
  damping_ratio_.resize(modes);
  components_ = system.ground_motion().component_count();
  participation_.resize(modes, components_);
  for (int b = 0; b < system_.building_count(); ++b) {
    omega_.segment(mode_offset_[b], bases_[b].size()) = bases_[b].omega_rad_s;
    damping_ratio_.segment(mode_offset_[b], bases_[b].size()) = bases_[b].damping_ratio;
    participation_.middleRows(mode_offset_[b], bases_[b].size()) = bases_[b].participation;
  }
  for (const contact::Candidate& c : system.candidates()) {
    for (int side = 0; side < 2; ++side) {
      for (int k = 0; k < 3; ++k) contact_dofs_[c.pair[side]].push_back(3 * (c.floors[side] - 1) + k);
    }
  }
  for (int b = 0; b < system_.building_count(); ++b) {
    std::vector<int>& dofs = contact_dofs_[b];
    std::sort(dofs.begin(), dofs.end());
    dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
    contact_shapes_[b].resize(static_cast<Eigen::Index>(dofs.size()), bases_[b].size());
    contact_static_[b].resize(static_cast<Eigen::Index>(dofs.size()), components_);
    for (std::size_t r = 0; r < dofs.size(); ++r) {
      contact_shapes_[b].row(static_cast<Eigen::Index>(r)) = bases_[b].shapes.row(dofs[r]);
      contact_static_[b].row(static_cast<Eigen::Index>(r)) = bases_[b].dropped_static_s2.row(dofs[r]);
    }
  }
  contact_y_ = Eigen::VectorXd::Constant(system.state_size(), std::numeric_limits<double>::quiet_NaN());
  for (int b = 0; b < system_.building_count(); ++b) {
    contact_q_[b].resize(contact_shapes_[b].rows());
    contact_q_rate_[b].resize(contact_shapes_[b].rows());
  }
  for (ModalState* modal : {&segment_.start, &end_, &probe_, &probe_b_}) {
    modal->eta.resize(modes);
    modal->eta_rate.resize(modes);
  }
  roots_start_.resize(functions.root_count());
  roots_end_.resize(functions.root_count());
  roots_probe_.resize(functions.root_count());
  restart(t0, y0);
}

void ModalExactIntegrator::restart(double t, const Eigen::VectorXd& y) {
  counters_ = {};  // like CVODE's, the counters run from the last restart
  // Only the system's own free motion decouples into its modes; anything else (a held contact)
  // goes to the numerical integrator.
  held_phase_ = !functions_.is_free_motion();
  if (held_phase_) {
    start_held_stretch(held_, functions_, settings_, t, y, max_step_s_);
    return;
  }
  const int n = system_.dof();
  ModalState& modal = segment_.start;
  for (int b = 0; b < system_.building_count(); ++b) {
    const int size = bases_[b].size(), dofs = system_.building(b).dof();
    modal.eta.segment(mode_offset_[b], size).noalias() = bases_[b].projection * y.segment(dof_offset_[b], dofs);
    modal.eta_rate.segment(mode_offset_[b], size).noalias() =
        bases_[b].projection * y.segment(n + dof_offset_[b], dofs);
  }
  segment_.t_start_s = t;
  end_t_s_ = std::numeric_limits<double>::quiet_NaN();
  state_ = y;
  t_s_ = t;
  roots_at(t, y, roots_start_);
}

void ModalExactIntegrator::set_max_step(double h_s) {
  max_step_s_ = h_s;
  if (held_phase_) held_->set_max_step(h_s);
}

void ModalExactIntegrator::set_stop_time(double t_s) {
  stop_time_s_ = t_s;
  if (held_phase_) held_->set_stop_time(t_s);
}

void ModalExactIntegrator::begin_segment(double t, double t_end) {
  // No step crosses a record sample (they are stop times), so a_g is one straight piece over the
  // step: the one of the record interval holding the step's middle, taken from the samples.
  if (t == end_t_s_) {
    segment_.start = end_;  // the last step's end, already evaluated
  } else if (t != segment_.t_start_s) {
    segment_.start = modal_at(t, probe_);  // on the last segment's load
  }
  segment_.t_start_s = t;
  const excitation::GroundMotion& motion = system_.ground_motion();
  const auto& times = motion.time_s();
  const double middle = 0.5 * (t + t_end);
  const auto after = std::upper_bound(times.begin(), times.end(), middle);
  for (int c = 0; c < components_; ++c) {
    const auto& accel = motion.accel_mps2(c);
    segment_.slope_mps3[c] = 0.0;
    if (after != times.begin() && after != times.end()) {
      const auto k = static_cast<std::size_t>(after - times.begin()) - 1;
      segment_.slope_mps3[c] = (accel[k + 1] - accel[k]) / (times[k + 1] - times[k]);
    }
    segment_.accel_mps2[c] = motion.accel_at(t, c);
  }
}

const std::vector<OscillatorStep>& ModalExactIntegrator::steps_over(StepCache& cache, double tau_s, double same_s,
                                                                    const Buildings& buildings) {
  auto slot = std::find_if(cache.begin(), cache.end(),
                           [&](const CachedSteps& c) { return std::abs(c.tau_s - tau_s) <= same_s; });
  if (slot == cache.end()) {
    slot = cache.end() - 1;  // the least recently used
    slot->tau_s = tau_s;
    slot->filled.assign(slot->filled.size(), false);
    slot->steps.resize(static_cast<std::size_t>(omega_.size()));
  }
  std::rotate(cache.begin(), slot, slot + 1);
  CachedSteps& entry = cache.front();
  for (int b = 0; b < system_.building_count(); ++b) {
    if (!buildings[b] || entry.filled[b]) continue;
    for (int k = mode_offset_[b]; k < mode_offset_[b] + bases_[b].size(); ++k) {
      entry.steps[static_cast<std::size_t>(k)] = oscillator_step(omega_[k], damping_ratio_[k], tau_s);
    }
    entry.filled[b] = true;
  }
  return entry.steps;
}

ModalExactIntegrator::ModalState& ModalExactIntegrator::modal_at(double t, ModalState& modal,
                                                                 const Buildings& buildings, StepCache* cache) {
  const double tau = t - segment_.t_start_s;
  // A step's τ = t_end − t is the difference of two rounded times: the same record interval or
  // step bound comes out a few ulps of t apart from step to step. At step ends those τ count as
  // one length (the state shifts in time by 4 ulps of t, below the recurrence's own round-off),
  // so they share coefficients instead of each costing a sin, cos and exp per mode; probes inside
  // a step (root polishing) get exactly their own τ.
  const double same_s = cache ? 4.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(t), tau) : 0.0;
  const std::vector<OscillatorStep>& steps = steps_over(cache ? *cache : probe_cache_, tau, same_s, buildings);
  modal.accel_mps2 = segment_.accel_mps2 + segment_.slope_mps3 * tau;
  modal.accel_rate_mps3 = segment_.slope_mps3;
  for (int b = 0; b < system_.building_count(); ++b) {
    if (!buildings[b]) {
      modal.eta.segment(mode_offset_[b], bases_[b].size()).setConstant(std::numeric_limits<double>::quiet_NaN());
      modal.eta_rate.segment(mode_offset_[b], bases_[b].size()).setConstant(std::numeric_limits<double>::quiet_NaN());
      continue;
    }
    for (int k = mode_offset_[b]; k < mode_offset_[b] + bases_[b].size(); ++k) {
      const OscillatorStep& s = steps[static_cast<std::size_t>(k)];
      // The modal load is −Σ_c Γ_c a_c(t) = −Σ_c Γ_c (accel_c + slope_c τ).
      Eigen::Vector2d x = s.free * Eigen::Vector2d(segment_.start.eta[k], segment_.start.eta_rate[k]) -
                          participation_(k, 0) * (s.start * segment_.accel_mps2[0] + s.slope * segment_.slope_mps3[0]);
      for (int c = 1; c < components_; ++c) {
        x -= participation_(k, c) * (s.start * segment_.accel_mps2[c] + s.slope * segment_.slope_mps3[c]);
      }
      modal.eta[k] = x[0];
      modal.eta_rate[k] = x[1];
    }
  }
  return modal;
}

void ModalExactIntegrator::physical(const ModalState& modal, Eigen::Ref<Eigen::VectorXd> y) const {
  const int n = system_.dof();
  for (int b = 0; b < system_.building_count(); ++b) {
    const int size = bases_[b].size(), dofs = system_.building(b).dof();
    y.segment(dof_offset_[b], dofs).noalias() = bases_[b].shapes * modal.eta.segment(mode_offset_[b], size);
    y.segment(n + dof_offset_[b], dofs).noalias() = bases_[b].shapes * modal.eta_rate.segment(mode_offset_[b], size);
    if (!truncated_) continue;
    for (int c = 0; c < components_; ++c) {
      y.segment(dof_offset_[b], dofs) += modal.accel_mps2[c] * bases_[b].dropped_static_s2.col(c);
      y.segment(n + dof_offset_[b], dofs) += modal.accel_rate_mps3[c] * bases_[b].dropped_static_s2.col(c);
    }
  }
}

const Eigen::VectorXd& ModalExactIntegrator::contact_state(const ModalState& modal) {
  const int n = system_.dof();
  for (int b = 0; b < system_.building_count(); ++b) {
    const int size = bases_[b].size();
    Eigen::VectorXd &q = contact_q_[b], &q_rate = contact_q_rate_[b];
    q.noalias() = contact_shapes_[b] * modal.eta.segment(mode_offset_[b], size);
    q_rate.noalias() = contact_shapes_[b] * modal.eta_rate.segment(mode_offset_[b], size);
    if (truncated_) {
      for (int c = 0; c < components_; ++c) {
        q += modal.accel_mps2[c] * contact_static_[b].col(c);
        q_rate += modal.accel_rate_mps3[c] * contact_static_[b].col(c);
      }
    }
    for (std::size_t r = 0; r < contact_dofs_[b].size(); ++r) {
      const int i = dof_offset_[b] + contact_dofs_[b][r];
      contact_y_[i] = q[static_cast<Eigen::Index>(r)];
      contact_y_[n + i] = q_rate[static_cast<Eigen::Index>(r)];
    }
  }
  return contact_y_;
}

const Eigen::VectorXd& ModalExactIntegrator::roots_at(double t, const Eigen::VectorXd& y, Eigen::VectorXd& g) {
  functions_.roots(t, y, g);
  ++counters_.root_evaluations;
  if (!g.allFinite()) throw std::logic_error("exact path: a root function reads the state outside the contact floors");
  return g;
}

double ModalExactIntegrator::earliest_root(double t_end, const Eigen::VectorXd& roots_end) {
  // Closing crossings (+ to − or onto 0), the direction the loop asks for. A function whose sign
  // is the same at both ends may still have dipped below zero and recovered inside the step (a
  // slow pair that touched and would have sunk in); then it may be below zero where another
  // function's root ends the step. So the bracket shrinks to each earliest root found and the
  // functions are checked again there, until no new one has crossed.
  double t_root = std::numeric_limits<double>::infinity();
  double t_high = t_end;
  Eigen::VectorXd roots_high = roots_end;
  std::vector<bool> located(static_cast<std::size_t>(roots_end.size()), false);
  for (;;) {
    bool located_new = false;
    for (Eigen::Index i = 0; i < roots_high.size(); ++i) {
      if (located[static_cast<std::size_t>(i)] || !(roots_start_[i] > 0.0 && roots_high[i] <= 0.0)) continue;
      located[static_cast<std::size_t>(i)] = located_new = true;
      const double b =
          find_root([&](double t) { return roots_at(t, contact_state(modal_at(t, probe_)), roots_probe_)[i]; }, t_s_,
                    t_high, roots_start_[i], roots_high[i]);
      t_root = std::min(t_root, b);  // the root function has reached ≤ 0 there
    }
    if (!located_new || !(t_root < t_high)) return t_root;
    t_high = t_root;
    roots_high = roots_at(t_high, contact_state(modal_at(t_high, probe_)), roots_probe_);
  }
}

StepOutcome ModalExactIntegrator::step(double t_final) {
  if (held_phase_) return held_->step(t_final);
  const double t_end = std::min({t_s_ + max_step_s_, stop_time_s_, t_final});
  begin_segment(t_s_, t_end);
  ++counters_.steps;

  end_t_s_ = std::numeric_limits<double>::quiet_NaN();
  const ModalState& end = modal_at(t_end, end_, every_building_, &step_cache_);
  const Eigen::VectorXd& roots_end = roots_at(t_end, contact_state(end), roots_end_);
  const double t_root = earliest_root(t_end, roots_end);

  roots_found_.assign(static_cast<std::size_t>(roots_end.size()), 0);
  if (t_root < std::numeric_limits<double>::infinity()) {
    physical(modal_at(t_root, probe_), state_);
    const Eigen::VectorXd& roots_here = roots_at(t_root, state_, roots_probe_);
    for (Eigen::Index i = 0; i < roots_here.size(); ++i) {
      if (roots_start_[i] > 0.0 && roots_here[i] <= 0.0) roots_found_[static_cast<std::size_t>(i)] = -1;
    }
    t_s_ = t_root;
    roots_start_ = roots_here;
    return {StepKind::root, t_root, {}};
  }
  physical(end, state_);
  end_t_s_ = t_end;
  t_s_ = t_end;
  roots_start_ = roots_end;
  if (t_end != stop_time_s_) return {StepKind::step, t_end, {}};
  // Like SUNDIALS', a stop time applies once: kept, it would make every later step empty.
  stop_time_s_ = std::numeric_limits<double>::infinity();
  return {StepKind::stop_time, t_end, {}};
}

const ModalExactIntegrator::ModalState& ModalExactIntegrator::modal_in_step(double t, ModalState& scratch) {
  if (t == segment_.t_start_s) return segment_.start;
  if (t == end_t_s_) return end_;
  return modal_at(t, scratch);
}

std::optional<StretchEnergy> ModalExactIntegrator::energy_between(double t_a, double t_b) {
  if (held_phase_ || truncated_) return std::nullopt;
  const ModalState &a = modal_in_step(t_a, probe_), &b = modal_in_step(t_b, probe_b_);
  const Eigen::Vector2d accel_a = segment_.accel_mps2 + segment_.slope_mps3 * (t_a - segment_.t_start_s);
  const Eigen::Vector2d accel_b = segment_.accel_mps2 + segment_.slope_mps3 * (t_b - segment_.t_start_s);
  StretchEnergy energy;
  for (Eigen::Index k = 0; k < omega_.size(); ++k) {
    const double w = omega_[k];
    // The modal load p = −Σ_c Γ_c a_c at both ends, and its rate.
    double load_a = -participation_(k, 0) * accel_a[0], load_b = -participation_(k, 0) * accel_b[0],
           load_rate = -participation_(k, 0) * segment_.slope_mps3[0];
    for (int c = 1; c < components_; ++c) {
      load_a -= participation_(k, c) * accel_a[c];
      load_b -= participation_(k, c) * accel_b[c];
      load_rate -= participation_(k, c) * segment_.slope_mps3[c];
    }
    const double d_eta = b.eta[k] - a.eta[k], d_rate = b.eta_rate[k] - a.eta_rate[k];
    // ω² ∫η = ∫p − Δη̇ − 2ζω Δη, from integrating η̈ + 2ζω η̇ + ω² η = p over the stretch.
    const double eta_integral =
        (0.5 * (load_a + load_b) * (t_b - t_a) - d_rate - 2.0 * damping_ratio_[k] * w * d_eta) / (w * w);
    const double input = load_b * b.eta[k] - load_a * a.eta[k] - load_rate * eta_integral;
    const double stored_change = 0.5 * (b.eta_rate[k] * b.eta_rate[k] - a.eta_rate[k] * a.eta_rate[k]) +
                                 0.5 * w * w * (b.eta[k] * b.eta[k] - a.eta[k] * a.eta[k]);
    energy.input_kJ += input;
    energy.damping_kJ += input - stored_change;
  }
  return energy;
}

void ModalExactIntegrator::interpolate(double t, Eigen::Ref<Eigen::VectorXd> y) {
  if (held_phase_) {
    held_->interpolate(t, y);
  } else {
    physical(modal_at(t, probe_), y);
  }
}

void ModalExactIntegrator::interpolate_components(double t, const std::vector<int>& indices,
                                                  Eigen::Ref<Eigen::VectorXd> y) {
  if (held_phase_) return held_->interpolate(t, y);
  const int n = system_.dof();
  // A floor's peak needs its own building's modes only.
  const auto building_of = [&](int dof) {
    return static_cast<int>(std::upper_bound(dof_offset_.begin(), dof_offset_.end(), dof) - dof_offset_.begin()) - 1;
  };
  needed_.assign(needed_.size(), false);
  for (int index : indices) needed_[static_cast<std::size_t>(building_of(index >= n ? index - n : index))] = true;
  const ModalState& modal = modal_at(t, probe_, needed_);
  for (int index : indices) {
    const bool rate = index >= n;
    const int dof = rate ? index - n : index;
    const int b = building_of(dof);
    const int size = bases_[b].size();
    const Eigen::VectorXd& coordinates = rate ? modal.eta_rate : modal.eta;
    y[index] = bases_[b].shapes.row(dof - dof_offset_[b]).dot(coordinates.segment(mode_offset_[b], size));
    if (truncated_) {
      for (int c = 0; c < components_; ++c) {
        y[index] +=
            (rate ? modal.accel_rate_mps3 : modal.accel_mps2)[c] * bases_[b].dropped_static_s2(dof - dof_offset_[b], c);
      }
    }
  }
}

}  // namespace pounding::solvers
