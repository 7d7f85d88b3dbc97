#include "pounding/solvers/hht.hpp"

#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <set>

#include "pounding/input_error.hpp"
#include "pounding/solvers/floor_impacts.hpp"
#include "pounding/solvers/recorder.hpp"
#include "pounding/solvers/root_finding.hpp"

namespace pounding::solvers {

HhtStepper::HhtStepper(Eigen::VectorXd mass_diagonal, Eigen::MatrixXd damping, Eigen::MatrixXd stiffness,
                       Force force, double alpha)
    : mass_(std::move(mass_diagonal)),
      damping_(std::move(damping)),
      stiffness_(std::move(stiffness)),
      force_(std::move(force)),
      alpha_(alpha),
      beta_((1.0 - alpha) * (1.0 - alpha) / 4.0),
      gamma_((1.0 - 2.0 * alpha) / 2.0) {}

HhtStepper::State HhtStepper::at(double t, Eigen::VectorXd d, Eigen::VectorXd v) const {
  Eigen::VectorXd f(mass_.size());
  force_(t, f);
  Eigen::VectorXd a = (f - damping_ * v - stiffness_ * d).cwiseQuotient(mass_);
  return {t, std::move(d), std::move(v), std::move(a)};
}

const Eigen::LLT<Eigen::MatrixXd>& HhtStepper::effective(double h) {
  auto found = factors_.find(h);
  if (found != factors_.end()) return found->second;
  if (factors_.size() > 64) factors_.clear();  // only the interpolating variant makes many sizes
  Eigen::MatrixXd matrix = (1.0 + alpha_) * gamma_ * h * damping_ + (1.0 + alpha_) * beta_ * h * h * stiffness_;
  matrix.diagonal() += mass_;
  ++factorizations_;
  return factors_.emplace(h, Eigen::LLT<Eigen::MatrixXd>(matrix)).first->second;
}

HhtStepper::State HhtStepper::step(const State& from, double h) {
  const Eigen::Index n = mass_.size();
  Eigen::VectorXd f0(n), f1(n);
  force_(from.t_s, f0);
  force_(from.t_s + h, f1);
  const Eigen::VectorXd d_pred = from.d + h * from.v + h * h * (0.5 - beta_) * from.a;
  const Eigen::VectorXd v_pred = from.v + h * (1.0 - gamma_) * from.a;
  const Eigen::VectorXd rhs = (1.0 + alpha_) * f1 - alpha_ * f0 -
                              (1.0 + alpha_) * (damping_ * v_pred + stiffness_ * d_pred) +
                              alpha_ * (damping_ * from.v + stiffness_ * from.d);
  State to;
  to.t_s = from.t_s + h;
  to.a = effective(h).solve(rhs);
  to.d = d_pred + beta_ * h * h * to.a;
  to.v = v_pred + gamma_ * h * to.a;
  return to;
}

void HhtOptions::validate() const {
  if (!(dt_s > 0.0) || !std::isfinite(dt_s)) throw InputError("dt_s", format_value(dt_s), "the time step must be positive (s)");
  if (!(alpha >= -1.0 / 3.0 && alpha <= 0.0)) throw InputError("alpha", format_value(alpha), "must lie in [-1/3, 0]");
  if (!(contact_tolerance_m > 0.0) || !std::isfinite(contact_tolerance_m)) {
    throw InputError("contact_tolerance_m", format_value(contact_tolerance_m), "must be positive (m)");
  }
  if (max_halvings < 0 || max_halvings > 60) {
    throw InputError("max_halvings", std::to_string(max_halvings), "must lie in 0..60");
  }
  if (!(restitution >= 0.0 && restitution <= 1.0)) {
    throw InputError("restitution", format_value(restitution), "must lie in [0, 1]");
  }
  if (!(history_interval_s > 0.0)) {
    throw InputError("history_interval_s", format_value(history_interval_s), "must be positive (s)");
  }
  if (max_steps < 1) throw InputError("max_steps", std::to_string(max_steps), "must be positive");
  budget.validate();
}

namespace {

using dynamics::VectorXd;
using State = HhtStepper::State;

/// The state inside a step from the cubic Hermite interpolant of (d, v) at both ends: (q, q̇).
VectorXd hermite(const State& from, const State& to, double t) {
  const double h = to.t_s - from.t_s, s = (t - from.t_s) / h;
  const double h00 = 2 * s * s * s - 3 * s * s + 1, h10 = s * s * s - 2 * s * s + s;
  const double h01 = -2 * s * s * s + 3 * s * s, h11 = s * s * s - s * s;
  const double d00 = 6 * s * s - 6 * s, d10 = 3 * s * s - 4 * s + 1, d01 = -6 * s * s + 6 * s, d11 = 3 * s * s - 2 * s;
  VectorXd y(2 * from.d.size());
  y << h00 * from.d + h10 * h * from.v + h01 * to.d + h11 * h * to.v,
      (d00 * from.d + d01 * to.d) / h + d10 * from.v + d11 * to.v;
  return y;
}

class HhtRun {
 public:
  HhtRun(const dynamics::CoupledSystem& system, const HhtOptions& options)
      : system_(system),
        options_(options),
        stepper_(system.mass_diagonal(), system.damping(), system.stiffness(),
                 [&system](double t, Eigen::Ref<VectorXd> f) { system.external_force(t, f); }, options.alpha),
        recorder_(system, options.history_floors, options.history_interval_s),
        touching_(system.candidates().size(), false) {}

  RunResult run(const std::string& method);

 private:
  VectorXd first_order(const State& s) const {
    VectorXd y(system_.state_size());
    y << s.d, s.v;
    return y;
  }
  /// Candidates that overlap at `to` beyond the tolerance while approaching, and did not at `from`.
  std::vector<std::size_t> new_overlaps(const State& from, const State& to) const;
  bool closing_contact(const State& s) const;
  bool out_of_steps(double t_s) {
    if (trial_steps_ <= options_.max_steps) return false;
    result_.status = RunStatus::step_limit;
    result_.status_detail = fmt::format("more than {} trial steps by t = {} s", options_.max_steps, t_s);
    return true;
  }
  void accept(const State& from, const State& to);
  State settle(const State& s, bool include_overlaps);
  State halve(State s, double h);
  State interpolate(const State& s, const State& trial, const std::vector<std::size_t>& overlaps);

  const dynamics::CoupledSystem& system_;
  const HhtOptions& options_;
  HhtStepper stepper_;
  Recorder recorder_;
  RunResult result_;
  std::vector<bool> touching_;  // in contact (|g| ≤ tolerance) at the last step end
  long trial_steps_ = 0;
};

std::vector<std::size_t> HhtRun::new_overlaps(const State& from, const State& to) const {
  const VectorXd y_from = first_order(from), y_to = first_order(to);
  std::vector<std::size_t> overlapping;
  for (std::size_t i = 0; i < system_.candidates().size(); ++i) {
    const contact::GapState s = system_.gap(y_to, i);
    if (s.on_segment() && s.gap_m < -options_.contact_tolerance_m && s.gap_rate_mps < 0.0 &&
        system_.gap(y_from, i).gap_m >= -options_.contact_tolerance_m) {
      overlapping.push_back(i);
    }
  }
  return overlapping;
}

bool HhtRun::closing_contact(const State& s) const {
  const VectorXd y = first_order(s);
  for (std::size_t i = 0; i < system_.candidates().size(); ++i) {
    const contact::GapState g = system_.gap(y, i);
    if (g.on_segment() && std::abs(g.gap_m) <= options_.contact_tolerance_m && g.gap_rate_mps < 0.0) return true;
  }
  return false;
}

void HhtRun::accept(const State& from, const State& to) {
  const double h = to.t_s - from.t_s;
  ++result_.statistics.steps;
  if (result_.statistics.smallest_step_s == 0.0 || h < result_.statistics.smallest_step_s) {
    result_.statistics.smallest_step_s = h;
  }
  recorder_.advance(from.t_s, to.t_s, first_order(to), [&](double t) { return hermite(from, to, t); },
                    [](double, const VectorXd&) { return 0.0; });
}

State HhtRun::settle(const State& s, bool include_overlaps) {
  // Impacts at this step end: per floor, every contact within the tolerance (and, when asked,
  // every overlap) solved together; a touch is a contact that appears without approaching.
  VectorXd y = first_order(s);
  const double tol = options_.contact_tolerance_m;
  std::vector<bool> in_contact(touching_.size(), false);
  std::set<int> floors;
  std::set<std::size_t> new_touches;
  for (std::size_t i = 0; i < touching_.size(); ++i) {
    const contact::GapState g = system_.gap(y, i);
    in_contact[i] = g.on_segment() && g.gap_m <= tol && (include_overlaps || g.gap_m >= -tol);
    if (!in_contact[i]) continue;
    if (g.gap_rate_mps < 0.0) floors.insert(system_.candidates()[i].floor);
    else if (!touching_[i]) new_touches.insert(i);
  }
  bool changed = false;
  for (int floor : floors) {
    const FloorContacts contacts = gather_floor_contacts(system_, y, floor, options_.restitution,
        [&](std::size_t i, const contact::GapState&) { return in_contact[i]; });
    const VectorXd before = y;
    const contact::ImpulseSolution solution = apply_impulses(system_, y, contacts);
    recorder_.add_impact_loss(record_floor_outcome(system_, s.t_s, contacts, solution, before, y, new_touches, {}, result_));
    ++result_.statistics.restarts;
    ++result_.statistics.events;
    changed = true;
  }
  for (std::size_t i : new_touches) {
    if (floors.count(system_.candidates()[i].floor)) continue;  // recorded with its floor's impact
    result_.touches.push_back(touch_record(system_, s.t_s, i, system_.gap(y, i)));
    ++result_.statistics.events;
  }
  touching_ = in_contact;
  if (!changed) return s;
  recorder_.sample(s.t_s, y);
  // The impact changes velocities only; the accelerations follow from the equation of motion.
  return stepper_.at(s.t_s, y.head(system_.dof()), y.tail(system_.dof()));
}

State HhtRun::halve(State s, double h) {
  // Bisection of the bracket [t, t + h] whose end overlaps: each trial step covers half the
  // bracket from its start. A trial that overlaps becomes the new bracket end; one that does not
  // is accepted and becomes the new start. Stops when the accepted end state is in contact
  // within the tolerance, so the number of halvings is about log2(Δt·|ġ| / tolerance).
  double bracket_end = s.t_s + h;
  for (int depth = 1; depth <= options_.max_halvings; ++depth) {
    ++result_.statistics.halvings;
    const State trial = stepper_.step(s, (bracket_end - s.t_s) / 2.0);
    ++trial_steps_;
    if (!new_overlaps(s, trial).empty()) {
      bracket_end = trial.t_s;
      continue;
    }
    accept(s, trial);
    s = trial;
    if (closing_contact(s)) return settle(s, false);  // found the contact: on with the full Δt
  }
  // Deepest level reached without a state within the tolerance: step to the bracket end and
  // apply the impact there, overlapping as it is.
  const State trial = stepper_.step(s, bracket_end - s.t_s);
  ++trial_steps_;
  if (!new_overlaps(s, trial).empty()) ++result_.statistics.unresolved_contacts;
  accept(s, trial);
  return settle(trial, true);
}

State HhtRun::interpolate(const State& s, const State& trial, const std::vector<std::size_t>& overlaps) {
  // Each overlapping gap along the step's cubic Hermite interpolant; the earliest zero is the
  // contact instant, and the step is redone to exactly there.
  const double h = trial.t_s - s.t_s;
  auto gap_at = [&](double t, std::size_t candidate) { return system_.gap(hermite(s, trial, t), candidate).gap_m; };
  double t_contact = trial.t_s;
  for (std::size_t candidate : overlaps) {
    const double g_start = gap_at(s.t_s, candidate);
    if (!(g_start > 0.0)) return halve(s, h);  // in the tolerance band already
    t_contact = std::min(t_contact, find_root([&](double t) { return gap_at(t, candidate); }, s.t_s, trial.t_s,
                                              g_start, gap_at(trial.t_s, candidate)));
  }
  const State redone = stepper_.step(s, t_contact - s.t_s);
  ++trial_steps_;
  accept(s, redone);
  return settle(redone, true);
}

RunResult HhtRun::run(const std::string& method) {
  const auto clock_start = std::chrono::steady_clock::now();
  result_.method = method;
  const excitation::GroundMotion& motion = system_.ground_motion();
  const double t_end = motion.end_s();
  const VectorXd y0 = options_.initial_state.size() ? options_.initial_state : VectorXd::Zero(system_.state_size());
  State s = stepper_.at(motion.start_s(), y0.head(system_.dof()), y0.tail(system_.dof()));
  result_.start_s = s.t_s;
  recorder_.sample(s.t_s, first_order(s));
  BudgetClock budget(options_.budget);
  while (s.t_s < t_end - 1e-9 * options_.dt_s) {
    if (budget.exhausted(s.t_s, result_) || out_of_steps(s.t_s)) break;
    const double h = std::min(options_.dt_s, t_end - s.t_s);
    const State trial = stepper_.step(s, h);
    ++trial_steps_;
    if (diverged(trial.t_s, first_order(trial), result_)) break;
    const std::vector<std::size_t> overlaps = new_overlaps(s, trial);
    if (overlaps.empty()) {
      accept(s, trial);
      s = settle(trial, false);
      continue;
    }
    switch (options_.location) {
      case HhtEventLocation::end_of_step:
        accept(s, trial);
        s = settle(trial, true);
        break;
      case HhtEventLocation::halving:
        s = halve(s, h);
        break;
      case HhtEventLocation::interpolate:
        s = interpolate(s, trial, overlaps);
        break;
    }
  }
  result_.end_s = s.t_s;
  result_.statistics.rhs_evaluations = trial_steps_;  // one effective-stiffness solve per trial step
  result_.statistics.jacobian_evaluations = stepper_.factorizations();
  recorder_.finish(first_order(s), result_);
  result_.statistics.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return std::move(result_);
}

}  // namespace

RunResult run_hht(const dynamics::CoupledSystem& system, const HhtOptions& options, const std::string& method) {
  options.validate();
  if (options.initial_state.size() != 0 && options.initial_state.size() != system.state_size()) {
    throw InputError("initial_state", std::to_string(options.initial_state.size()) + " values",
                     "needs one value per state (" + std::to_string(system.state_size()) + ")");
  }
  HhtRun run(system, options);
  return run.run(method);
}

}  // namespace pounding::solvers
