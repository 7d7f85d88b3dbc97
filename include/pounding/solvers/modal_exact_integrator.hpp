#pragma once
// The exact path in modal form: free flight advanced as the buildings' real modal oscillators.
//
// Each building alone is classically damped (Rayleigh), so in free flight its 3N coordinates
// decouple into damped oscillators under the piecewise-linear ground acceleration
// (model/modal_basis.hpp). Over a step inside one record interval each oscillator moves by the
// exact 2×2 recurrence of modal_propagator.hpp, kept per step length (the common lengths repeat:
// the loop's step bound, the record's Δt and the recorder's Gauss points within them). No
// eigendecomposition at restarts and no complex arithmetic.
//
// The physical state is built on demand: in full (Φη) at step ends and on interpolate(), and for
// the root functions only at the contact floors (their rows of Φ), so locating a crossing costs
// O(modes × contact floors) per evaluation, not O(n²). Roots are found as a
// sign change over each step (the loop bounds steps to a fraction of the shortest period that
// moves a gap, and examines every interior minimum through interpolate()) polished to round-off.
//
// Held stretches are integrated by CVODE BDF at ExactSettings' tolerances (exact_settings.hpp
// says why). The tests check this form against a state-space exact propagator of the whole J
// (tests/support/state_space_exact.hpp).
//
// Truncation (ExactSettings::modes_cutoff_hz > 0, off by default): only each building's modes
// below the cut-off are advanced; the others are taken as their quasi-static response R a_g(t)
// (model::keep_modes_below), added wherever the physical state is formed: q = Φ η + R a_g and
// q̇ = Φ η̇ + R ȧ_g (ȧ_g the record interval's slope, so q̇ is the derivative of q inside a step
// and jumps at record samples). A restart projects the loop's state on the kept modes (η = ΦᵀM q,
// which drops R: ΦᵀM R = 0), so an impulse acts on the kept modes only; held stretches are still
// integrated in full physical form and projected when they end. Not exact: docs/model.md.

#include <Eigen/Core>
#include <array>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "pounding/dynamics/coupled_system.hpp"
#include "pounding/model/modal_basis.hpp"
#include "pounding/solvers/exact_settings.hpp"
#include "pounding/solvers/integrator.hpp"
#include "pounding/solvers/modal_propagator.hpp"

namespace pounding::solvers {

class ModalExactIntegrator final : public Integrator {
 public:
  /// `functions` is the event loop of `system` (run_event_driven's): it is advanced in modal form
  /// while is_free_motion(), by CVODE BDF otherwise; in free motion its root functions must read
  /// y only at the candidates' floors. Both must outlive the integrator.
  /// @throws std::runtime_error if a building's damping is not classical (model::modal_basis), or
  ///   (from roots) if a root function reads a state component outside the contact floors.
  ModalExactIntegrator(OdeFunctions& functions, const dynamics::CoupledSystem& system, double t0,
                       const Eigen::VectorXd& y0, ExactSettings settings = {});

  void restart(double t, const Eigen::VectorXd& y) override;
  void set_max_step(double h_s) override;
  void set_stop_time(double t_s) override;
  StepOutcome step(double t_final) override;
  const Eigen::VectorXd& state() const override { return held_phase_ ? held_->state() : state_; }
  void interpolate(double t, Eigen::Ref<Eigen::VectorXd> y) override;
  void interpolate_components(double t, const std::vector<int>& indices, Eigen::Ref<Eigen::VectorXd> y) override;
  std::vector<int> roots_found() override { return held_phase_ ? held_->roots_found() : roots_found_; }
  IntegratorCounters counters() override { return held_phase_ ? held_->counters() : counters_; }
  /// Free flight: per mode, with the load p = −Γ a_g linear in t, the input ∫p η̇ dt =
  /// [p η] − ṗ ∫η dt, where ∫η dt follows from the oscillator's equation, and the damping's
  /// dissipation is the input less the change of ½(η̇² + ω²η²): exact, no quadrature.
  /// Held stretches and truncated runs (the quasi-static part has no closed form here): empty.
  /// @pre t_a ≤ t_b within the last step.
  std::optional<StretchEnergy> energy_between(double t_a, double t_b) override;

 private:
  /// Modal displacements and rates of both buildings (building 1's modes first).
  struct ModalState {
    Eigen::VectorXd eta, eta_rate;
    /// Each ground-motion component's a_c and ȧ_c there, for the static correction: set by
    /// modal_at (a restart's state is never formed back into a physical one: the loop's y is kept
    /// as it is).
    Eigen::Vector2d accel_mps2 = Eigen::Vector2d::Zero(), accel_rate_mps3 = Eigen::Vector2d::Zero();
  };
  /// The current step: its start, the modal state there, and a_c = accel_c + slope_c·τ over it.
  struct Segment {
    double t_start_s = 0.0;
    ModalState start;
    Eigen::Vector2d accel_mps2 = Eigen::Vector2d::Zero(), slope_mps3 = Eigen::Vector2d::Zero();
  };
  /// Every mode's OscillatorStep over one τ, filled per building as asked for.
  struct CachedSteps {
    double tau_s = -1.0;
    std::vector<bool> filled;  // per building
    std::vector<OscillatorStep> steps;
  };
  /// The most recently used τ first; at step ends a τ within round-off of a kept one reuses it
  /// (see modal_at). Two caches, so the probes inside a step (root polishing, the recorder's
  /// points) do not evict the step lengths that recur from step to step.
  using StepCache = std::array<CachedSteps, 4>;
  using Buildings = std::vector<bool>;  // which buildings' modes to evaluate

  void begin_segment(double t, double t_end);
  /// Every mode's step over τ from `cache` (one within same_s of τ), computed for `buildings` if missing.
  const std::vector<OscillatorStep>& steps_over(StepCache& cache, double tau_s, double same_s,
                                                const Buildings& buildings);
  /// Writes the modes of `buildings` at t within the current step into `modal` (the others
  /// NaN); returns `modal`. `cache`: the step-length cache, for a step's end (null: a probe).
  ModalState& modal_at(double t, ModalState& modal, const Buildings& buildings, StepCache* cache = nullptr);
  /// modal_at for every building.
  ModalState& modal_at(double t, ModalState& modal) { return modal_at(t, modal, every_building_); }
  /// modal_at, reusing the step's start and end states (else written into `scratch`).
  const ModalState& modal_in_step(double t, ModalState& scratch);
  void physical(const ModalState& modal, Eigen::Ref<Eigen::VectorXd> y) const;
  /// y at the contact floors only (the other components NaN), for the root functions.
  const Eigen::VectorXd& contact_state(const ModalState& modal);
  /// The root functions at (t, y) into `g`; returns it.
  const Eigen::VectorXd& roots_at(double t, const Eigen::VectorXd& y, Eigen::VectorXd& g);
  /// The earliest closing crossing in (t_s_, t_end] of any root function, +inf if none; roots_end
  /// are the functions at t_end.
  double earliest_root(double t_end, const Eigen::VectorXd& roots_end);

  OdeFunctions& functions_;
  const dynamics::CoupledSystem& system_;
  ExactSettings settings_;
  std::unique_ptr<Integrator> held_;  // integrates the held stretches
  bool held_phase_ = false;

  // Per building:
  std::vector<model::ModalBasis> bases_;
  std::vector<int> mode_offset_;           // first mode of each building in ModalState
  std::vector<int> dof_offset_;            // first DOF of each building in q
  Buildings every_building_;               // all true
  Eigen::VectorXd omega_, damping_ratio_;  // every mode, building 1's first
  Eigen::MatrixXd participation_;          // Γ: a row per mode as above, a column per ground-motion component
  int components_ = 1;                     // of the ground motion
  // Contact floors' DOFs: per building, the local DOF indices and the matching rows of Φ.
  std::vector<std::vector<int>> contact_dofs_;
  std::vector<Eigen::MatrixXd> contact_shapes_;
  std::vector<Eigen::MatrixXd> contact_static_;  // the same rows of the static correction R (a column per component)
  bool truncated_ = false;                       // some mode is left out
  Eigen::VectorXd contact_y_;                    // NaN outside the contact floors
  StepCache step_cache_, probe_cache_;
  // Scratch, sized once, so that a step allocates nothing.
  std::vector<Eigen::VectorXd> contact_q_, contact_q_rate_;
  Buildings needed_;  // interpolate_components: the buildings its indices read
  ModalState probe_, probe_b_;
  Eigen::VectorXd roots_end_, roots_probe_;

  Segment segment_;
  ModalState end_;                                             // the modal state at the last step's end ...
  double end_t_s_ = std::numeric_limits<double>::quiet_NaN();  // ... at this time (NaN: none)
  Eigen::VectorXd state_;
  Eigen::VectorXd roots_start_;
  std::vector<int> roots_found_;
  double t_s_ = 0.0;
  double max_step_s_ = 0.01;
  double stop_time_s_ = std::numeric_limits<double>::infinity();
  IntegratorCounters counters_;
};

}  // namespace pounding::solvers
