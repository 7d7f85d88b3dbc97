#include "pounding/solvers/event_driven.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <deque>
#include <numbers>
#include <fmt/format.h>
#include <optional>
#include <Eigen/QR>
#include <set>

#include "pounding/input_error.hpp"
#include "pounding/solvers/contact_states.hpp"
#include "pounding/solvers/event_step_bound.hpp"
#include "pounding/solvers/floor_impacts.hpp"
#include "pounding/solvers/missed_contacts.hpp"
#include "pounding/solvers/recorder.hpp"

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
  }
  return "?";
}

void EventOptions::validate() const {
  auto positive = [](double value, const char* field) {
    if (!(value > 0.0) || !std::isfinite(value)) throw InputError(field, format_value(value), "must be positive");
  };
  require_range("restitution", restitution, {0.0, 1.0});  // also for programs that call the solver directly
  positive(contact_tolerance_m, "contact_tolerance_m");
  positive(reopen_gap_m, "reopen_gap_m");
  positive(overlap_allowance_m, "overlap_allowance_m");
  positive(hold_velocity_mps, "hold_velocity_mps");
  positive(hold_height_m, "hold_height_m");
  positive(max_events_per_s, "max_events_per_s");
  positive(history_interval_s, "history_interval_s");
  if (max_step_s < 0.0) throw InputError("max_step_s", format_value(max_step_s), "must be zero (automatic) or positive");
  if (!(modes_cutoff_hz >= 0.0) || !std::isfinite(modes_cutoff_hz)) {
    throw InputError("modes_cutoff_hz", format_value(modes_cutoff_hz), "must be zero (every mode) or positive");
  }
  if (!(steps_per_period >= 1.0) || !std::isfinite(steps_per_period)) {
    throw InputError("steps_per_period", format_value(steps_per_period), "must be at least 1");
  }
  if (max_steps < 1) throw InputError("max_steps", std::to_string(max_steps), "must be positive");
  if (law != contact::ContactLaw::impulse) positive(contact_stiffness, "contact_stiffness");
  if (law == contact::ContactLaw::jankowski && restitution == 0.0) {
    throw InputError("restitution", "0", "must be positive for the jankowski law (its damping ratio is infinite at 0)");
  }
  budget.validate();
  if (initial_state.size() != 0 && !initial_state.allFinite()) {
    throw InputError("initial_state", "", "must be finite");
  }
}

namespace {

using dynamics::VectorXd;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// Per candidate, the components of y its gap reads: (u, v, φ) of its two floors and their rates.
std::vector<std::vector<int>> gap_components(const dynamics::CoupledSystem& system) {
  std::vector<std::vector<int>> components;
  for (const contact::Candidate& c : system.candidates()) {
    std::vector<int>& own = components.emplace_back();
    for (int b = 0; b < 2; ++b) {
      for (int k = 0; k < 3; ++k) {
        own.push_back(system.floor_index(b, c.floors[b]) + k);
        own.push_back(system.dof() + system.floor_index(b, c.floors[b]) + k);
      }
    }
  }
  return components;
}

/// A compliant contact in progress: its law, its record and the integrals over it.
struct OpenContact {
  contact::CompliantContact law;
  ImpactRecord record;
  double work_kJ = 0.0;  // ∫F ġ dt: the contact's work on the slabs (−energy lost)
};

class EventDrivenRun final : public OdeFunctions {
 public:
  EventDrivenRun(const dynamics::CoupledSystem& system, const EventOptions& options)
      : system_(system),
        options_(options),
        count_(system.candidates().size()),
        states_(count_, options.overlap_allowance_m),
        witnesses_(count_),
        hold_record_(count_, -1),
        open_(count_),
        gap_components_(gap_components(system)),
        recorder_(system, recorded_dynamics(), options.history_floors, options.history_interval_s, options.outputs,
                  options.sink) {}

  int state_size() const override { return system_.state_size(); }
  int root_count() const override { return witnesses_.size(); }
  bool is_linear() const override { return is_free_motion(); }
  bool is_free_motion() const override { return states_.free_motion(); }

  void rhs(double t, const Eigen::Ref<const VectorXd>& y, Eigen::Ref<VectorXd> y_dot) override {
    forces_.resize(static_cast<Eigen::Index>(states_.held().size()));
    system_.constrained_rhs(t, y, states_.held(), y_dot, forces_);
    for (std::size_t i : states_.acting()) system_.add_contact_force(y, i, compliant_force(i, y), y_dot);
  }

  void jacobian(double t, const Eigen::Ref<const VectorXd>& y, Eigen::Ref<Eigen::MatrixXd> jac) override {
    const int n = system_.dof();
    Eigen::SparseMatrix<double> rows;
    acceleration_jacobian(t, y, rows);
    jac.topRows(n).setZero();
    jac.topRightCorner(n, n).setIdentity();
    jac.bottomRows(n) = rows;
  }

  bool acceleration_jacobian(double, const Eigen::Ref<const VectorXd>& y, Eigen::SparseMatrix<double>& rows) override {
    system_.constrained_acceleration_jacobian(y, states_.held(), rows);
    for (std::size_t i : states_.acting()) {
      const contact::GapState s = system_.gap(y, i);
      const contact::ForceSlopes slopes = open_[i]->law.slopes(-s.gap_m, -s.gap_rate_mps);
      system_.add_contact_force_jacobian(y, i, slopes.per_overlap_kN_per_m, slopes.per_rate_kNs_per_m, rows);
    }
    return true;
  }

  // The witnesses (contact_states.hpp, Witness): gap roots of armed and masked pairs; for a
  // compliant contact from onset until its gap opens, the overlap and the law's switch function
  // (released where the force turns tensile, acting again where it would push: the jankowski
  // phases); for a held one its force; for both, the edge root while the contact point is on it.
  void roots(double t, const Eigen::Ref<const VectorXd>& y, Eigen::Ref<VectorXd> g) override {
    g.setConstant(1.0);
    for (std::size_t i = 0; i < count_; ++i) {
      if (states_.is(i, ContactMode::armed) || states_.is(i, ContactMode::masked)) {
        g[witnesses_.at(Witness::gap, i)] = states_.gap_witness(i, system_.gap(y, i).gap_m);
      }
    }
    for (std::size_t i = 0; i < count_; ++i) {
      if (!open_[i]) continue;
      const contact::GapState s = system_.gap(y, i);
      g[witnesses_.at(Witness::gap, i)] = -s.gap_m;
      g[witnesses_.at(Witness::force, i)] = open_[i]->law.switch_value(-s.gap_m, -s.gap_rate_mps);
    }
    for (std::size_t i : states_.acting()) g[witnesses_.at(Witness::edge, i)] = edge_witness(y, i);
    const std::vector<std::size_t>& held = states_.held();
    if (held.empty()) return;
    const VectorXd forces = hold_forces(t, y);
    for (std::size_t r = 0; r < held.size(); ++r) {
      g[witnesses_.at(Witness::force, held[r])] = forces[static_cast<Eigen::Index>(r)];
      g[witnesses_.at(Witness::edge, held[r])] = edge_witness(y, held[r]);
    }
  }

  RunResult run(const IntegratorFactory& make_integrator, const std::string& method);

 private:
  /// How far candidate i's contact point is from the nearer end of its edge (fraction of the
  /// edge), shifted by on_segment()'s tolerance so that a contact at a corner does not start at a root.
  double edge_witness(const Eigen::Ref<const VectorXd>& y, std::size_t i) const {
    const double s = system_.gap(y, i).segment_param;
    return std::min(s, 1.0 - s) + contact::kOnSegmentTolerance;
  }
  VectorXd hold_forces(double t, const Eigen::Ref<const VectorXd>& y) const {
    VectorXd y_dot(system_.state_size()), forces(static_cast<Eigen::Index>(states_.held().size()));
    system_.constrained_rhs(t, y, states_.held(), y_dot, forces);
    return forces;
  }
  /// The law's force of compliant contact i (kN) at δ = −g.
  double compliant_force(std::size_t i, const Eigen::Ref<const VectorXd>& y) const {
    const contact::GapState s = system_.gap(y, i);
    return open_[i]->law.force_kN(-s.gap_m, -s.gap_rate_mps);
  }
  /// The rate of compliant contact i's switch function in state y (its unit per s).
  double switch_rate(double t, const VectorXd& y, std::size_t i) {
    VectorXd y_dot(system_.state_size());
    rhs(t, y, y_dot);
    const contact::GapState s = system_.gap(y, i);
    return open_[i]->law.switch_rate(-s.gap_m, -s.gap_rate_mps, -system_.gap_acceleration(y, y_dot, i));
  }
  /// For the recorder: this rhs, the forces of the acting compliant contacts and the held ones,
  /// and whether none acts (is_free_motion).
  RecordedDynamics recorded_dynamics() {
    return {.derivative = [this](double t, const VectorXd& y, Eigen::Ref<VectorXd> y_dot) { rhs(t, y, y_dot); },
            .contact_forces = [this](double t, const VectorXd& y) {
              std::vector<ContactForce> forces;
              for (std::size_t i : states_.acting()) forces.push_back({i, compliant_force(i, y)});
              const std::vector<std::size_t>& held = states_.held();
              if (held.empty()) return forces;
              const VectorXd held_forces = hold_forces(t, y);
              for (std::size_t r = 0; r < held.size(); ++r) forces.push_back({held[r], held_forces[static_cast<Eigen::Index>(r)]});
              return forces;
            },
            .free_motion = [this] { return is_free_motion(); }};
  }
  double constraint_power(double t, const VectorXd& y) const {
    const std::vector<std::size_t>& held = states_.held();
    if (held.empty()) return 0.0;
    const VectorXd forces = hold_forces(t, y);
    double power = 0.0;
    for (std::size_t r = 0; r < held.size(); ++r) power += forces[r] * system_.gap(y, held[r]).gap_rate_mps;
    return power;
  }

  void start(double t, VectorXd& y);
  bool step_once();
  /// scan_missed_contacts over the step (prev_t_, t], whose ends' gaps are prev_gaps_ and gaps_;
  /// its grazes become touches.
  std::optional<MissedContact> missed_contact(double t);
  void settle_holds(double t, const VectorXd& y);
  void note_overlaps(double t);
  void handle_event(double t, VectorXd& y, const std::vector<std::size_t>& gap_roots,
                    const std::vector<std::size_t>& released, const char* release_reason);
  FloorContacts floor_contacts(const VectorXd& y, int level, const std::set<std::size_t>& fired) const;
  /// g̈ of each member of `contacts` in state y with the contacts `held` kept closed.
  VectorXd free_gap_accelerations(double t, const VectorXd& y, const std::vector<std::size_t>& held,
                                  const FloorContacts& contacts) const {
    VectorXd y_dot(system_.state_size()), forces(static_cast<Eigen::Index>(held.size()));
    system_.constrained_rhs(t, y, held, y_dot, forces);
    VectorXd accel(static_cast<Eigen::Index>(contacts.members.size()));
    for (std::size_t k = 0; k < contacts.members.size(); ++k) {
      accel[static_cast<Eigen::Index>(k)] = system_.gap_acceleration(y, y_dot, contacts.members[k]);
    }
    return accel;
  }
  std::vector<bool> settle_floor(double t, VectorXd& y, FloorContacts& contacts,
                                 contact::ImpulseSolution& solution) const;
  void stick(const FloorContacts& contacts, const std::vector<bool>& holding, VectorXd& y,
             contact::ImpulseSolution& solution) const;
  void resolve_floor(double t, VectorXd& y, int level, const std::set<std::size_t>& fired);
  /// Masks candidate i until its gap exceeds reopen_m, with a root at its floor.
  void mask(std::size_t i, double reopen_m, const VectorXd& y) { states_.mask(i, reopen_m, system_.gap(y, i).gap_m); }
  void hold(std::size_t i, double t);
  bool compliant() const { return options_.law != contact::ContactLaw::impulse; }
  /// Compliant laws: the events at t (gap, force and edge roots) instead of impulses and holds.
  void handle_compliant_event(double t, const VectorXd& y, const std::vector<std::size_t>& gap_roots,
                              const std::vector<std::size_t>& force_roots, const std::vector<std::size_t>& edge_roots);
  void begin_contact(std::size_t i, double t, const VectorXd& y);
  void end_contact(std::size_t i, double t, const VectorXd& y);
  /// Peak force, impulse and work of the acting contacts over [t_a, t_b] on the interpolant.
  void integrate_contacts(double t_a, double t_b, const VectorXd& y_b);
  void release(std::size_t i, double t, const VectorXd& y, const std::string& reason);
  /// Step limits and bookkeeping for a new smooth stretch starting at (t, y).
  void begin_phase(double t, const VectorXd& y);
  void restart(double t, const VectorXd& y);
  /// The bookkeeping after a step that ends at (t, y) without an event; gaps_ holds y's gaps.
  void after_step(double t, const VectorXd& y);
  /// `gaps`: every candidate's gap in state y.
  void update_step_bound(double t, const VectorXd& y, const std::vector<contact::GapState>& gaps);
  /// True when options_.modes_cutoff_hz leaves out some mode of a building.
  bool drops_modes() const {
    const double cutoff_hz = options_.modes_cutoff_hz;
    if (cutoff_hz == 0.0) return false;
    for (int b = 0; b < 2; ++b) {
      if (system_.building(b).modes.back().omega_rad_s / (2.0 * std::numbers::pi) >= cutoff_hz) return true;
    }
    return false;
  }
  /// Every candidate's gap in state y, into `gaps`.
  void evaluate_gaps(const VectorXd& y, std::vector<contact::GapState>& gaps) const {
    gaps.resize(count_);
    for (std::size_t i = 0; i < count_; ++i) gaps[i] = system_.gap(y, i);
  }
  void update_hold_records(double t, const VectorXd& y);
  /// Ends a completed run as unresolved_overlap if a pair not held sank past the touch band.
  void report_overlap();
  void count_event(double t);
  void set_next_stop(double t);
  void accumulate_counters();

  const dynamics::CoupledSystem& system_;
  const EventOptions& options_;
  BudgetClock budget_{options_.budget};
  std::size_t count_;
  ContactStates states_;
  WitnessLayout witnesses_;
  std::vector<int> hold_record_;  // index into result_.sustained_contacts while held
  std::vector<std::optional<OpenContact>> open_;  // compliant contacts: set from onset until the gap opens
  std::vector<std::vector<int>> gap_components_;   // per candidate, the components of y its gap reads
  VectorXd forces_;
  Recorder recorder_;
  RunResult result_;
  std::unique_ptr<Integrator> integrator_;
  std::optional<EventStepBound> step_bound_;
  double current_max_step_s_ = 0.0;
  double prev_t_ = 0.0;
  VectorXd prev_y_;
  // Every candidate's gap at prev_y_ and at the end of the step in progress: evaluated once per
  // step for the checks that read them all (each gap takes the slabs' exact rotation).
  std::vector<contact::GapState> prev_gaps_, gaps_;
  std::deque<double> recent_events_;
  bool stop_ = false;
};

void EventDrivenRun::set_next_stop(double t) {
  // Record samples are where the forcing's slope changes: never step across one.
  if (const auto next = system_.ground_motion().next_sample_after(t)) integrator_->set_stop_time(*next);
}

void EventDrivenRun::accumulate_counters() {
  const IntegratorCounters c = integrator_->counters();
  SolverStatistics& s = result_.statistics;
  s.steps += c.steps;
  s.rhs_evaluations += c.rhs_evaluations;
  s.root_evaluations += c.root_evaluations;
  s.jacobian_evaluations += c.jacobian_evaluations;
  s.error_test_failures += c.error_test_failures;
}

void EventDrivenRun::begin_phase(double t, const VectorXd& y) {
  current_max_step_s_ = -1.0;  // force update_step_bound to hand the integrator its bound
  set_next_stop(t);
  evaluate_gaps(y, prev_gaps_);
  states_.watch_arrivals(prev_gaps_);
  update_step_bound(t, y, prev_gaps_);
  prev_t_ = t;
  prev_y_ = y;
}

void EventDrivenRun::restart(double t, const VectorXd& y) {
  accumulate_counters();  // re-initialisation resets the integrator's own counters
  integrator_->restart(t, y);
  ++result_.statistics.restarts;
  begin_phase(t, y);
}

void EventDrivenRun::count_event(double t) {
  ++result_.statistics.events;
  recent_events_.push_back(t);
  while (!recent_events_.empty() && recent_events_.front() < t - 1.0) recent_events_.pop_front();
  if (static_cast<double>(recent_events_.size()) > options_.max_events_per_s) {
    result_.status = RunStatus::event_limit;
    result_.status_detail = fmt::format("more than {} events within one simulated second before t = {} s",
                                        options_.max_events_per_s, t);
    stop_ = true;
  }
}

void EventDrivenRun::hold(std::size_t i, double t) {
  if (!states_.hold(i)) return;
  const contact::Candidate& c = system_.candidates()[i];
  SustainedContactRecord record;
  record.level = c.level;
  record.floors = c.floors;
  record.elevation_m = c.elevation_m;
  record.striking_building = c.striking_building + 1;
  record.vertex = c.vertex_index + 1;
  record.candidate = i;
  record.start_s = t;
  hold_record_[i] = static_cast<int>(result_.sustained_contacts.size());
  result_.sustained_contacts.push_back(record);
}

void EventDrivenRun::release(std::size_t i, double t, const VectorXd& y, const std::string& reason) {
  // At g ≈ 0, opening slowly: armed again once clearly open.
  if (!states_.release_hold(i, options_.contact_tolerance_m, system_.gap(y, i).gap_m)) return;
  SustainedContactRecord& record = result_.sustained_contacts[hold_record_[i]];
  record.release_s = t;
  record.release_reason = reason;
  hold_record_[i] = -1;
}

void EventDrivenRun::start(double t, VectorXd& y) {
  // CVODE does not report roots at the initial time: contacts that exist at rest (a zero gap)
  // are handled here as an event.
  std::vector<std::size_t> touching;
  for (std::size_t i = 0; i < count_; ++i) {
    const contact::GapState s = system_.gap(y, i);
    if (s.gap_m <= options_.contact_tolerance_m && s.on_segment()) touching.push_back(i);
  }
  if (touching.empty()) return;
  if (compliant()) {
    handle_compliant_event(t, y, touching, {}, {});
  } else {
    handle_event(t, y, touching, {}, "");
  }
}

void EventDrivenRun::handle_event(double t, VectorXd& y, const std::vector<std::size_t>& gap_roots,
                                  const std::vector<std::size_t>& released, const char* release_reason) {
  count_event(t);
  for (std::size_t i : released) release(i, t, y, release_reason);
  std::set<std::size_t> fired;
  std::set<int> levels;
  for (std::size_t i : gap_roots) {
    const contact::GapState s = system_.gap(y, i);
    if (!s.on_segment()) {
      states_.mask_beside_edge(i, options_.reopen_gap_m);  // the vertex crossed the edge's extension
      ++result_.statistics.off_segment_crossings;
      continue;
    }
    result_.statistics.note_overlap(s.gap_m, t, i);
    fired.insert(i);
    levels.insert(system_.candidates()[i].level);
  }
  for (int level : levels) resolve_floor(t, y, level, fired);
  settle_holds(t, y);
  update_hold_records(t, y);  // a hold may end before the next step does
  recorder_.sample(t, y);
}

void EventDrivenRun::handle_compliant_event(double t, const VectorXd& y, const std::vector<std::size_t>& gap_roots,
                                            const std::vector<std::size_t>& force_roots,
                                            const std::vector<std::size_t>& edge_roots) {
  // A root is located to the solver's tolerance on either side of zero, so after the restart the
  // same function may cross again: each root acts only if the state at it moves in the direction
  // of its switch (closing gap, falling switch function, opening gap).
  count_event(t);
  for (std::size_t i : edge_roots) {
    if (states_.is(i, ContactMode::compliant)) end_contact(i, t, y);
  }
  for (std::size_t i : force_roots) {
    if (!open_[i] || switch_rate(t, y, i) >= 0.0) continue;
    contact::CompliantContact& law = open_[i]->law;
    const bool acted = law.acts();
    if (!acted && system_.gap(y, i).gap_m >= 0.0) continue;  // already open: the gap root ends it
    law.toggle();
    if (acted && !law.acts()) {
      states_.stop_acting(i);  // tensile from here on: the slabs fly apart while still overlapping
      open_[i]->record.separation_velocity_mps = system_.gap(y, i).gap_rate_mps;
      open_[i]->record.duration_s = t - open_[i]->record.t_s;
    } else if (!acted) {
      states_.start_acting(i);  // pushing again before the gap opened: the same contact goes on
    }  // else a jankowski contact changed phase and acts on
  }
  for (std::size_t i : gap_roots) {
    const contact::GapState s = system_.gap(y, i);
    if (states_.is(i, ContactMode::released) || states_.is(i, ContactMode::compliant)) {
      if (s.gap_rate_mps >= 0.0) end_contact(i, t, y);  // the gap opened: the contact is over
      continue;
    }
    if (!states_.is(i, ContactMode::armed) && !states_.is(i, ContactMode::masked)) continue;
    if (!s.on_segment()) {
      states_.mask_beside_edge(i, options_.reopen_gap_m);  // the vertex crossed the edge's extension
      ++result_.statistics.off_segment_crossings;
    } else if (s.gap_rate_mps < 0.0) {
      begin_contact(i, t, y);
    } else if (s.gap_m <= options_.contact_tolerance_m) {
      result_.touches.push_back(touch_record(system_, t, i, s));
      mask(i, options_.reopen_gap_m, y);  // grazed: armed again once clearly open
    }
  }
  recorder_.sample(t, y);
}

void EventDrivenRun::begin_contact(std::size_t i, double t, const VectorXd& y) {
  // The effective mass and approach speed at onset, held for the contact so that the damping
  // (and the Jacobian) stay smooth.
  const contact::GapState s = system_.gap(y, i);
  open_[i].emplace(OpenContact{contact::CompliantContact(options_.law, options_.contact_stiffness, options_.restitution,
                                                         -s.gap_rate_mps, system_.normal_inverse_mass(y, i)),
                               impact_at(system_, t, i, s)});
  open_[i]->record.peak_force_kN = std::max(0.0, compliant_force(i, y));
  states_.start_acting(i);
}

void EventDrivenRun::end_contact(std::size_t i, double t, const VectorXd& y) {
  ImpactRecord& r = open_[i]->record;
  if (states_.is(i, ContactMode::compliant)) {  // slid off the edge or the run ended while pushing
    r.separation_velocity_mps = system_.gap(y, i).gap_rate_mps;
    r.duration_s = t - r.t_s;
  }
  // What the contact took from the slabs (dissipated, or still in its spring at the run's end)
  // counts as impact loss, as an impulse's does.
  r.energy_lost_kJ = -open_[i]->work_kJ;
  recorder_.add_impact_loss(r.energy_lost_kJ);
  result_.impacts.push_back(r);
  recorder_.stream_new_impacts(result_.impacts);
  open_[i].reset();
  mask(i, options_.reopen_gap_m, y);
}

void EventDrivenRun::integrate_contacts(double t_a, double t_b, const VectorXd& y_b) {
  // Composite Simpson on the step's interpolant: its error is of the interpolant's order, far
  // below the solver tolerance for the smooth force inside a contact (no switch inside a step).
  if (states_.acting().empty() || !(t_b > t_a)) return;
  constexpr int kIntervals = 16;
  VectorXd y(system_.state_size());
  const double h = (t_b - t_a) / kIntervals;
  for (int k = 0; k <= kIntervals; ++k) {
    if (k == kIntervals) {
      y = y_b;
    } else {
      integrator_->interpolate(t_a + k * h, y);
    }
    const double weight = (k == 0 || k == kIntervals ? 1.0 : k % 2 ? 4.0 : 2.0) * h / 3.0;
    for (std::size_t i : states_.acting()) {
      const double force = compliant_force(i, y);
      OpenContact& open = *open_[i];
      open.record.peak_force_kN = std::max(open.record.peak_force_kN, force);
      open.record.impulse_kNs += weight * force;
      open.work_kJ += weight * force * system_.gap(y, i).gap_rate_mps;
    }
  }
}

void EventDrivenRun::settle_holds(double t, const VectorXd& y) {
  // A velocity jump anywhere (stiffness-proportional damping couples adjacent floors) or a
  // release changes the force every held contact needs; a force root cannot see a force that
  // jumped to tensile at the restart. So after every event the held set is settled again, all
  // together: the held contacts that the complementarity problem leaves without force while
  // their gap would open are released.
  const std::vector<std::size_t>& held = states_.held();
  if (held.empty()) return;
  // A twin held beside its contact (coincident corners: the same row twice) gets no force and
  // zero acceleration; only an opening acceleration clearly above round-off releases a pair.
  const contact::LcpSolution solution = system_.hold_complementarity(t, y, held);
  const double round_off = 1e-9 * (1.0 + solution.w.cwiseAbs().maxCoeff());
  std::vector<std::size_t> separating;
  for (std::size_t r = 0; r < held.size(); ++r) {
    const auto k = static_cast<Eigen::Index>(r);
    if (solution.x[k] <= 0.0 && solution.w[k] > round_off) separating.push_back(held[r]);
  }
  for (std::size_t i : separating) release(i, t, y, "tensile force");
}

FloorContacts EventDrivenRun::floor_contacts(const VectorXd& y, int level, const std::set<std::size_t>& fired) const {
  // Every contact of this level's slab pair that is closed now takes part, so simultaneous
  // contacts are solved together, never one after another.
  return gather_floor_contacts(system_, y, level, options_.restitution, [&](std::size_t i, const contact::GapState& s) {
    const bool closed = std::abs(s.gap_m) <= options_.contact_tolerance_m && s.on_segment();
    return states_.is(i, ContactMode::held) || fired.count(i) || closed;
  });
}

std::vector<bool> EventDrivenRun::settle_floor(double t, VectorXd& y, FloorContacts& contacts,
                                               contact::ImpulseSolution& solution) const {
  // First the impact law with restitution k. A contact that then separates slower than the hold
  // velocity, or would fly lower than the hold height, is held if the force holding it is
  // compressive; held contacts are solved again with k = 0. Repeats until the held set no longer
  // changes; stick() then brings the held ones to ġ = 0 exactly.
  const std::size_t n = contacts.members.size();
  std::vector<bool> holding(n, false);
  VectorXd y_after = y;
  for (std::size_t pass = 0; pass <= n; ++pass) {
    for (std::size_t k = 0; k < n; ++k) contacts.rows[k].restitution = holding[k] ? 0.0 : options_.restitution;
    y_after = y;
    solution = apply_impulses(system_, y_after, contacts);
    const contact::Vector6d v_after = system_.pair_velocities(y_after, contacts.floors);

    std::vector<std::size_t> trial;  // held elsewhere, plus this floor's slow separations
    for (std::size_t i : states_.held()) {
      if (system_.candidates()[i].level != contacts.level) trial.push_back(i);
    }
    const std::size_t others = trial.size();
    const VectorXd accel = free_gap_accelerations(t, y_after, trial, contacts);
    std::vector<std::size_t> slow;
    for (std::size_t k = 0; k < n; ++k) {
      const double rate = contacts.rows[k].jacobian.dot(v_after);
      const double apex_m = accel[k] < 0.0 ? rate * rate / (-2.0 * accel[k]) : kInfinity;
      if (rate < options_.hold_velocity_mps || apex_m < options_.hold_height_m) {
        trial.push_back(contacts.members[k]);
        slow.push_back(k);
      }
    }
    // Held if the physical force is compressive: the drift correction (3ġ/τ at the slow ġ the
    // impulse left) would pull a gently pressed pair apart, and stick() brings ġ to 0 anyway.
    std::vector<bool> proposal(n, false);
    if (!slow.empty()) {
      const std::vector<bool> pressing = system_.physical_hold_forces(t, y_after, trial).pressing;
      for (std::size_t s = 0; s < slow.size(); ++s) proposal[slow[s]] = pressing[others + s];
    }
    if (proposal == holding) break;
    holding = proposal;
  }
  stick(contacts, holding, y_after, solution);
  y = y_after;
  return holding;
}

void EventDrivenRun::stick(const FloorContacts& contacts, const std::vector<bool>& holding, VectorXd& y,
                           contact::ImpulseSolution& solution) const {
  // A contact goes into hold separating at up to hold_velocity_mps (the bounce sequence it cuts
  // off would have brought it to rest). Left to the drift correction, that speed would open the
  // gap by ~v·τ and do work against the constraint; instead the held contacts are brought to
  // ġ = 0 together here, and the kinetic energy this takes counts as impact loss.
  std::vector<std::size_t> held;
  for (std::size_t k = 0; k < holding.size(); ++k) {
    if (holding[k]) held.push_back(k);
  }
  if (held.empty()) return;
  const Eigen::Index m = static_cast<Eigen::Index>(held.size());
  const contact::Vector6d inverse_mass = system_.pair_inverse_mass(contacts.floors);
  const contact::Vector6d velocities = system_.pair_velocities(y, contacts.floors);
  Eigen::MatrixXd rows(m, 6);
  for (Eigen::Index r = 0; r < m; ++r) rows.row(r) = contacts.rows[held[static_cast<std::size_t>(r)]].jacobian;
  const Eigen::MatrixXd w = rows * inverse_mass.asDiagonal() * rows.transpose();
  const VectorXd impulses = w.completeOrthogonalDecomposition().solve(-(rows * velocities));
  const contact::Vector6d change = inverse_mass.cwiseProduct(rows.transpose() * impulses);
  system_.add_pair_velocities(y, contacts.floors, change);
  solution.velocity_change += change;
  for (Eigen::Index r = 0; r < m; ++r) solution.impulses_kNs[held[static_cast<std::size_t>(r)]] += impulses[r];
}

void EventDrivenRun::resolve_floor(double t, VectorXd& y, int level, const std::set<std::size_t>& fired) {
  FloorContacts contacts = floor_contacts(y, level, fired);
  const VectorXd y_before = y;
  contact::ImpulseSolution solution;
  std::vector<bool> were_held(contacts.members.size());
  for (std::size_t k = 0; k < contacts.members.size(); ++k) were_held[k] = states_.is(contacts.members[k], ContactMode::held);
  const std::vector<bool> holding = settle_floor(t, y, contacts, solution);
  recorder_.add_impact_loss(
      record_floor_outcome(system_, t, contacts, solution, y_before, y, fired, holding, were_held, result_));
  recorder_.stream_new_impacts(result_.impacts);
  for (std::size_t k = 0; k < contacts.members.size(); ++k) {
    const std::size_t i = contacts.members[k];
    if (were_held[k]) result_.sustained_contacts[hold_record_[i]].impulse_kNs += solution.impulses_kNs[k];
    if (holding[k]) {
      hold(i, t);
    } else if (states_.is(i, ContactMode::held)) {
      release(i, t, y, "separated by an impact");
    } else {
      mask(i, options_.reopen_gap_m, y);
    }
  }
}

std::optional<MissedContact> EventDrivenRun::missed_contact(double t) {
  if (t <= step_bound_->open_until_s()) return std::nullopt;  // every gap stayed above the touch band
  // The step's interpolant, evaluated only in the components a candidate's gap reads.
  class Interpolant final : public StepGaps {
   public:
    explicit Interpolant(EventDrivenRun& run) : run_(run), at_(run.system_.state_size()) {}
    contact::GapState at(std::size_t i, double t_s) override {
      run_.integrator_->interpolate_components(t_s, run_.gap_components_[i], at_);
      return run_.system_.gap(at_, i);
    }
    double rate_round_off_mps(std::size_t i) override { return run_.system_.gap_rate_round_off_mps(at_, i); }

   private:
    EventDrivenRun& run_;
    VectorXd at_;
  } path(*this);
  std::vector<Graze> grazes;
  const std::optional<MissedContact> missed = scan_missed_contacts(
      states_, path, prev_t_, t, prev_gaps_, gaps_,
      {.contact_tolerance_m = options_.contact_tolerance_m, .overlap_allowance_m = options_.overlap_allowance_m},
      grazes);
  for (const Graze& graze : grazes) result_.touches.push_back(touch_record(system_, graze.t_s, graze.candidate, graze.gap));
  return missed;
}

void EventDrivenRun::update_step_bound(double t, const VectorXd& y, const std::vector<contact::GapState>& gaps) {
  VectorXd y_dot;
  auto gap_acceleration = [&](std::size_t i) {
    if (y_dot.size() == 0) {
      y_dot.resize(system_.state_size());
      rhs(t, y, y_dot);
    }
    return system_.gap_acceleration(y, y_dot, i);
  };
  const double bound = step_bound_->max_step_s(t, y, gaps, states_, gap_acceleration);
  if (bound != current_max_step_s_) {
    integrator_->set_max_step(bound);
    current_max_step_s_ = bound;
  }
}

void EventDrivenRun::note_overlaps(double t) {
  for (std::size_t i = 0; i < count_; ++i) {
    if (!states_.is(i, ContactMode::armed) && !states_.is(i, ContactMode::masked)) {
      continue;  // a held gap's drift is reported with its hold, a compliant one's penetration is the law's
    }
    const contact::GapState& s = gaps_[i];
    if (s.on_segment()) result_.statistics.note_overlap(s.gap_m, t, i);
  }
}

void EventDrivenRun::after_step(double t, const VectorXd& y) {
  note_overlaps(t);
  states_.rearm(gaps_);
  update_hold_records(t, y);
  update_step_bound(t, y, gaps_);
}

void EventDrivenRun::report_overlap() {
  // Every closing is located before the pair sinks in; an overlap deeper than the touch band means
  // a contact was passed over and everything after it is off, so the run must not say completed.
  const SolverStatistics& stats = result_.statistics;
  if (result_.status != RunStatus::completed || !(stats.max_interpenetration_m > options_.contact_tolerance_m)) return;
  const contact::Candidate& c = system_.candidates()[static_cast<std::size_t>(stats.max_interpenetration_candidate)];
  result_.status = RunStatus::unresolved_overlap;
  result_.status_detail = fmt::format(
      "slabs sank {:.3g} m into each other at {:.6f} s (deeper than contact_tolerance_m {} m), level {}: {}",
      stats.max_interpenetration_m, stats.max_interpenetration_t_s, options_.contact_tolerance_m, c.level,
      contact::describe(c));
}

void EventDrivenRun::update_hold_records(double t, const VectorXd& y) {
  const std::vector<std::size_t>& held = states_.held();
  if (held.empty()) return;
  const VectorXd forces = hold_forces(t, y);
  for (std::size_t r = 0; r < held.size(); ++r) {
    SustainedContactRecord& record = result_.sustained_contacts[hold_record_[held[r]]];
    record.max_force_kN = std::max(record.max_force_kN, forces[r]);
    record.max_gap_drift_m = std::max(record.max_gap_drift_m, std::abs(system_.gap(y, held[r]).gap_m));
  }
}

bool EventDrivenRun::step_once() {
  if (budget_.exhausted(prev_t_, result_)) return false;
  const double t_end = system_.ground_motion().end_s();
  if (prev_t_ >= t_end) return false;  // an event exactly at the end: no stop time is left to obey
  const StepOutcome outcome = integrator_->step(t_end);
  if (outcome.kind == StepKind::failure) {
    result_.status = RunStatus::solver_failure;
    result_.status_detail = fmt::format("after t = {} s: {}", prev_t_, outcome.failure);
    return false;
  }
  const double t = outcome.t_s;
  VectorXd y = integrator_->state();
  if (diverged(t, y, result_)) return false;
  evaluate_gaps(y, gaps_);
  auto interpolated = [&](double time) {
    VectorXd state(system_.state_size());
    integrator_->interpolate(time, state);
    return state;
  };
  auto power = [&](double time, const VectorXd& state) { return constraint_power(time, state); };
  auto components = [&](double time, const std::vector<int>& indices, VectorXd& state) {
    integrator_->interpolate_components(time, indices, state);
  };

  if (const std::optional<MissedContact> hidden = missed_contact(t)) {
    ++result_.statistics.interpolant_events;
    VectorXd y_event = interpolated(hidden->t_s);
    recorder_.advance(prev_t_, hidden->t_s, y_event, interpolated, power,
                      integrator_->energy_between(prev_t_, hidden->t_s), components);
    integrate_contacts(prev_t_, hidden->t_s, y_event);
    if (compliant()) {
      handle_compliant_event(hidden->t_s, y_event, {hidden->candidate}, {}, {});
    } else {
      handle_event(hidden->t_s, y_event, {hidden->candidate}, {}, "");
    }
    restart(hidden->t_s, y_event);
    return !stop_;
  }
  recorder_.advance(prev_t_, t, y, interpolated, power, integrator_->energy_between(prev_t_, t), components);
  integrate_contacts(prev_t_, t, y);

  if (outcome.kind == StepKind::root) {
    const std::vector<int> flags = integrator_->roots_found();
    WitnessLayout::Crossed crossed = witnesses_.crossed(flags);
    // An integrator flags the functions whose crossing it located; one that went through zero
    // at the same instant by a rounding (g = −5e-16 m) can go unflagged, and after the restart
    // it would start below zero, where its root can no longer fire.
    for (std::size_t i = 0; i < count_; ++i) {
      if (!witnesses_.flagged(flags, Witness::gap, i) && states_.is(i, ContactMode::armed) && gaps_[i].gap_m <= 0.0 &&
          gaps_[i].on_segment() && gaps_[i].gap_rate_mps < 0.0) {
        crossed.gap.push_back(i);
      }
    }
    std::sort(crossed.gap.begin(), crossed.gap.end());
    if (compliant()) {
      handle_compliant_event(t, y, crossed.gap, crossed.force, crossed.edge);
      restart(t, y);
      return !stop_;
    }
    for (std::size_t i : crossed.edge) release(i, t, y, "slid off the edge");
    handle_event(t, y, crossed.gap, crossed.force, "tensile force");
    restart(t, y);
    return !stop_;
  }
  if (outcome.kind == StepKind::stop_time) set_next_stop(t);
  after_step(t, y);
  prev_t_ = t;
  prev_y_ = y;
  std::swap(prev_gaps_, gaps_);
  if (result_.statistics.steps + integrator_->counters().steps > options_.max_steps) {
    result_.status = RunStatus::step_limit;
    result_.status_detail = fmt::format("more than {} steps by t = {} s", options_.max_steps, t);
    return false;
  }
  return t < t_end;
}

RunResult EventDrivenRun::run(const IntegratorFactory& make_integrator, const std::string& method) {
  const auto clock_start = std::chrono::steady_clock::now();
  result_.method = method;
  const double t0 = system_.ground_motion().start_s();
  result_.start_s = t0;
  VectorXd y = options_.initial_state.size() ? options_.initial_state : VectorXd::Zero(system_.state_size());
  step_bound_.emplace(system_, options_);

  recorder_.sample(t0, y);
  start(t0, y);
  try {
    // A truncated run's dropped modes move as R a_g, which GapClearance does not bound.
    if (options_.max_step_s == 0.0 && options_.clearance_steps && !compliant() && !drops_modes()) {
      // Throws, as the exact path does, if a building's damping is not classical. Its steps may
      // span whole record intervals: the peaks are located on quarter periods.
      recorder_.set_peak_step(step_bound_->enable_clearance() / 4.0);
    }
    integrator_ = make_integrator(*this, t0, y);
    begin_phase(t0, y);
    while (!stop_ && step_once()) {
    }
    accumulate_counters();
  } catch (const InputError&) {
    throw;  // bad settings are the caller's to report
  } catch (const std::exception& error) {
    // An integrator that cannot go on (a SUNDIALS call failing, a phase the exact path cannot
    // diagonalise) ends the run with what it has, and says why.
    result_.status = RunStatus::solver_failure;
    result_.status_detail = fmt::format("after t = {} s: {}", prev_t_, error.what());
  }
  result_.end_s = prev_t_;
  report_overlap();
  for (std::size_t i : std::vector<std::size_t>(states_.held())) release(i, prev_t_, prev_y_, "end of run");
  for (std::size_t i = 0; i < count_; ++i) {
    if (open_[i]) end_contact(i, prev_t_, prev_y_);
  }
  // Compliant impacts are complete, so streamed, at their release; the result lists them by onset.
  if (compliant()) {
    std::stable_sort(result_.impacts.begin(), result_.impacts.end(),
                     [](const ImpactRecord& a, const ImpactRecord& b) { return a.t_s < b.t_s; });
  }
  recorder_.finish(prev_y_, result_);
  result_.statistics.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return std::move(result_);
}

}  // namespace

RunResult run_event_driven(const dynamics::CoupledSystem& system, const EventOptions& options,
                           const IntegratorFactory& make_integrator, const std::string& method) {
  options.validate();
  if (options.initial_state.size() != 0 && options.initial_state.size() != system.state_size()) {
    throw InputError("initial_state", std::to_string(options.initial_state.size()) + " values",
                     "needs one value per state (" + std::to_string(system.state_size()) + ")");
  }
  EventDrivenRun run(system, options);
  return run.run(make_integrator, method);
}

}  // namespace pounding::solvers
