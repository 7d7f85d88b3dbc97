#include "pounding/solvers/event_driven.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <numbers>
#include <optional>

#include "law_events.hpp"
#include "pounding/contact/impact.hpp"
#include "pounding/input_error.hpp"
#include "pounding/solvers/contact_states.hpp"
#include "pounding/solvers/event_step_bound.hpp"
#include "pounding/solvers/floor_impacts.hpp"
#include "pounding/solvers/missed_contacts.hpp"
#include "pounding/solvers/recorder.hpp"
#include "pounding/solvers/simulator.hpp"
#include "pounding/solvers/yield_states.hpp"

namespace pounding::solvers {

std::string_view to_string(RunStatus status) {
  switch (status) {
    case RunStatus::completed: return "completed";
    case RunStatus::solver_failure: return "solver_failure";
    case RunStatus::event_limit: return "event_limit";
    case RunStatus::step_limit: return "step_limit";
    case RunStatus::unresolved_overlap: return "unresolved_overlap";
    case RunStatus::time_limit: return "time_limit";
    case RunStatus::interrupted: return "interrupted";
    case RunStatus::non_finite: return "non_finite";
    case RunStatus::collapse: return "collapse";
  }
  return "?";
}

void EventOptions::validate() const {
  auto positive = [](double value, const char* field) {
    if (!(value > 0.0) || !std::isfinite(value)) throw InputError(field, format_value(value), "must be positive");
  };
  require_range("restitution", restitution,
                contact::kRestitutionRange);  // also for programs that call the solver directly
  positive(contact_tolerance_m, "contact_tolerance_m");
  positive(reopen_gap_m, "reopen_gap_m");
  positive(overlap_allowance_m, "overlap_allowance_m");
  positive(hold_velocity_mps, "hold_velocity_mps");
  positive(hold_height_m, "hold_height_m");
  positive(max_events_per_s, "max_events_per_s");
  positive(history_interval_s, "history_interval_s");
  if (max_step_s < 0.0)
    throw InputError("max_step_s", format_value(max_step_s), "must be zero (automatic) or positive");
  if (!(modes_cutoff_hz >= 0.0) || !std::isfinite(modes_cutoff_hz)) {
    throw InputError("modes_cutoff_hz", format_value(modes_cutoff_hz), "must be zero (every mode) or positive");
  }
  if (!(steps_per_period >= 1.0) || !std::isfinite(steps_per_period)) {
    throw InputError("steps_per_period", format_value(steps_per_period), "must be at least 1");
  }
  if (max_steps < 1) throw InputError("max_steps", std::to_string(max_steps), "must be positive");
  if (law != contact::ContactLaw::impulse) positive(contact_stiffness, "contact_stiffness");
  if (contact::refuses_plastic(law) && restitution == 0.0) {
    throw InputError(
        "restitution", "0",
        fmt::format("must be positive for the {} law (its damping is infinite at 0)", contact::to_string(law)));
  }
  budget.validate();
  if (initial_state.size() != 0 && !initial_state.allFinite()) {
    throw InputError("initial_state", "", "must be finite");
  }
}

namespace {

using dynamics::VectorXd;

/// Per candidate, the components of y its gap reads: (u, v, φ) of its floors and their rates.
std::vector<std::vector<int>> gap_components(const dynamics::CoupledSystem& system) {
  std::vector<std::vector<int>> components;
  const VectorXd rest = VectorXd::Zero(system.state_size());
  for (std::size_t i = 0; i < system.candidates().size(); ++i) {
    std::vector<int>& own = components.emplace_back();
    for (const auto& block : system.row_blocks(system.candidates()[i], system.gap(rest, i))) {
      for (int k = 0; k < 3; ++k) {
        own.push_back(block.first + k);
        own.push_back(system.dof() + block.first + k);
      }
    }
  }
  return components;
}

/// Every building's name, by scene index.
std::vector<std::string> building_names(const dynamics::CoupledSystem& system) {
  std::vector<std::string> names;
  for (int b = 0; b < system.building_count(); ++b) names.push_back(system.building(b).definition.name);
  return names;
}

/// Every building's slab outline size, by scene index (contact::link_corners).
std::vector<std::size_t> outline_sizes(const dynamics::CoupledSystem& system) {
  std::vector<std::size_t> sizes;
  for (int b = 0; b < system.building_count(); ++b) sizes.push_back(system.building(b).definition.slab.size());
  return sizes;
}

class EventDrivenSystem final : public HybridSystem {
 public:
  EventDrivenSystem(const dynamics::CoupledSystem& system, const EventOptions& options)
      : system_(system),
        options_(options),
        count_(system.candidates().size()),
        states_(count_, options.overlap_allowance_m),
        cover_(system.candidates(), contact::link_corners(system.candidates(), outline_sizes(system)),
               options.contact_tolerance_m),
        yields_(system.springs(), options.max_events_per_s, /*locate_shear_failures=*/true),
        building_names_(building_names(system)),
        witnesses_(count_, yields_.size(), watches_struck_columns(system, options)),
        gap_components_(gap_components(system)),
        recorder_(system, recorded_dynamics(), {options.history_floors, options.history_other_floors},
                  options.history_interval_s, options.outputs, options.sink),
        law_(make_law_events()) {
    recorder_.set_spring_states(yields_.states());
  }

  int state_size() const override { return system_.state_size(); }
  int root_count() const override { return witnesses_.size(); }
  // A yielding column changes the Jacobian at its events, and its slip force moves with q.
  bool is_linear() const override { return is_free_motion() && yields_.empty(); }
  // Bouc–Wen springs never leave the motion free: their z moves with it.
  bool is_free_motion() const override {
    return states_.free_motion() && !yields_.any_yielding() && system_.springs().smooth_count() == 0;
  }

  void rhs(double t, const Eigen::Ref<const VectorXd>& y, Eigen::Ref<VectorXd> y_dot) override {
    forces_.resize(static_cast<Eigen::Index>(states_.held().size()));
    system_.constrained_rhs(t, y, states_.held(), y_dot, forces_, yields_.states());
    law_->add_forces(y, y_dot);
  }

  void jacobian(double, const Eigen::Ref<const VectorXd>& y, Eigen::Ref<Eigen::MatrixXd> jac) override {
    Eigen::SparseMatrix<double> rows;
    acceleration_rows(y, rows);
    system_.full_jacobian(y, rows, jac, states_.held());
  }

  bool acceleration_jacobian(double, const Eigen::Ref<const VectorXd>& y, Eigen::SparseMatrix<double>& rows) override {
    acceleration_rows(y, rows);
    return true;
  }
  int extra_state_count() const override { return system_.springs().smooth_count(); }
  void extra_state_jacobian(double, const Eigen::Ref<const VectorXd>& y, Eigen::SparseMatrix<double>& accel_by_w,
                            Eigen::SparseMatrix<double>& w_rate_by_velocity, VectorXd& w_rate_by_w) override {
    system_.smooth_jacobian(y, states_.held(), accel_by_w, w_rate_by_velocity, w_rate_by_w);
  }

  // The witnesses (contact_states.hpp, Witness): the gap roots of armed and masked pairs here,
  // the rest from the law's contacts.
  void roots(double t, const Eigen::Ref<const VectorXd>& y, Eigen::Ref<VectorXd> g) override {
    g.setConstant(1.0);
    for (std::size_t i = 0; i < count_; ++i) {
      if (cover_.live(i)) {
        g[witnesses_.at(Witness::gap, i)] = states_.gap_witness(i, system_.gap(y, i).gap_m);
      }
    }
    law_->write_witnesses(t, y, witnesses_, g);
    if (yields_.empty()) return;
    for (std::size_t j = 0; j < yields_.size(); ++j) g[witnesses_.at_spring(j)] = yields_.witness(y, j);
  }

  // The phases (simulator.hpp), each as the event-driven run takes it (event_driven.hpp).
  void start(double t0, VectorXd& y) override;
  void prepare(Integrator& integrator) override;
  void begin_phase(double t, const VectorXd& y, Integrator& integrator) override;
  std::optional<HiddenEvent> examine_step(double t_a, double t_b, const VectorXd& y_b, Integrator& integrator) override;
  void record(double t_a, double t_b, const VectorXd& y_b, Integrator& integrator) override;
  bool on_event(double t, VectorXd& y, const EventCause& cause) override;
  void after_step(double t, const VectorXd& y, Integrator& integrator) override;
  bool stopped() const override { return stop_; }

  RunResult run(const IntegratorFactory& make_integrator, const std::string& method);

 private:
  /// [∂q̈/∂q, ∂q̈/∂q̇] (n × 2n) of the present phase: held contacts, the law's forces, the springs.
  void acceleration_rows(const Eigen::Ref<const VectorXd>& y, Eigen::SparseMatrix<double>& rows) const {
    system_.constrained_acceleration_jacobian(y, states_.held(), rows, yields_.states());
    law_->add_force_jacobian(y, rows);
  }
  std::unique_ptr<LawEvents> make_law_events() {
    const EventContext context{system_,
                               options_,
                               states_,
                               cover_,
                               recorder_,
                               result_,
                               yields_.states(),
                               [this](double t, const VectorXd& y, Eigen::Ref<VectorXd> y_dot) { rhs(t, y, y_dot); },
                               [this](std::size_t j) { return yields_.failed_in_shear(j); },
                               [this](std::size_t j, double t, const VectorXd& y) { yields_.lose_stiffness(j, t, y); }};
    return options_.law == contact::ContactLaw::impulse ? make_impulse_events(context) : make_compliant_events(context);
  }
  /// For the recorder: this rhs, the law's contact forces, and whether none acts (is_free_motion).
  RecordedDynamics recorded_dynamics() {
    return {.derivative = [this](double t, const VectorXd& y, Eigen::Ref<VectorXd> y_dot) { rhs(t, y, y_dot); },
            .contact_forces = [this](double t, const VectorXd& y) { return law_->contact_forces(t, y); },
            .free_motion = [this] { return is_free_motion(); }};
  }

  /// scan_missed_contacts over the step (t_a, t_b], whose ends' gaps are prev_gaps_ and gaps_;
  /// its grazes become touches.
  std::optional<MissedContact> missed_contact(double t_a, double t_b, Integrator& integrator);
  /// Notes the overlap of every open, uncovered pair whose vertex is inside the other slab at
  /// (t, y), whose gaps are gaps_.
  void note_overlaps(double t, const VectorXd& y);
  /// The event at t: counted, handed to the law, recorded.
  void event(double t, VectorXd& y, const WitnessLayout::Crossed& crossed);
  /// `gaps`: every candidate's gap in state y.
  void update_step_bound(double t, const VectorXd& y, const std::vector<contact::GapState>& gaps,
                         Integrator& integrator);
  /// True when options_.modes_cutoff_hz leaves out some mode of a building.
  bool drops_modes() const {
    const double cutoff_hz = options_.modes_cutoff_hz;
    if (cutoff_hz == 0.0) return false;
    for (int b = 0; b < system_.building_count(); ++b) {
      if (system_.building(b).modes.back().omega_rad_s / (2.0 * std::numbers::pi) >= cutoff_hz) return true;
    }
    return false;
  }
  /// Every candidate's gap in state y, into `gaps`.
  void evaluate_gaps(const VectorXd& y, std::vector<contact::GapState>& gaps) const {
    gaps.resize(count_);
    for (std::size_t i = 0; i < count_; ++i) gaps[i] = system_.gap(y, i);
  }
  /// Adds to `crossed` the live armed candidates that went through zero at the event's instant by
  /// a rounding (g = −5e-16 m), closing, whose root no integrator or scan flagged: after the
  /// restart they would start below zero, where their roots can no longer fire. `gaps`: every
  /// candidate's gap at the event.
  void add_rounded_through(const std::vector<contact::GapState>& gaps, WitnessLayout::Crossed& crossed) const;
  /// Ends a completed run as unresolved_overlap if a pair not held sank past the touch band.
  void report_overlap();
  void count_event(double t);
  /// The yielding springs' branch changes at an event at (t, y) (YieldStates::switch_branches).
  void switch_springs(double t, const VectorXd& y);
  /// Ends the run if its yielding columns call for it at (t, y) (YieldStates::stop: collapse,
  /// chattering).
  void check_columns(double t, const VectorXd& y);
  /// The integrator's counters summed over the run, and its restarts, into the statistics.
  void take_counters(const SimulatorOutcome& outcome);

  const dynamics::CoupledSystem& system_;
  const EventOptions& options_;
  std::size_t count_;
  ContactStates states_;
  CornerCover cover_;  // covered and live candidates, updated at every check
  YieldStates yields_;
  std::vector<std::string> building_names_;  // for the columns' messages
  WitnessLayout witnesses_;
  std::vector<std::vector<int>> gap_components_;  // per candidate, the components of y its gap reads
  VectorXd forces_;
  Recorder recorder_;
  RunResult result_;
  std::unique_ptr<LawEvents> law_;  // the contact law's policy; after what it refers to
  std::optional<EventStepBound> step_bound_;
  double current_max_step_s_ = 0.0;
  // Every candidate's gap at the step's start and at its end: evaluated once per step for the
  // checks that read them all (each gap takes the slabs' exact rotation).
  std::vector<contact::GapState> prev_gaps_, gaps_;
  std::deque<double> recent_events_;
  bool stop_ = false;
};

void EventDrivenSystem::begin_phase(double t, const VectorXd& y, Integrator& integrator) {
  current_max_step_s_ = -1.0;  // force update_step_bound to hand the integrator its bound
  evaluate_gaps(y, prev_gaps_);
  states_.watch_arrivals(prev_gaps_, [&](std::size_t i) { return law_->meets(i, y, prev_gaps_[i]); });
  cover_.update(prev_gaps_, states_);
  update_step_bound(t, y, prev_gaps_, integrator);
}

void EventDrivenSystem::count_event(double t) {
  ++result_.statistics.events;
  recent_events_.push_back(t);
  while (!recent_events_.empty() && recent_events_.front() < t - 1.0) recent_events_.pop_front();
  if (static_cast<double>(recent_events_.size()) > options_.max_events_per_s) {
    result_.status = RunStatus::event_limit;
    result_.status_detail =
        fmt::format("more than {} events within one simulated second before t = {} s", options_.max_events_per_s, t);
    stop_ = true;
  }
}

void EventDrivenSystem::start(double t, VectorXd& y) {
  recorder_.sample(t, y);
  // CVODE does not report roots at the initial time: contacts that exist at rest (a zero gap)
  // are handled here as an event.
  std::vector<std::size_t> touching;
  for (std::size_t i = 0; i < count_; ++i) {
    const contact::GapState s = system_.gap(y, i);
    if (s.gap_m <= options_.contact_tolerance_m && s.on_segment()) touching.push_back(i);
  }
  if (!touching.empty()) event(t, y, {.gap = touching});
  switch_springs(t, y);  // a column started beyond its yield drift (an initial state) yields at once
  // A truncated run's dropped modes move as R a_g, which GapClearance does not bound.
  if (options_.max_step_s == 0.0 && options_.clearance_steps && options_.law == contact::ContactLaw::impulse &&
      !drops_modes()) {
    // Throws, as the exact path does, if a building's damping is not classical. Its steps may
    // span whole record intervals: the peaks are located on quarter periods.
    recorder_.set_peak_step(step_bound_->enable_clearance() / 4.0);
  }
}

void EventDrivenSystem::prepare(Integrator& integrator) {
  if (!integrator.steps_across_samples()) return;
  // Its steps are bounded by the modes that move a gap only: the peaks of the others are
  // located on pieces no longer than the record's spacing, as the physical form's steps are.
  recorder_.split_energy_at_samples(true);
  recorder_.set_peak_step(system_.ground_motion().sample_spacing_s());
}

void EventDrivenSystem::event(double t, VectorXd& y, const WitnessLayout::Crossed& crossed) {
  if (crossed.contacts()) {
    count_event(t);
    law_->on_event(t, y, crossed);
  }
  // After the law: an impulse can turn a yielding column's drift rate, which unloads it.
  switch_springs(t, y);
  recorder_.sample(t, y);
}

void EventDrivenSystem::switch_springs(double t, const VectorXd& y) {
  if (yields_.empty()) return;
  VectorXd y_dot(system_.state_size());
  rhs(t, y, y_dot);
  result_.statistics.yield_events += yields_.switch_branches(t, y, y_dot);
  check_columns(t, y);
}

void EventDrivenSystem::check_columns(double t, const VectorXd& y) {
  if (yields_.empty()) return;
  std::optional<YieldingStop> stop = yields_.stop(t, y, building_names_);
  if (!stop || stop_) return;
  result_.status = stop->status;
  result_.status_detail = std::move(stop->detail);
  stop_ = true;
}

std::optional<MissedContact> EventDrivenSystem::missed_contact(double t_a, double t_b, Integrator& integrator) {
  if (t_b <= step_bound_->open_until_s()) return std::nullopt;  // every gap stayed above the touch band
  // The step's interpolant, evaluated only in the components a candidate's gap reads.
  class Interpolant final : public StepGaps {
   public:
    Interpolant(EventDrivenSystem& run, Integrator& integrator)
        : run_(run), integrator_(integrator), at_(run.system_.state_size()) {}
    contact::GapState at(std::size_t i, double t_s) override {
      integrator_.interpolate_components(t_s, run_.gap_components_[i], at_);
      return run_.system_.gap(at_, i);
    }
    double rate_round_off_mps(std::size_t i) override { return run_.system_.gap_rate_round_off_mps(at_, i); }
    double depth_inside_m(std::size_t i) override {
      return run_.system_.depth_inside_m(at_, i, run_.system_.gap(at_, i));
    }

   private:
    EventDrivenSystem& run_;
    Integrator& integrator_;
    VectorXd at_;
  } path(*this, integrator);
  std::vector<Graze> grazes;
  const std::optional<MissedContact> missed = scan_missed_contacts(
      states_, path, t_a, t_b, prev_gaps_, gaps_,
      {.contact_tolerance_m = options_.contact_tolerance_m, .overlap_allowance_m = options_.overlap_allowance_m},
      grazes, &cover_);
  for (const Graze& graze : grazes)
    result_.touches.push_back(touch_record(system_, graze.t_s, graze.candidate, graze.gap));
  return missed;
}

void EventDrivenSystem::update_step_bound(double t, const VectorXd& y, const std::vector<contact::GapState>& gaps,
                                          Integrator& integrator) {
  VectorXd y_dot;
  auto gap_acceleration = [&](std::size_t i) {
    if (y_dot.size() == 0) {
      y_dot.resize(system_.state_size());
      rhs(t, y, y_dot);
    }
    return system_.gap_acceleration(y, y_dot, i);
  };
  const double bound = step_bound_->max_step_s(t, y, gaps, states_, cover_, gap_acceleration);
  if (bound != current_max_step_s_) {
    integrator.set_max_step(bound);
    current_max_step_s_ = bound;
  }
}

void EventDrivenSystem::note_overlaps(double t, const VectorXd& y) {
  for (std::size_t i = 0; i < count_; ++i) {
    // A held gap's drift is reported with its hold, a compliant one's penetration is the law's,
    // a covered one's point is in a contact in progress.
    if (states_.open(i) && !cover_.covered(i) && gaps_[i].on_segment()) law_->note_overlap(t, y, i, gaps_[i]);
  }
}

void EventDrivenSystem::after_step(double t, const VectorXd& y, Integrator& integrator) {
  note_overlaps(t, y);
  check_columns(t, y);
  states_.rearm(gaps_, [&](std::size_t i) { return law_->meets(i, y, gaps_[i]); });
  cover_.update(gaps_, states_);
  law_->after_step(t, y);
  update_step_bound(t, y, gaps_, integrator);
  std::swap(prev_gaps_, gaps_);
}

std::optional<HiddenEvent> EventDrivenSystem::examine_step(double t_a, double t_b, const VectorXd& y_b,
                                                           Integrator& integrator) {
  evaluate_gaps(y_b, gaps_);
  const std::optional<MissedContact> hidden = missed_contact(t_a, t_b, integrator);
  if (!hidden) return std::nullopt;
  return HiddenEvent{hidden->t_s, hidden->candidate};
}

void EventDrivenSystem::record(double t_a, double t_b, const VectorXd& y_b, Integrator& integrator) {
  auto interpolated = [&](double time) {
    VectorXd state(system_.state_size());
    integrator.interpolate(time, state);
    return state;
  };
  auto power = [&](double time, const VectorXd& state) { return law_->constraint_power(time, state); };
  auto interpolate = [&](double time, VectorXd& state) { integrator.interpolate(time, state); };
  auto components = [&](double time, const std::vector<int>& indices, VectorXd& state) {
    integrator.interpolate_components(time, indices, state);
  };
  recorder_.advance(t_a, t_b, y_b, interpolated, power, integrator.energy_between(t_a, t_b), components);
  law_->integrate(t_a, t_b, y_b, interpolate);
}

bool EventDrivenSystem::on_event(double t, VectorXd& y, const EventCause& cause) {
  WitnessLayout::Crossed crossed;
  if (cause.hidden) {  // a contact the step's interpolant showed: the gaps at its instant
    ++result_.statistics.interpolant_events;
    crossed.gap = {*cause.hidden};
    std::vector<contact::GapState> at_event;
    evaluate_gaps(y, at_event);
    add_rounded_through(at_event, crossed);
  } else {  // roots at the step's end, whose gaps examine_step evaluated
    crossed = witnesses_.crossed(cause.root_flags);
    add_rounded_through(gaps_, crossed);
  }
  event(t, y, crossed);
  return true;  // velocities or contact states changed: the integrator restarts
}

void EventDrivenSystem::add_rounded_through(const std::vector<contact::GapState>& gaps,
                                            WitnessLayout::Crossed& crossed) const {
  for (std::size_t i = 0; i < count_; ++i) {
    const contact::GapState& s = gaps[i];
    const bool rounded_through = s.gap_m <= 0.0 && s.gap_m > -options_.overlap_allowance_m;
    if (rounded_through && cover_.live(i) && states_.is(i, ContactMode::armed) && s.on_segment() &&
        s.gap_rate_mps < 0.0 && std::find(crossed.gap.begin(), crossed.gap.end(), i) == crossed.gap.end()) {
      crossed.gap.push_back(i);
    }
  }
  std::sort(crossed.gap.begin(), crossed.gap.end());
}

void EventDrivenSystem::report_overlap() {
  // Every closing is located before the pair sinks in; an overlap deeper than the touch band means
  // a contact was passed over and everything after it is off, so the run must not say completed.
  const SolverStatistics& stats = result_.statistics;
  if (result_.status != RunStatus::completed || !(stats.max_interpenetration_m > options_.contact_tolerance_m)) return;
  const contact::Candidate& c = system_.candidates()[static_cast<std::size_t>(stats.max_interpenetration_candidate)];
  result_.status = RunStatus::unresolved_overlap;
  // The touch band is the event loop's own, fixed (not hht's contact_tolerance_m setting).
  result_.status_detail = fmt::format(
      "{} lay {:.3g} m inside the other slab at {:.6f} s, level {}, with no contact holding it: deeper than the "
      "event loop's {:g} m touch band, so a contact was passed over before it (docs/model.md §7)",
      contact::describe(c), stats.max_interpenetration_m, stats.max_interpenetration_t_s, c.level,
      options_.contact_tolerance_m);
}

RunResult EventDrivenSystem::run(const IntegratorFactory& make_integrator, const std::string& method) {
  const auto clock_start = std::chrono::steady_clock::now();
  result_.method = method;
  const double t0 = system_.ground_motion().start_s();
  result_.start_s = t0;
  VectorXd y = options_.initial_state.size() ? options_.initial_state : VectorXd::Zero(system_.state_size());
  step_bound_.emplace(system_, options_);
  Simulator simulator(*this, system_.ground_motion(), {.max_steps = options_.max_steps, .budget = options_.budget});
  SimulatorOutcome outcome;
  try {
    outcome = simulator.run(t0, std::move(y), make_integrator);
  } catch (const InputError&) {
    throw;  // bad settings are the caller's to report
  } catch (const std::exception& error) {
    // An integrator that cannot go on (a SUNDIALS call failing, a phase the exact path cannot
    // diagonalise) ends the run with what it has, and says why.
    outcome = simulator.outcome_so_far();
    outcome.status = RunStatus::solver_failure;
    outcome.detail = fmt::format("after t = {} s: {}", outcome.end_s, error.what());
  }
  if (outcome.status != RunStatus::completed) {
    result_.status = outcome.status;
    result_.status_detail = outcome.detail;
  }
  take_counters(outcome);
  const VectorXd& end_y = outcome.end_state;
  result_.end_s = outcome.end_s;
  result_.statistics.corner_candidates = cover_.corner_count();
  result_.statistics.corner_candidates_armed = cover_.corner_armed();
  report_overlap();
  law_->finish(outcome.end_s, end_y);
  double hysteretic_kJ = 0.0;
  if (!yields_.empty()) result_.springs = yields_.finish(end_y, recorder_.smooth_dissipated_kJ(), hysteretic_kJ);
  recorder_.finish(end_y, result_, yields_.states());
  result_.energy.hysteretic_kJ = hysteretic_kJ;  // the audit's own terms come from the recorder
  result_.statistics.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return std::move(result_);
}

void EventDrivenSystem::take_counters(const SimulatorOutcome& outcome) {
  const IntegratorCounters& c = outcome.counters;
  SolverStatistics& s = result_.statistics;
  s.steps += c.steps;
  s.rhs_evaluations += c.rhs_evaluations;
  s.root_evaluations += c.root_evaluations;
  s.jacobian_evaluations += c.jacobian_evaluations;
  s.error_test_failures += c.error_test_failures;
  s.restarts += outcome.restarts;
}

}  // namespace

RunResult run_event_driven(const dynamics::CoupledSystem& system, const EventOptions& options,
                           const IntegratorFactory& make_integrator, const std::string& method) {
  options.validate();
  if (options.initial_state.size() != 0 && options.initial_state.size() != system.state_size()) {
    throw InputError("initial_state", std::to_string(options.initial_state.size()) + " values",
                     "needs one value per state (" + std::to_string(system.state_size()) + ")");
  }
  // The impact module solves impulses slab against slab; a column point reads three floors.
  if (options.law == contact::ContactLaw::impulse && contact::has_column_pairs(system.candidates())) {
    throw InputError("law", "impulse", "cannot resolve slab-to-column contacts: they need a compliant law");
  }
  EventDrivenSystem run(system, options);
  return run.run(make_integrator, method);
}

}  // namespace pounding::solvers
