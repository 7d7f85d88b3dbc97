#include "pounding/analysis/needed_gap.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <map>
#include <mutex>
#include <numbers>
#include <optional>

#include "pounding/analysis/run_scene.hpp"
#include "pounding/input_error.hpp"
#include "pounding/model/mode.hpp"
#include "pounding/solvers/cvode_integrator.hpp"
#include "pounding/solvers/event_options.hpp"
#include "pounding/solvers/gap_mode_bound.hpp"
#include "pounding/solvers/simulator.hpp"
#include "pounding/solvers/yield_states.hpp"
#include "parallel.hpp"

namespace pounding::analysis {

GapRules gap_rules(double delta1_m, double delta2_m, double rho) {
  const double sum_of_squares = delta1_m * delta1_m + delta2_m * delta2_m;
  return {delta1_m + delta2_m, std::sqrt(sum_of_squares),
          std::sqrt(std::max(0.0, sum_of_squares - 2.0 * rho * delta1_m * delta2_m))};
}

double cqc_correlation(double period1_s, double damping1, double period2_s, double damping2) {
  const double r = period1_s / period2_s;  // ω₂/ω₁
  const double numerator = 8.0 * std::sqrt(damping1 * damping2) * (damping1 + r * damping2) * std::pow(r, 1.5);
  const double denominator = (1.0 - r * r) * (1.0 - r * r) + 4.0 * damping1 * damping2 * r * (1.0 + r * r) +
                             4.0 * (damping1 * damping1 + damping2 * damping2) * r * r;
  return numerator / denominator;
}

namespace {

using dynamics::CoupledSystem;
using Eigen::VectorXd;
/// A mode moving no gap by more than this (m) sets no step bound (as overlap_allowance_m does in
/// the event-driven loop): it could shift the needed gap by about this much at most.
constexpr double kGapResolution_m = 1e-9;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// A pair counts when widening the gap opens it at rest at least this fast (b = ∂g/∂G): edges
// within 84° of facing the other building. Edges along x (b = 0) do not move apart with the gap.
constexpr double kMinimumOpeningRate = 0.1;

Eigen::Matrix2d rotation(double phi) {
  const double c = std::cos(phi), s = std::sin(phi);
  return (Eigen::Matrix2d() << c, -s, s, c).finished();
}

/// +1 when building 2 owns the vertex (moving it along +x moves the vertex), −1 when it owns the edge.
double shift_sign(const contact::Candidate& c) { return c.striking_building == 1 ? 1.0 : -1.0; }

/// One pair seen at the gap where it just touches.
struct Touch {
  double gap_m = 0.0;  // the touch gap G(t)
  double rate = 0.0;   // −b dG/dt: the pair's ġ in that geometry (negative while G rises)
  bool on_segment = false;
};

/// A facing vertex of one building at one level (or a column point between two floors): its
/// displacement towards the other building.
struct FacingPoint {
  int building = 0;
  int floor = 1;
  std::size_t level_slot = 0;  // index into the level list
  model::Point2 arm_rest;      // from the CM at rest (m)
  /// A column point: carried by `floor` with weight N₂ and by `lower_floor` (0: the ground) with
  /// N₁ (contact::column_shape); a slab vertex: N₂ = 1, no lower floor.
  int lower_floor = 0;
  std::array<double, 2> weights{0.0, 1.0};
};

/// The touch geometry of the pairs and facing points: where each pair just touches as the gap
/// changes, and how far each facing point has moved towards the other building.
class TouchGeometry {
 public:
  TouchGeometry(const CoupledSystem& system, double scene_gap_m, std::vector<FacingPoint> points,
                std::vector<std::size_t> slots)
      : system_(system), scene_gap_m_(scene_gap_m), points_(std::move(points)), slots_(std::move(slots)) {}

  Touch touch(const Eigen::Ref<const VectorXd>& y, std::size_t i) const {
    const contact::Candidate& c = system_.candidates()[i];
    const contact::GapState s = system_.gap(y, i);
    const double sigma = shift_sign(c);
    const int struck = c.struck_building;
    const int q = system_.floor_index(struck, c.floors[struck]) + 2;
    const double spin = y[system_.dof() + q];
    const double b = sigma * s.normal.x();
    const double b_dot = -sigma * spin * s.normal.y();
    const double shift = -s.gap_m / b;  // G − G₀
    const model::Point2 edge = rotation(y[q]) * (c.edge_end_rest - c.edge_start_rest);
    const double param = s.segment_param + sigma * shift * edge.x() / edge.squaredNorm();
    return {scene_gap_m_ + shift, -(s.gap_rate_mps + shift * b_dot),
            param >= -contact::kOnSegmentTolerance && param <= 1.0 + contact::kOnSegmentTolerance};
  }

  /// Displacement (m) of the point towards the other building, and its rate (m/s).
  std::pair<double, double> towards(const Eigen::Ref<const VectorXd>& y, const FacingPoint& p) const {
    const auto [dx, dx_dot] = carried(y, p.building, p.floor, p.arm_rest);
    const double direction = p.building == 0 ? 1.0 : -1.0;
    if (p.lower_floor == 0) return {direction * p.weights[1] * dx, direction * p.weights[1] * dx_dot};
    const auto [lower_dx, lower_dx_dot] = carried(y, p.building, p.lower_floor, p.arm_rest);
    return {direction * (p.weights[0] * lower_dx + p.weights[1] * dx),
            direction * (p.weights[0] * lower_dx_dot + p.weights[1] * dx_dot)};
  }

  const std::vector<FacingPoint>& points() const { return points_; }
  /// The entry of NeededGap::levels that candidate i belongs to.
  std::size_t slot(std::size_t i) const { return slots_[i]; }

 private:
  /// The x displacement (m) and its rate (m/s) of the point at `arm_rest` from the CM as `floor`
  /// of `building` carries it.
  std::pair<double, double> carried(const Eigen::Ref<const VectorXd>& y, int building, int floor,
                                    const model::Point2& arm_rest) const {
    const int i = system_.floor_index(building, floor);
    const model::Point2 arm = rotation(y[i + 2]) * arm_rest;
    return {y[i] + arm.x() - arm_rest.x(), y[system_.dof() + i] - y[system_.dof() + i + 2] * arm.y()};
  }

  const CoupledSystem& system_;
  double scene_gap_m_;
  std::vector<FacingPoint> points_;
  std::vector<std::size_t> slots_;
};

/// The contact-free run's root functions, by name. Every pair and point root falls through zero
/// at a maximum: a counted pair's touch gap (−ġ at its touch geometry), a facing point's
/// displacement towards the other building (its velocity that way); then each yielding column
/// spring's branch change (YieldStates).
class FreeRunRoots {
 public:
  FreeRunRoots(std::size_t pairs, std::size_t points, std::size_t springs)
      : pairs_(pairs), points_(points), springs_(springs) {}
  int size() const { return static_cast<int>(pairs_ + points_ + springs_); }
  Eigen::Index pair(std::size_t i) const { return static_cast<Eigen::Index>(i); }
  Eigen::Index point(std::size_t k) const { return static_cast<Eigen::Index>(pairs_ + k); }
  Eigen::Index spring(std::size_t j) const { return static_cast<Eigen::Index>(pairs_ + points_ + j); }
  bool flagged(const std::vector<int>& flags, Eigen::Index root) const {
    return flags[static_cast<std::size_t>(root)] != 0;
  }

 private:
  std::size_t pairs_, points_, springs_;
};

std::vector<bool> counted_pairs(const CoupledSystem& system) {
  std::vector<bool> counted;
  // A corner candidate (a side edge, an edge facing away) does not close as the gap closes.
  for (const contact::Candidate& c : system.candidates())
    counted.push_back(!c.corner && shift_sign(c) * c.normal_rest.x() > kMinimumOpeningRate);
  return counted;
}

/// The entries of NeededGap::levels: the levels, then one per slab facing columns (its slab's
/// building and floor), in candidate order; and per candidate the index of its entry.
std::vector<std::size_t> facade_entries(const CoupledSystem& system, std::vector<LevelGap>& entries) {
  for (const contact::Level& level : system.levels()) entries.push_back({.level = level});
  std::vector<std::size_t> slots;
  for (const contact::Candidate& c : system.candidates()) {
    const auto same = [&](const LevelGap& e) {
      return c.column ? e.column && e.slab_building == c.struck_building && e.level.floors == c.floors
                      : !e.column && e.level.index == c.level;
    };
    auto entry = std::find_if(entries.begin(), entries.end(), same);
    if (entry == entries.end()) {  // a slab facing columns, seen first
      entries.push_back({.level = {0, c.floors, c.elevation_m},
                         .column = true,
                         .slab_building = c.struck_building,
                         .storey = c.floor_of(c.striking_building),
                         .height_ratio = c.height_ratio});
      entry = entries.end() - 1;
    }
    slots.push_back(static_cast<std::size_t>(entry - entries.begin()));
  }
  for (LevelGap& entry : entries) entry.needed_gap_m = -std::numeric_limits<double>::infinity();
  return slots;
}

/// The vertices of each building that take part in a counted pair at each entry (the facing
/// edge), and the column points at the slabs facing columns.
std::vector<FacingPoint> facing_points(const CoupledSystem& system, const std::vector<bool>& counted,
                                       const std::vector<std::size_t>& slots) {
  std::vector<FacingPoint> points;
  auto add = [&](FacingPoint point, const model::Point2& rest) {
    point.arm_rest = rest - system.building(point.building).definition.centre_of_mass;
    for (const FacingPoint& p : points) {
      if (p.building == point.building && p.level_slot == point.level_slot &&
          (p.arm_rest - point.arm_rest).norm() < 1e-12)
        return;
    }
    points.push_back(point);
  };
  for (std::size_t i = 0; i < counted.size(); ++i) {
    if (!counted[i]) continue;
    const contact::Candidate& c = system.candidates()[i];
    FacingPoint vertex{
        .building = c.striking_building, .floor = c.floor_of(c.striking_building), .level_slot = slots[i]};
    if (c.column) {
      const auto [lower, upper] = contact::column_shape(c.height_ratio);
      vertex.lower_floor = c.lower_floor;
      vertex.weights = {lower, upper};
    }
    add(vertex, c.vertex_rest);
    const FacingPoint edge{
        .building = c.struck_building, .floor = c.floor_of(c.struck_building), .level_slot = slots[i]};
    add(edge, c.edge_start_rest);
    add(edge, c.edge_end_rest);
  }
  return points;
}

GapMode gap_mode(const model::Building& building) {
  const std::vector<model::Mode>& modes = building.modes;
  std::size_t k = 0;
  while (k < modes.size() && modes[k].dominant != model::ModeComponent::x) ++k;
  if (k == modes.size()) k = 0;  // no mode dominated by x: the fundamental one
  const double omega = modes[k].omega_rad_s;
  const double ratio = building.rayleigh.a0_per_s / (2.0 * omega) + building.rayleigh.a1_s * omega / 2.0;
  return {static_cast<int>(k) + 1, modes[k].period_s, ratio};
}

/// Takes the pairs' touch gaps and the facing points' displacements at (t, y) into the result
/// where they exceed what it holds: all of them, or only those whose root `found` flags (a root
/// return, laid out as `roots`).
void note_maxima(const TouchGeometry& geometry, double t, const VectorXd& y, const std::vector<bool>& counted,
                 NeededGap& result, const FreeRunRoots* roots = nullptr, const std::vector<int>* found = nullptr) {
  for (std::size_t i = 0; i < counted.size(); ++i) {
    if (!counted[i] || (found && !roots->flagged(*found, roots->pair(i)))) continue;
    if (found) ++result.extrema;
    const Touch touch = geometry.touch(y, i);
    LevelGap& level = result.levels[geometry.slot(i)];
    if (touch.on_segment && touch.gap_m > level.needed_gap_m) {
      level.needed_gap_m = touch.gap_m;
      level.t_s = t;
      level.candidate = static_cast<long>(i);
    }
  }
  for (std::size_t k = 0; k < geometry.points().size(); ++k) {
    if (found && !roots->flagged(*found, roots->point(k))) continue;
    const FacingPoint& p = geometry.points()[k];
    const double towards = geometry.towards(y, p).first;
    LevelGap& level = result.levels[p.level_slot];
    if (towards > level.peak_towards_m[p.building]) {
      level.peak_towards_m[p.building] = towards;
      level.peak_t_s[p.building] = t;
    }
  }
}

/// The contact-free run as a HybridSystem (solvers/simulator.hpp): the buildings' free motion
/// with their yielding columns, its roots the maxima of the touch gaps and of the facing points'
/// displacements (noted into the result) and the columns' branch changes (which restart it). The
/// state is sampled every `history_interval_s` for the history.
class FreeRunSystem final : public solvers::HybridSystem {
 public:
  FreeRunSystem(const CoupledSystem& system, const TouchGeometry& geometry, const std::vector<bool>& counted,
                double history_interval_s, NeededGap& result, std::vector<VectorXd>& samples)
      : system_(system),
        geometry_(geometry),
        counted_(counted),
        yields_(system.springs(), solvers::EventOptions{}.max_events_per_s),
        roots_(counted.size(), geometry.points().size(), yields_.size()),
        bound_(system, kGapResolution_m, 4.0),
        interval_s_(history_interval_s),
        result_(result),
        samples_(samples) {
    for (int b = 0; b < system.building_count(); ++b) building_names_.push_back(system.building(b).definition.name);
  }

  int state_size() const override { return system_.state_size(); }
  int root_count() const override { return roots_.size(); }
  // Yielding columns change the Jacobian at their branch changes.
  bool is_linear() const override { return yields_.empty(); }
  void rhs(double t, const Eigen::Ref<const VectorXd>& y, Eigen::Ref<VectorXd> y_dot) override {
    system_.rhs(t, y, y_dot, yields_.states());
  }
  void jacobian(double, const Eigen::Ref<const VectorXd>& y, Eigen::Ref<Eigen::MatrixXd> jac) override {
    if (yields_.empty()) {
      jac = system_.jacobian();
      return;
    }
    Eigen::SparseMatrix<double> rows;
    system_.constrained_acceleration_jacobian(y, {}, rows, yields_.states());
    system_.full_jacobian(y, rows, jac);
  }
  // Sparse, so that CVODE's Newton matrices cost O(n) to factor rather than O(n³).
  bool acceleration_jacobian(double, const Eigen::Ref<const VectorXd>& y, Eigen::SparseMatrix<double>& rows) override {
    system_.constrained_acceleration_jacobian(y, {}, rows, yields_.states());
    return true;
  }
  int extra_state_count() const override { return system_.springs().smooth_count(); }
  void extra_state_jacobian(double, const Eigen::Ref<const VectorXd>& y, Eigen::SparseMatrix<double>& accel_by_w,
                            Eigen::SparseMatrix<double>& w_rate_by_velocity, VectorXd& w_rate_by_w) override {
    system_.smooth_jacobian(y, {}, accel_by_w, w_rate_by_velocity, w_rate_by_w);
  }
  void roots(double, const Eigen::Ref<const VectorXd>& y, Eigen::Ref<VectorXd> g) override {
    for (std::size_t i = 0; i < counted_.size(); ++i)
      g[roots_.pair(i)] = counted_[i] ? geometry_.touch(y, i).rate : 1.0;
    for (std::size_t k = 0; k < geometry_.points().size(); ++k)
      g[roots_.point(k)] = geometry_.towards(y, geometry_.points()[k]).second;
    for (std::size_t j = 0; j < yields_.size(); ++j) g[roots_.spring(j)] = yields_.witness(y, j);
  }

  // The phases (simulator.hpp).
  void start(double t0, VectorXd& y) override {
    note_maxima(geometry_, t0, y, counted_, result_);
    next_sample_s_ = t0;
    t0_ = t0;
  }
  // As in the event-driven loop: a quarter of the shortest damped period among the modes that
  // move a gap (so no rate changes sign twice in a step unseen).
  void begin_phase(double, const VectorXd& y, solvers::Integrator& integrator) override {
    integrator.set_max_step(bound_.max_step_s(y));
  }
  // A root function that stays at zero after a root (a column spring whose witness rests at zero)
  // is an illegal input to CVODE's next root check; a restart there takes it as a root at the
  // start, which CVODE leaves alone until it moves. Once at an instant, then a failure.
  bool recover(double t, const VectorXd&, const std::string& failure) override {
    if (failure.find("CV_ILL_INPUT") == std::string::npos || restarted_at_s_ == t) return false;
    restarted_at_s_ = t;
    return true;
  }
  void record(double, double t_b, const VectorXd&, solvers::Integrator& integrator) override {
    VectorXd state(system_.state_size());
    for (; next_sample_s_ <= t_b; next_sample_s_ = t0_ + static_cast<double>(samples_.size()) * interval_s_) {
      integrator.interpolate(next_sample_s_, state);
      samples_.push_back(state);
      result_.history_t_s.push_back(next_sample_s_);
    }
  }
  // A root: the maxima it marks, then the columns that switch branch (the equations change).
  bool on_event(double t, VectorXd& y, const solvers::EventCause& cause) override {
    note_maxima(geometry_, t, y, counted_, result_, &roots_, &cause.root_flags);
    int switched = 0;
    if (!yields_.empty()) {
      VectorXd y_dot(system_.state_size());
      rhs(t, y, y_dot);
      switched = yields_.switch_branches(t, y, y_dot);
      result_.yield_events += switched;
    }
    check_columns(t, y);
    return switched > 0;
  }
  void after_step(double t, const VectorXd& y, solvers::Integrator& integrator) override {
    check_columns(t, y);
    if (!stopped_) integrator.set_max_step(bound_.max_step_s(y));
  }
  bool stopped() const override { return stopped_; }

 private:
  /// Ends the run if its yielding columns call for it (YieldStates::stop: collapse, chattering).
  void check_columns(double t, const VectorXd& y) {
    if (yields_.empty() || stopped_) return;
    if (std::optional<solvers::YieldingStop> stop = yields_.stop(t, y, building_names_)) {
      result_.status = stop->status;
      result_.status_detail = std::move(stop->detail);
      stopped_ = true;
    }
  }

  const CoupledSystem& system_;
  const TouchGeometry& geometry_;
  const std::vector<bool>& counted_;
  solvers::YieldStates yields_;
  FreeRunRoots roots_;
  solvers::GapModeBound bound_;
  std::vector<std::string> building_names_;  // for the columns' messages
  double interval_s_;
  NeededGap& result_;
  std::vector<VectorXd>& samples_;
  double t0_ = 0.0, next_sample_s_ = 0.0;
  double restarted_at_s_ = -std::numeric_limits<double>::infinity();
  bool stopped_ = false;
};

/// Integrates the free motion over the record on CVODE (Adams or BDF as `options` say), noting
/// every maximum into `result`; samples the states every options.history_interval_s.
void integrate(const CoupledSystem& system, const NeededGapOptions& options, const TouchGeometry& geometry,
               const std::vector<bool>& counted, NeededGap& result, std::vector<VectorXd>& samples) {
  solvers::CvodeSettings settings;
  settings.method = options.adams ? solvers::CvodeMethod::adams : solvers::CvodeMethod::bdf;
  settings.rtol = options.rtol;
  settings.atol = options.atol;
  FreeRunSystem run(system, geometry, counted, options.history_interval_s, result, samples);
  solvers::Simulator simulator(run, system.ground_motion(), {.budget = options.budget});
  const solvers::SimulatorOutcome outcome =
      simulator.run(system.ground_motion().start_s(), VectorXd::Zero(system.state_size()),
                    [&](solvers::OdeFunctions& functions, double t0, const VectorXd& y0) {
                      return std::make_unique<solvers::CvodeIntegrator>(functions, settings, t0, y0);
                    });
  if (outcome.status == solvers::RunStatus::solver_failure) {
    throw std::runtime_error(fmt::format("contact-free run failed {}", outcome.detail));
  }
  if (outcome.status != solvers::RunStatus::completed) {
    result.status = outcome.status;
    result.status_detail = outcome.detail;
  }
  note_maxima(geometry, outcome.end_s, outcome.end_state, counted, result);  // maxima still rising at the end
  result.steps += outcome.counters.steps;
  result.end_s = outcome.end_s;
}

void fill_history(const TouchGeometry& run, const std::vector<VectorXd>& samples, NeededGap& result) {
  for (const LevelGap& level : result.levels) {
    std::vector<double> column;
    for (const VectorXd& y : samples) {
      if (level.candidate < 0) {
        column.push_back(kNaN);
        continue;
      }
      const Touch touch = run.touch(y, static_cast<std::size_t>(level.candidate));
      column.push_back(touch.on_segment ? touch.gap_m : kNaN);
    }
    result.history_touch_gap_m.push_back(std::move(column));
  }
}

}  // namespace

void NeededGapOptions::validate() const {
  auto positive = [](double value, const char* field) {
    if (!(value > 0.0) || !std::isfinite(value)) throw InputError(field, format_value(value), "must be positive");
  };
  require_range("rtol", rtol, *spec(Setting::rtol).range);
  require_range("atol", atol, *spec(Setting::atol).range);
  positive(history_interval_s, "history_interval_s");
  budget.validate();
}

namespace {

/// needed_gap(system, ...) that also hands back the states it sampled every
/// options.history_interval_s (superposed by add_all_angles).
NeededGap sampled_needed_gap(const CoupledSystem& system, double scene_gap_m, const NeededGapOptions& options,
                             std::vector<VectorXd>* states) {
  options.validate();
  const auto clock_start = std::chrono::steady_clock::now();
  NeededGap result;
  result.scene_gap_m = scene_gap_m;
  result.candidates = system.candidates();
  result.yielding = !system.springs().empty();
  result.counted = counted_pairs(system);
  std::vector<std::size_t> slots = facade_entries(system, result.levels);
  for (int b = 0; b < 2; ++b) result.modes[b] = gap_mode(system.building(b));
  result.rho = cqc_correlation(result.modes[0].period_s, result.modes[0].damping_ratio, result.modes[1].period_s,
                               result.modes[1].damping_ratio);

  std::vector<FacingPoint> points = facing_points(system, result.counted, slots);
  const TouchGeometry geometry(system, scene_gap_m, std::move(points), std::move(slots));
  std::vector<VectorXd> samples;
  integrate(system, options, geometry, result.counted, result, samples);
  fill_history(geometry, samples, result);
  if (states) *states = std::move(samples);

  result.needed_gap_m = -std::numeric_limits<double>::infinity();
  for (LevelGap& level : result.levels) {
    level.rules = gap_rules(level.peak_towards_m[0], level.peak_towards_m[1], result.rho);
    result.rules.abs_m = std::max(result.rules.abs_m, level.rules.abs_m);
    result.rules.srss_m = std::max(result.rules.srss_m, level.rules.srss_m);
    result.rules.ddc_m = std::max(result.rules.ddc_m, level.rules.ddc_m);
    if (level.needed_gap_m > result.needed_gap_m) {
      result.needed_gap_m = level.needed_gap_m;
      result.t_s = level.t_s;
      result.level = level.candidate >= 0 ? level.level.index : 0;
      result.entry = level.candidate >= 0 ? &level - result.levels.data() : -1;
      result.candidate = level.candidate;
    }
  }
  result.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return result;
}

/// The contact-free run's options for `scene`: its solver's tolerances (Adams for cvode-adams).
NeededGapOptions scene_options(const Scene& scene, const solvers::RunBudget& budget) {
  const UsedSettings used = resolve(scene.solver);  // the scene's tolerances, or the defaults
  return {.adams = scene.solver.method == "cvode-adams", .rtol = used.rtol, .atol = used.atol, .budget = budget};
}

}  // namespace

NeededGap needed_gap(const Scene& scene, const solvers::RunBudget& budget) {
  if (scene.is_row()) {
    throw InputError("building", fmt::format("{} buildings", scene.buildings.size()),
                     "form a row, whose needed gaps are found pair by pair (pounding gap does; from Python, "
                     "needed_gap on each of Scene.pair_scenes())",
                     scene.file.string());
  }
  const auto clock_start = std::chrono::steady_clock::now();
  const CoupledSystem system = build_system(scene);
  NeededGap result;
  try {
    result = needed_gap(system, scene.contact.gap_m, scene_options(scene, budget));
  } catch (const InputError& error) {
    throw error.in_context(scene.file.string());
  }
  result.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return result;
}

NeededGap needed_gap(const CoupledSystem& system, double scene_gap_m, const NeededGapOptions& options) {
  return sampled_needed_gap(system, scene_gap_m, options, nullptr);
}

void add_amplified_elastic(const Scene& scene, double factor, NeededGap& gap, const solvers::RunBudget& budget) {
  require_range("amplification", factor, kAmplificationFactor);
  Scene elastic = scene;
  bool yields = false;
  for (model::BuildingDefinition& b : elastic.buildings) {
    yields = yields || b.hysteresis.yields();
    b.hysteresis = {};
  }
  if (!yields) {
    throw InputError("amplification", format_value(factor),
                     "applies to scenes whose columns yield (the code rules of an elastic scene are already printed)");
  }
  const NeededGap free = needed_gap(elastic, budget);
  AmplifiedElastic amplified{
      .factor = factor, .elastic_needed_gap_m = free.needed_gap_m, .rules = {}, .status = free.status};
  for (const LevelGap& level : free.levels) {
    const GapRules rules = gap_rules(factor * level.peak_towards_m[0], factor * level.peak_towards_m[1], free.rho);
    amplified.rules.abs_m = std::max(amplified.rules.abs_m, rules.abs_m);
    amplified.rules.srss_m = std::max(amplified.rules.srss_m, rules.srss_m);
    amplified.rules.ddc_m = std::max(amplified.rules.ddc_m, rules.ddc_m);
  }
  gap.amplified_elastic = amplified;
}

namespace {

constexpr double kSuperpositionStep_deg = 1.0;
constexpr double kSweepStep_deg = 10.0;
constexpr double kEnvelopeInterval_s = 0.005;
constexpr double kMaxEnvelopeSamples = 50'000;  // per run: the sample interval grows for longer records
constexpr double kMaxEnvelopeBytes = 256e6;     // per run's kept states: bounds it for tall buildings

Scene turned_to(const Scene& scene, double angle_deg) {
  Scene turned = scene;
  turned.excitation.direction_deg = angle_deg;
  return turned;
}

void note_status(const NeededGap& run, AllAngles& all) {
  ++all.runs;
  if (all.status == solvers::RunStatus::completed) all.status = run.status;
}

/// One angle's contact-free run; a run that fails is noted with its angle (the first such in
/// AllAngles::status_detail) and gives no needed gap (NaN), so the others still count.
NeededGap run_at(const Scene& scene, double angle_deg, const solvers::RunBudget& budget, AllAngles& all) {
  NeededGap run;
  try {
    run = needed_gap(turned_to(scene, angle_deg), budget);
  } catch (const std::runtime_error& error) {
    if (dynamic_cast<const InputError*>(&error)) throw;
    run.status = solvers::RunStatus::solver_failure;
    run.status_detail = error.what();
    run.needed_gap_m = std::numeric_limits<double>::quiet_NaN();
  }
  if (run.status != solvers::RunStatus::completed && all.status_detail.empty()) {
    all.status_detail =
        fmt::format("the run with the record along {:g} deg: {}{}", angle_deg, solvers::to_string(run.status),
                    run.status_detail.empty() ? "" : " (" + run.status_detail + ")");
  }
  note_status(run, all);
  return run;
}

/// Elastic buildings: the motion at angle θ is cos θ y₀(t) + sin θ y₉₀(t), so two contact-free
/// runs sampled on one time grid give every angle's touch gaps, evaluated exactly (rotation
/// included) at the combined states.
void superposed_envelope(const Scene& scene, const solvers::RunBudget& budget, AllAngles& all) {
  const CoupledSystem along_0 = build_system(turned_to(scene, 0.0)), along_90 = build_system(turned_to(scene, 90.0));
  NeededGapOptions options = scene_options(scene, budget);
  const excitation::GroundMotion& motion = along_0.ground_motion();
  const double most_samples =
      std::min(kMaxEnvelopeSamples, kMaxEnvelopeBytes / (8.0 * static_cast<double>(along_0.state_size())));
  options.history_interval_s = std::max(kEnvelopeInterval_s, (motion.end_s() - motion.start_s()) / most_samples);
  std::vector<VectorXd> states_0, states_90;
  const NeededGap run_0 = sampled_needed_gap(along_0, scene.contact.gap_m, options, &states_0);
  note_status(run_0, all);
  note_status(sampled_needed_gap(along_90, scene.contact.gap_m, options, &states_90), all);
  const TouchGeometry pairs(along_0, scene.contact.gap_m, {}, {});  // a pair's touch gap is geometry alone
  const std::size_t samples = std::min(states_0.size(), states_90.size());
  VectorXd state(along_0.state_size());
  all.method = "superposition";
  all.step_deg = kSuperpositionStep_deg;
  all.sample_interval_s = options.history_interval_s;
  for (double angle = 0.0; angle < 360.0 - 1e-9; angle += kSuperpositionStep_deg) {
    const double c = std::cos(angle * std::numbers::pi / 180.0), s = std::sin(angle * std::numbers::pi / 180.0);
    AngleGap at{angle, -std::numeric_limits<double>::infinity()};
    for (std::size_t k = 0; k < samples; ++k) {
      state = c * states_0[k] + s * states_90[k];
      for (std::size_t i = 0; i < run_0.counted.size(); ++i) {
        if (!run_0.counted[i]) continue;
        const Touch touch = pairs.touch(state, i);
        if (touch.on_segment) at.needed_gap_m = std::max(at.needed_gap_m, touch.gap_m);
      }
    }
    all.envelope.push_back(at);
  }
}

/// Yielding buildings: no superposition; one contact-free run per angle.
void swept_envelope(const Scene& scene, const solvers::RunBudget& budget, AllAngles& all) {
  all.method = "sweep";
  all.step_deg = kSweepStep_deg;
  for (double angle = 0.0; angle < 360.0 - 1e-9; angle += kSweepStep_deg) {
    all.envelope.push_back({angle, run_at(scene, angle, budget, all).needed_gap_m});
  }
}

/// Golden-section search with full runs within one envelope step of the estimate.
void refine_worst_angle(const Scene& scene, const solvers::RunBudget& budget, AllAngles& all) {
  std::map<double, NeededGap> runs;
  auto at = [&](double angle) -> double {
    auto found = runs.find(angle);
    if (found == runs.end()) found = runs.emplace(angle, run_at(scene, angle, budget, all)).first;
    // A failed angle's NaN never wins a comparison: the search goes the other way.
    return std::isnan(found->second.needed_gap_m) ? -std::numeric_limits<double>::infinity()
                                                  : found->second.needed_gap_m;
  };
  const double golden = (std::sqrt(5.0) - 1.0) / 2.0;
  double low = all.estimate.angle_deg - all.step_deg, high = all.estimate.angle_deg + all.step_deg;
  double a = high - golden * (high - low), b = low + golden * (high - low);
  at(all.estimate.angle_deg);
  while (high - low > all.refine_tolerance_deg) {
    if (at(a) >= at(b)) {
      high = b, b = a, a = high - golden * (high - low);
    } else {
      low = a, a = b, b = low + golden * (high - low);
    }
  }
  const auto worst = std::max_element(runs.begin(), runs.end(), [](const auto& x, const auto& y) {
    return std::isnan(x.second.needed_gap_m) || x.second.needed_gap_m < y.second.needed_gap_m;
  });
  all.worst = {std::fmod(worst->first + 360.0, 360.0), worst->second.needed_gap_m};
  all.worst_level = worst->second.level;
  all.worst_t_s = worst->second.t_s;
  all.worst_candidate = worst->second.candidate;
}

}  // namespace

void add_all_angles(const Scene& scene, NeededGap& gap, const solvers::RunBudget& budget) {
  AllAngles all;
  all.record_angle_deg = scene.excitation.direction_deg;
  bool yields = false;
  for (const model::BuildingDefinition& b : scene.buildings) yields = yields || b.hysteresis.yields();
  if (yields) {
    swept_envelope(scene, budget, all);
  } else {
    superposed_envelope(scene, budget, all);
  }
  all.estimate = *std::max_element(all.envelope.begin(), all.envelope.end(), [](const AngleGap& x, const AngleGap& y) {
    return std::isnan(x.needed_gap_m) || x.needed_gap_m < y.needed_gap_m;  // a failed angle never the largest
  });
  refine_worst_angle(scene, budget, all);
  gap.all_angles = std::move(all);
}

std::vector<RuleVerdict> rule_verdicts(const GapRules& rules, double needed_gap_m) {
  return {{"ABS", rules.abs_m, rules.abs_m - needed_gap_m},
          {"SRSS", rules.srss_m, rules.srss_m - needed_gap_m},
          {"DDC", rules.ddc_m, rules.ddc_m - needed_gap_m}};
}

std::vector<RuleVerdict> rule_verdicts(const NeededGap& gap) { return rule_verdicts(gap.rules, gap.needed_gap_m); }

namespace {

SeverityPoint severity_at(Scene scene, double gap_m) {
  scene.set_gap(gap_m);
  scene.output.history = false;  // a point keeps impact statistics only
  scene.output.peaks.clear();
  const RunReport report = run_scene(scene);
  SeverityPoint point;
  point.gap_m = gap_m;
  point.status = std::string(solvers::to_string(report.result.status));
  point.impacts = static_cast<long>(report.result.impacts.size());
  for (const solvers::ImpactRecord& impact : report.result.impacts) {
    point.max_impulse_kNs = std::max(point.max_impulse_kNs, impact.impulse_kNs);
    point.max_approach_mps = std::max(point.max_approach_mps, impact.approach_velocity_mps);
  }
  point.energy_lost_kJ = report.result.energy.impact_loss_kJ;
  point.wall_time_s = report.result.statistics.wall_time_s;
  return point;
}

}  // namespace

std::vector<SeverityPoint> severity_curve(const Scene& scene, double needed_gap_m, int count, unsigned threads,
                                          const std::function<void(const SeverityPoint&)>& progress) {
  if (count < 2) throw InputError("count", std::to_string(count), "needs at least 2 gaps");
  if (!(needed_gap_m > 0.0) || !std::isfinite(needed_gap_m)) {
    throw InputError("needed_gap_m", format_value(needed_gap_m), "must be positive: no gap short of it to try");
  }
  std::vector<SeverityPoint> points(static_cast<std::size_t>(count));
  std::mutex progress_mutex;
  detail::parallel_for(points.size(), threads, [&](std::size_t k) {
    points[k] = severity_at(scene, needed_gap_m * static_cast<double>(k) / count);
    if (progress) {
      const std::lock_guard<std::mutex> lock(progress_mutex);
      progress(points[k]);
    }
  });
  return points;
}

}  // namespace pounding::analysis
