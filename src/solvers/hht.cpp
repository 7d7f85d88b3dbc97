#include "pounding/solvers/hht.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <fmt/format.h>
#include <set>

#include "pounding/contact/impact.hpp"
#include "pounding/input_error.hpp"
#include "pounding/solvers/energy_balance.hpp"
#include "pounding/solvers/floor_impacts.hpp"
#include "pounding/solvers/recorder.hpp"
#include "pounding/solvers/root_finding.hpp"

namespace pounding::solvers {

HhtStepper::HhtStepper(Eigen::VectorXd mass_diagonal, Eigen::MatrixXd damping, Eigen::MatrixXd stiffness, Force force,
                       double alpha)
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

Eigen::VectorXd HhtStepper::defect(const State& s) const {
  Eigen::VectorXd f(mass_.size());
  force_(s.t_s, f);
  return mass_.cwiseProduct(s.a) - f + damping_ * s.v + stiffness_ * s.d;
}

double HhtStepper::algorithmic_dissipation(const State& from, const State& to) const {
  // With Δx = x₁ − x₀ and ⟨x⟩ = (x₀ + x₁)/2, the Newmark updates read Δd = h⟨v⟩ + h²(β − γ/2)Δa
  // and Δv = h⟨a⟩ + h(γ − ½)Δa; multiplying M⟨a⟩ by Δd gives, from the kinematics alone,
  //   Δdᵀ M⟨a⟩ = ΔT − h(γ − ½)⟨v⟩ᵀ M Δa + h²(β − γ/2) Δ(½ aᵀ M a),   T = ½ vᵀ M v.
  // The scheme's accelerations satisfy M a = f − C v − K d + r (r = α(Δf − CΔv − KΔd) after an
  // HHT step, 0 where a is computed from the equation of motion), and Δdᵀ K⟨d⟩ = ΔV exactly, so
  //   ΔT + ΔV = Δdᵀ⟨f⟩ − Δdᵀ C⟨v⟩ − D,
  //   D = −Δdᵀ⟨r⟩ − h(γ − ½)⟨v⟩ᵀ M Δa + h²(β − γ/2) Δ(½ aᵀ M a).
  // With α = 0 (γ = ½, β = ¼, r = 0) every term vanishes.
  const double h = to.t_s - from.t_s;
  const Eigen::VectorXd mean_r = 0.5 * (defect(from) + defect(to));
  const Eigen::VectorXd mean_v = 0.5 * (from.v + to.v);
  const Eigen::VectorXd m_delta_a = mass_.cwiseProduct(to.a - from.a);
  const double delta_acceleration_energy = 0.5 * (to.a.cwiseAbs2() - from.a.cwiseAbs2()).dot(mass_);
  return -(to.d - from.d).dot(mean_r) - h * (gamma_ - 0.5) * mean_v.dot(m_delta_a) +
         h * h * (beta_ - 0.5 * gamma_) * delta_acceleration_energy;
}

void HhtOptions::validate() const {
  // The user-facing rules (the scene's keys, tighter ranges) are analysis::SolverSettings::validate()
  // and the scene's contact validator; these are the scheme's own, kept in release builds for
  // programs that call the solver directly.
  require_range("dt_s", dt_s, {0.0, std::numeric_limits<double>::max(), "s", true});
  require_range("alpha", alpha, {-1.0 / 3.0, 0.0, {}, false, "[-1/3, 0]"});  // unconditionally stable, 2nd order
  require_range("contact_tolerance_m", contact_tolerance_m, {0.0, std::numeric_limits<double>::max(), "m", true});
  require_range("max_halvings", max_halvings, {0.0, 60.0});  // dt / 2⁶⁰ is below the round-off of t
  require_range("restitution", restitution, contact::kRestitutionRange);
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
        stepper_(
            system.mass_diagonal(), system.damping(), system.stiffness(),
            [&system](double t, Eigen::Ref<VectorXd> f) { system.external_force(t, f); }, options.alpha),
        recorder_(system, free_dynamics(system), {options.history_floors, options.history_other_floors},
                  options.history_interval_s, options.outputs, options.sink),
        touching_(system.candidates().size(), false),
        sunk_(system.candidates().size(), false),
        no_approach_mps_(1e-6 * options.contact_tolerance_m / options.dt_s),
        undersampled_(system.ground_motion().skips_samples(options.dt_s)) {}

  RunResult run(const std::string& method);

 private:
  VectorXd first_order(const State& s) const {
    VectorXd y(system_.state_size());
    y << s.d, s.v;
    return y;
  }
  /// On its edge, with its vertex inside the other slab if behind the tolerance band: a corner
  /// beside the slab's end, behind the line of its facade, is outside (docs/model.md §5a).
  bool on_edge(const VectorXd& y, std::size_t i, const contact::GapState& g) const {
    return g.on_segment() && (g.gap_m >= -options_.contact_tolerance_m || system_.depth_inside_m(y, i, g) > 0.0);
  }
  /// On its edge (on_edge) and deeper than the contact tolerance.
  bool sunk(const VectorXd& y, std::size_t i, const contact::GapState& g) const {
    return g.gap_m < -options_.contact_tolerance_m && on_edge(y, i, g);
  }
  /// Per candidate, the gap below which a step from `s` overlaps: −tolerance, or for a pair
  /// already sunk at `s` (an overlap halving did not resolve) a further tolerance below where it
  /// is, so that it cannot sink on unnoticed.
  std::vector<double> overlap_limits(const State& s) const;
  /// Candidates below their limit at `to`, on their edge there or where they crossed it, or
  /// that dipped below it inside the step and came out again: a contact the step passed over,
  /// whatever the gap's rate at `to` (the vertex may already be on its way out, or have slid
  /// past the edge's end).
  std::vector<std::size_t> new_overlaps(const std::vector<double>& limits, const State& from, const State& to) const;
  /// One candidate over one step: the step's ends and the candidate's gap at each.
  struct StepGap {
    const State& from;
    const State& to;
    std::size_t candidate;
    contact::GapState start, end;
  };
  /// The gap fell below `limit` inside the step (on the Hermite interpolant) while on its edge.
  bool crossed_on_edge(const StepGap& step, double limit) const;
  /// The gap has a minimum inside the step (on the Hermite interpolant) below `limit`, on its edge.
  bool dipped_on_edge(const StepGap& step, double limit) const;
  /// Some candidate approaches within the tolerance band above its limit.
  bool closing_contact(const std::vector<double>& limits, const State& s) const;
  bool out_of_steps(double t_s) {
    if (trial_steps_ <= options_.max_steps) return false;
    result_.status = RunStatus::step_limit;
    result_.status_detail = fmt::format("more than {} trial steps by t = {} s", options_.max_steps, t_s);
    return true;
  }
  void accept(const State& from, const State& to);
  /// With steps longer than the record's sample spacing (the run's record_undersampled warning):
  /// the input and damping over a step that spans samples, for the forcing the scheme applies,
  /// a_g at the step's ends and a straight line between, so the audit balances against the record
  /// the scheme saw. Empty otherwise: the recorder integrates the record itself (a step of at most
  /// the spacing sees every sample, if not always at a step end).
  std::optional<StretchEnergy> energy_of_skipping_step(const State& from, const State& to) const;
  /// Counts every pair that sinks deeper than the tolerance at an accepted step end.
  void track_overlaps(const State& s);
  /// A contact in the band is an impact only if it closes: already touching or overlapping
  /// (g ≤ 0), or approaching fast enough to touch within a step. A pair resting in the band at a
  /// positive gap (e.g. two identical buildings closer than the tolerance) drifting together
  /// slower than that has not touched; if it goes on, the step that overlaps is halved.
  bool approaching(const contact::GapState& g) const {
    return g.gap_rate_mps < -no_approach_mps_ && g.gap_m + g.gap_rate_mps * options_.dt_s <= 0.0;
  }
  State settle(const State& s);
  void report_overlaps();
  State halve(State s, double h);
  State interpolate(const State& s, const State& trial, const std::vector<std::size_t>& overlaps);

  const dynamics::CoupledSystem& system_;
  const HhtOptions& options_;
  HhtStepper stepper_;
  Recorder recorder_;
  RunResult result_;
  std::vector<bool> touching_;  // on the edge with g ≤ 0 at the last step end
  std::vector<bool> sunk_;      // deeper than the tolerance at the last accepted step end
  // An approach this slow would close the gap by a millionth of the tolerance in a step:
  // round-off, not motion.
  double no_approach_mps_;
  bool undersampled_;  // dt_s is longer than the record's sample spacing
  long trial_steps_ = 0;
};

std::vector<double> HhtRun::overlap_limits(const State& s) const {
  const VectorXd y = first_order(s);
  const double tol = options_.contact_tolerance_m;
  std::vector<double> limits(system_.candidates().size());
  for (std::size_t i = 0; i < limits.size(); ++i) {
    const contact::GapState g = system_.gap(y, i);
    limits[i] = sunk(y, i, g) ? g.gap_m - tol : -tol;
  }
  return limits;
}

std::vector<std::size_t> HhtRun::new_overlaps(const std::vector<double>& limits, const State& from,
                                              const State& to) const {
  const VectorXd y_from = first_order(from), y_to = first_order(to);
  std::vector<std::size_t> overlapping;
  for (std::size_t i = 0; i < limits.size(); ++i) {
    const StepGap step{from, to, i, system_.gap(y_from, i), system_.gap(y_to, i)};
    const bool below = step.end.gap_m < limits[i] && (on_edge(y_to, i, step.end) || crossed_on_edge(step, limits[i]));
    if (below || (step.end.gap_m >= limits[i] && dipped_on_edge(step, limits[i]))) overlapping.push_back(i);
  }
  return overlapping;
}

bool HhtRun::crossed_on_edge(const StepGap& step, double limit) const {
  // Slabs that overlap over a short stretch of y pass corner by corner: at the step end the
  // vertex is beyond the edge's line but also beyond its end, so only the crossing shows it.
  const double start = step.start.gap_m - limit, end = step.end.gap_m - limit;
  if (!(start > 0.0 && end < 0.0)) return false;
  auto gap_at = [&](double t) { return system_.gap(hermite(step.from, step.to, t), step.candidate); };
  const double t = find_root([&](double t) { return gap_at(t).gap_m - limit; }, step.from.t_s, step.to.t_s, start, end);
  return on_edge(hermite(step.from, step.to, t), step.candidate, gap_at(t));
}

bool HhtRun::dipped_on_edge(const StepGap& step, double limit) const {
  // Along the step the gap is close to the cubic Hermite polynomial of its values and rates at
  // both ends; its minima inside the step are where that cubic's derivative, a quadratic in
  // s = (t − t₀)/h, vanishes. The true gap is then checked there on the state's interpolant.
  const double h = step.to.t_s - step.from.t_s;
  const double g0 = step.start.gap_m, g1 = step.end.gap_m;
  const double r0 = h * step.start.gap_rate_mps, r1 = h * step.end.gap_rate_mps;
  const double a = 6 * g0 + 3 * r0 - 6 * g1 + 3 * r1, b = -6 * g0 - 4 * r0 + 6 * g1 - 2 * r1;
  const double c = r0;
  std::vector<double> roots;
  if (std::abs(a) < 1e-14 * (std::abs(b) + std::abs(c))) {
    if (b != 0.0) roots.push_back(-c / b);
  } else if (const double disc = b * b - 4 * a * c; disc >= 0.0) {
    const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));  // no cancellation
    if (q != 0.0) roots.push_back(c / q);
    roots.push_back(q / a);
  }
  for (double s : roots) {
    if (!(s > 0.0 && s < 1.0)) continue;
    const VectorXd y = hermite(step.from, step.to, step.from.t_s + s * h);
    const contact::GapState inside = system_.gap(y, step.candidate);
    if (inside.gap_m < limit && on_edge(y, step.candidate, inside)) return true;
  }
  return false;
}

bool HhtRun::closing_contact(const std::vector<double>& limits, const State& s) const {
  const VectorXd y = first_order(s);
  for (std::size_t i = 0; i < limits.size(); ++i) {
    const contact::GapState g = system_.gap(y, i);
    if (g.gap_m >= limits[i] && g.gap_m <= limits[i] + 2.0 * options_.contact_tolerance_m && g.gap_rate_mps < 0.0 &&
        on_edge(y, i, g)) {
      return true;
    }
  }
  return false;
}

void HhtRun::accept(const State& from, const State& to) {
  const double h = to.t_s - from.t_s;
  ++result_.statistics.steps;
  if (result_.statistics.smallest_step_s == 0.0 || h < result_.statistics.smallest_step_s) {
    result_.statistics.smallest_step_s = h;
  }
  recorder_.advance(
      from.t_s, to.t_s, first_order(to), [&](double t) { return hermite(from, to, t); },
      [](double, const VectorXd&) { return 0.0; }, energy_of_skipping_step(from, to));
  recorder_.add_algorithmic_dissipation(stepper_.algorithmic_dissipation(from, to));
  track_overlaps(to);
}

std::optional<StretchEnergy> HhtRun::energy_of_skipping_step(const State& from, const State& to) const {
  const excitation::GroundMotion& motion = system_.ground_motion();
  if (!undersampled_) return std::nullopt;
  const double h = to.t_s - from.t_s;
  const std::optional<double> next = motion.next_sample_after(from.t_s);
  if (!next || *next >= to.t_s - 1e-9 * h) return std::nullopt;
  const double half = 0.5 * h, mid = 0.5 * (from.t_s + to.t_s);
  StretchEnergy energy;
  for (std::size_t k = 0; k < kGaussNodes.size(); ++k) {
    const double t = mid + half * kGaussNodes[k];
    const VectorXd y = hermite(from, to, t);
    for (int c = 0; c < motion.component_count(); ++c) {
      // The step's own straight a_c between its ends, as the scheme saw it (not the record's samples).
      const double a_from = motion.accel_at(from.t_s, c), a_to = motion.accel_at(to.t_s, c);
      const double a_c = a_from + (a_to - a_from) * (t - from.t_s) / h;
      const VectorXd mass_influence = system_.mass_diagonal().cwiseProduct(system_.influence(c));
      energy.input_kJ -= half * kGaussWeights[k] * y.tail(system_.dof()).dot(mass_influence) * a_c;
    }
    energy.damping_kJ += half * kGaussWeights[k] * system_.damping_power(y);
  }
  return energy;
}

void HhtRun::track_overlaps(const State& s) {
  const VectorXd y = first_order(s);
  for (std::size_t i = 0; i < sunk_.size(); ++i) {
    const contact::GapState g = system_.gap(y, i);
    if (g.on_segment() && g.gap_m < -result_.statistics.max_interpenetration_m) {
      const double overlap_m =
          noted_overlap_m(g.gap_m, options_.contact_tolerance_m, [&] { return system_.depth_inside_m(y, i, g); });
      if (!std::isnan(overlap_m)) result_.statistics.note_overlap(overlap_m, s.t_s, i);
    }
    const bool now = sunk(y, i, g);
    if (now && !sunk_[i]) ++result_.statistics.unresolved_contacts;
    sunk_[i] = now;
  }
}

State HhtRun::settle(const State& s) {
  // Impacts at this step end: per group of levels that share a slab, every contact within the
  // tolerance or deeper solved together (an overlap that halving could not resolve still takes its
  // impulse, so it does not sink on); a touch is a pair that reaches g ≤ 0 (within the tolerance) without approaching.
  VectorXd y = first_order(s);
  const double tol = options_.contact_tolerance_m;
  std::vector<bool> in_contact(touching_.size(), false), touching(touching_.size(), false);
  std::set<int> levels;
  std::set<std::size_t> new_touches;
  for (std::size_t i = 0; i < touching_.size(); ++i) {
    const contact::GapState g = system_.gap(y, i);
    in_contact[i] = g.gap_m <= tol && on_edge(y, i, g);
    touching[i] = in_contact[i] && g.gap_m <= 0.0;
    if (!in_contact[i]) continue;
    if (approaching(g))
      levels.insert(system_.candidates()[i].level);
    else if (touching[i] && !touching_[i] && g.gap_m >= -tol)
      new_touches.insert(i);
  }
  bool changed = false;
  const TakeContact take = [&](std::size_t i, const contact::GapState&) { return in_contact[i]; };
  const std::set<std::vector<int>> groups = level_groups(system_, y, levels, take);
  std::set<int> resolved;  // every level of a group
  for (const std::vector<int>& group : groups) {
    resolved.insert(group.begin(), group.end());
    const FloorContacts contacts = gather_floor_contacts(system_, y, group, options_.restitution, take);
    const VectorXd before = y;
    const contact::ImpulseSolution solution = apply_impulses(system_, y, contacts);
    result_.statistics.note_lcp(solution.exact, solution.lcp_residual);
    recorder_.add_impact_loss(
        record_floor_outcome(system_, s.t_s, contacts, solution, before, y, new_touches, {}, {}, result_));
    recorder_.stream_new_impacts(result_.impacts);
    ++result_.statistics.restarts;
    ++result_.statistics.events;
    changed = true;
  }
  for (std::size_t i : new_touches) {
    if (resolved.count(system_.candidates()[i].level)) continue;  // recorded with its group's impact
    result_.touches.push_back(touch_record(system_, s.t_s, i, system_.gap(y, i)));
    ++result_.statistics.events;
  }
  touching_ = touching;
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
  const std::vector<double> limits = overlap_limits(s);
  double bracket_end = s.t_s + h;
  for (int depth = 1; depth <= options_.max_halvings; ++depth) {
    ++result_.statistics.halvings;
    const State trial = stepper_.step(s, (bracket_end - s.t_s) / 2.0);
    ++trial_steps_;
    if (!new_overlaps(limits, s, trial).empty()) {
      bracket_end = trial.t_s;
      continue;
    }
    accept(s, trial);
    s = trial;
    if (closing_contact(limits, s)) return settle(s);  // found the contact: on with the full Δt
  }
  // Deepest level reached without a state within the tolerance: step to the bracket end and
  // apply the impact there, overlapping as it is (accept counts it).
  const State trial = stepper_.step(s, bracket_end - s.t_s);
  ++trial_steps_;
  accept(s, trial);
  return settle(trial);
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
    t_contact = std::min(t_contact, find_root([&](double t) { return gap_at(t, candidate); }, s.t_s, trial.t_s, g_start,
                                              gap_at(trial.t_s, candidate)));
  }
  const State redone = stepper_.step(s, t_contact - s.t_s);
  ++trial_steps_;
  accept(s, redone);
  return settle(redone);
}

void HhtRun::report_overlaps() {
  // Every candidate, corner ones included, is examined at every step end: all are armed.
  SolverStatistics& stats = result_.statistics;
  for (const contact::Candidate& c : system_.candidates()) stats.corner_candidates += c.corner;
  stats.corner_candidates_armed = stats.corner_candidates;
  if (stats.unresolved_contacts == 0 || result_.status != RunStatus::completed) return;
  const contact::Candidate& c = system_.candidates()[static_cast<std::size_t>(stats.max_interpenetration_candidate)];
  result_.status = RunStatus::unresolved_overlap;
  result_.status_detail = fmt::format(
      "{} overlap{} deeper than the contact tolerance {} m not resolved; deepest {:.3g} m at {:.4f} s, level {}: {}",
      stats.unresolved_contacts, stats.unresolved_contacts == 1 ? "" : "s", options_.contact_tolerance_m,
      stats.max_interpenetration_m, stats.max_interpenetration_t_s, c.level, contact::describe(c));
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
    const std::vector<std::size_t> overlaps = new_overlaps(overlap_limits(s), s, trial);
    if (overlaps.empty()) {
      accept(s, trial);
      s = settle(trial);
      continue;
    }
    switch (options_.location) {
      case HhtEventLocation::end_of_step:
        accept(s, trial);
        s = settle(trial);
        break;
      case HhtEventLocation::halving: s = halve(s, h); break;
      case HhtEventLocation::interpolate: s = interpolate(s, trial, overlaps); break;
    }
  }
  result_.end_s = s.t_s;
  result_.statistics.rhs_evaluations = trial_steps_;  // one effective-stiffness solve per trial step
  result_.statistics.jacobian_evaluations = stepper_.factorizations();
  recorder_.finish(first_order(s), result_);
  report_overlaps();
  result_.statistics.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return std::move(result_);
}

}  // namespace

RunResult run_hht(const dynamics::CoupledSystem& system, const HhtOptions& options, const std::string& method) {
  options.validate();
  if (options.initial_state.size() != 0 && options.initial_state.size() != system.state_size()) {
    throw InputError("initial_state", std::to_string(options.initial_state.size()) + " values",
                     "needs one value per state (" + std::to_string(system.state_size()) + ")");
  }
  if (contact::has_column_pairs(system.candidates())) {  // HHT resolves impulses slab against slab
    throw InputError("method", "hht", "cannot resolve slab-to-column contacts: they need a compliant law");
  }
  HhtRun run(system, options);
  return run.run(method);
}

}  // namespace pounding::solvers
