#include "pounding/solvers/recorder.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

#include "pounding/solvers/history_schema.hpp"
#include "pounding/solvers/root_finding.hpp"

namespace pounding::solvers {
namespace {

void add_unique(std::vector<model::Point2>& points, const model::Point2& p) {
  if (std::find(points.begin(), points.end(), p) == points.end()) points.push_back(p);
}

/// The velocity (m/s) of a slab point given at rest, `arm` from the CM, from the slab's (u̇, v̇)
/// and φ̇; c, s: cos φ and sin φ (point_displacement's rate).
model::Point2 point_velocity(const model::Point2& arm, double c, double s, double u_rate, double v_rate,
                             double phi_rate) {
  return {u_rate - phi_rate * (s * arm.x() + c * arm.y()), v_rate + phi_rate * (c * arm.x() - s * arm.y())};
}

/// x-displacement of a slab point given at rest, exact rotation.
double vertex_dx(const model::Point2& vertex, const model::Point2& centre, double u, double phi) {
  return point_displacement(vertex - centre, u, 0.0, std::cos(phi), std::sin(phi)).x();
}

/// Its rate (m/s).
double vertex_dx_rate(const model::Point2& vertex, const model::Point2& centre, double phi, double u_rate,
                      double phi_rate) {
  return point_velocity(vertex - centre, std::cos(phi), std::sin(phi), u_rate, 0.0, phi_rate).x();
}

/// The 1-based numbers in `slab`'s outline of `points` (each one of its vertices, as candidates
/// copy them), and the points reordered by number.
std::vector<int> outline_numbers(const model::Polygon& slab, std::vector<model::Point2>& points) {
  std::vector<int> numbers;
  for (const model::Point2& p : points) {
    const auto found = std::find(slab.vertices().begin(), slab.vertices().end(), p);
    if (found == slab.vertices().end()) throw std::logic_error("a contact vertex is not a vertex of its slab");
    numbers.push_back(static_cast<int>(found - slab.vertices().begin()) + 1);
  }
  std::sort(numbers.begin(), numbers.end());
  for (std::size_t k = 0; k < numbers.size(); ++k) points[k] = slab.vertex(static_cast<std::size_t>(numbers[k] - 1));
  return numbers;
}

}  // namespace

std::vector<model::Point2> contact_vertices(const std::vector<contact::Candidate>& candidates, int building) {
  std::vector<model::Point2> points;
  for (const contact::Candidate& c : candidates) {
    if (c.striking_building == building) add_unique(points, c.vertex_rest);
    if (c.struck_building == building) {
      add_unique(points, c.edge_start_rest);
      add_unique(points, c.edge_end_rest);
    }
  }
  return points;
}

RecordedDynamics free_dynamics(const dynamics::CoupledSystem& system) {
  return {.derivative = [&system](double t, const dynamics::VectorXd& y,
                                  Eigen::Ref<dynamics::VectorXd> y_dot) { system.rhs(t, y, y_dot); },
          .contact_forces = {},
          .free_motion = {}};
}

namespace {

std::vector<contact::Level> chosen_levels(const dynamics::CoupledSystem& system, const std::vector<int>& history_levels) {
  if (history_levels.empty()) return system.levels();
  std::vector<contact::Level> levels;
  for (int level : history_levels) levels.push_back(system.levels().at(static_cast<std::size_t>(level - 1)));
  return levels;
}

}  // namespace

std::vector<std::string> history_columns(const dynamics::CoupledSystem& system, const std::vector<int>& history_levels) {
  std::vector<std::string> columns{"t_s"};
  std::array<std::vector<int>, 2> numbers;
  for (int b = 0; b < 2; ++b) {
    std::vector<model::Point2> vertices = contact_vertices(system.candidates(), b);
    numbers[b] = outline_numbers(system.building(b).definition.slab, vertices);
  }
  for (const contact::Level& level : chosen_levels(system, history_levels)) {
    for (int b = 0; b < 2; ++b) {
      const std::string prefix = fmt::format("B{}_f{}_", b + 1, level.floors[b]);
      const std::size_t corners = system.building(b).definition.slab.size();
      for_each_slab_column(numbers[b].size(), corners, [&](const HistoryQuantity& quantity, std::size_t k) {
        const bool vertex = quantity.per == HistoryQuantity::Per::contact_vertex;
        columns.push_back(prefix + quantity.column(vertex ? numbers[b][k] : static_cast<int>(k) + 1));
      });
    }
  }
  return columns;
}

Recorder::Recorder(const dynamics::CoupledSystem& system, RecordedDynamics dynamics,
                   const std::vector<int>& history_levels, double history_interval_s, const OutputSelection& outputs,
                   RunSink* sink)
    : system_(system),
      dynamics_(std::move(dynamics)),
      outputs_(outputs),
      history_levels_(chosen_levels(system, history_levels)),
      interval_s_(history_interval_s),
      energy_(system),
      sink_(sink) {
  next_sample_s_ = system.ground_motion().start_s();
  if (outputs_.history) {
    for (const contact::Level& level : history_levels_) history_.levels.push_back(level.index);
    history_.interval_s = interval_s_;
    history_.columns = history_columns(system, history_levels);
    row_.resize(static_cast<Eigen::Index>(history_.columns.size()) - 1);
  }
  drift_offset_ = {0, drift_slots(0) * static_cast<std::size_t>(system.building(0).storeys()), 0};
  drift_offset_[2] = drift_offset_[1] + drift_slots(1) * static_cast<std::size_t>(system.building(1).storeys());
  const int n = system.dof();
  for (int b = 0; b < 2; ++b) {
    vertices_[b] = contact_vertices(system.candidates(), b);
    BuildingPeaks peaks;
    peaks.name = system.building(b).definition.name;
    // Outputs name a vertex by its number in the slab outline, as impacts and candidates do.
    peaks.contact_vertices = outline_numbers(system.building(b).definition.slab, vertices_[b]);
    peaks.contact_vertices_rest = vertices_[b];
    for (int f = 1; f <= system.building(b).storeys(); ++f) {
      FloorPeaks floor;
      floor.floor = f;
      floor.vertex_dx_m.resize(vertices_[b].size());
      floor.corner_drift_x.resize(system.building(b).definition.slab.size());
      floor.corner_drift_y.resize(system.building(b).definition.slab.size());
      peaks.floors.push_back(floor);
      const int i = system.floor_index(b, f);
      FloorComponents c;
      for (int k = 0; k < 3; ++k) c.coordinate[k] = {i + k, n + i + k};
      c.vertex = {i, i + 2, n + i, n + i + 2};
      for (int below = std::max(1, f - 1); below <= f; ++below) {  // a drift reads this floor and the one below
        const int j = system.floor_index(b, below);
        for (int k = 0; k < 3; ++k) c.drift.insert(c.drift.end(), {j + k, n + j + k});
      }
      components_[b].push_back(std::move(c));
    }
    peaks_.push_back(std::move(peaks));
  }
  y_dot_.resize(system.state_size());
  y_ddot_.resize(system.state_size());
  partial_ = dynamics::VectorXd::Zero(system.state_size());
  const std::size_t points = 1 + std::max(system.building(0).definition.slab.size(), system.building(1).definition.slab.size());
  below_.resize(points);
  below_rate_.resize(points);
}

std::size_t Recorder::drift_index(int b, int floor, std::size_t slot) const {
  return drift_offset_[b] + static_cast<std::size_t>(floor - 1) * drift_slots(b) + slot;
}

std::size_t Recorder::drift_slots(int b) const { return 2 * (system_.building(b).definition.slab.size() + 1); }

void Recorder::storey_drifts(const dynamics::VectorXd& y, Drifts& d) const {
  d.value.resize(static_cast<Eigen::Index>(drift_offset_[2]));
  d.rate.resize(static_cast<Eigen::Index>(drift_offset_[2]));
  const int n = system_.dof();
  for (int b = 0; b < 2; ++b) {
    const model::BuildingDefinition& def = system_.building(b).definition;
    const std::size_t points = def.slab.size() + 1;  // the CM, then the corners
    // Each floor's point motions once (one sin/cos per floor), then differences of floors.
    std::fill_n(below_.begin(), points, model::Point2::Zero());
    std::fill_n(below_rate_.begin(), points, model::Point2::Zero());
    for (int f = 1; f <= system_.building(b).storeys(); ++f) {
      const int i = system_.floor_index(b, f);
      const double height_m = def.storey_height_m.at(static_cast<std::size_t>(f - 1));
      const double c = std::cos(y[i + 2]), s = std::sin(y[i + 2]);
      for (std::size_t k = 0; k < points; ++k) {
        const model::Point2 arm = k == 0 ? model::Point2::Zero() : model::Point2(def.slab.vertex(k - 1) - def.centre_of_mass);
        const model::Point2 here = point_displacement(arm, y[i], y[i + 1], c, s);
        const model::Point2 here_rate = point_velocity(arm, c, s, y[n + i], y[n + i + 1], y[n + i + 2]);
        for (int axis = 0; axis < 2; ++axis) {
          const auto j = static_cast<Eigen::Index>(drift_index(b, f, 2 * k + static_cast<std::size_t>(axis)));
          d.value[j] = (here[axis] - below_[k][axis]) / height_m;
          d.rate[j] = (here_rate[axis] - below_rate_[k][axis]) / height_m;
        }
        below_[k] = here;
        below_rate_[k] = here_rate;
      }
    }
  }
}

bool Recorder::free_motion() const { return !dynamics_.free_motion || dynamics_.free_motion(); }

Recorder::Drift Recorder::storey_drift(const dynamics::VectorXd& y, int b, int floor, std::size_t slot) const {
  const model::BuildingDefinition& def = system_.building(b).definition;
  const std::size_t k = slot / 2;
  const int axis = static_cast<int>(slot % 2), n = system_.dof();
  const model::Point2 arm = k == 0 ? model::Point2::Zero() : model::Point2(def.slab.vertex(k - 1) - def.centre_of_mass);
  auto motion = [&](int f) {  // displacement and rate of the point on floor f along the axis; the ground's is zero
    if (f == 0) return std::pair{0.0, 0.0};
    const int i = system_.floor_index(b, f);
    const double c = std::cos(y[i + 2]), s = std::sin(y[i + 2]);
    return std::pair{point_displacement(arm, y[i], y[i + 1], c, s)[axis],
                     point_velocity(arm, c, s, y[n + i], y[n + i + 1], y[n + i + 2])[axis]};
  };
  const auto [upper, upper_rate] = motion(floor);
  const auto [lower, lower_rate] = motion(floor - 1);
  const double height_m = def.storey_height_m.at(static_cast<std::size_t>(floor - 1));
  return {(upper - lower) / height_m, (upper_rate - lower_rate) / height_m};
}

void Recorder::absolute_accelerations(double t, const dynamics::VectorXd& y, dynamics::VectorXd& accel) const {
  dynamics_.derivative(t, y, y_dot_);
  accel = y_dot_.tail(system_.dof()) + system_.influence() * system_.ground_motion().accel_at(t);
}

namespace {

/// How closely the drift and acceleration peaks' instants are located: at a turning point the
/// value is flat, so an instant 1e-7 of the stretch off moves it by ~10⁻¹⁴ of its change over
/// the stretch, while the root finder stops several costly interpolations earlier.
double peak_time_width(double t_a, double t_b) { return 1e-7 * (t_b - t_a); }

Peak& drift_peak(FloorPeaks& floor, std::size_t slot) {
  if (slot < 2) return slot == 0 ? floor.drift_x : floor.drift_y;
  return (slot % 2 == 0 ? floor.corner_drift_x : floor.corner_drift_y)[slot / 2 - 1];
}

}  // namespace

void Recorder::measure(double t, const dynamics::VectorXd& y, bool accelerations, bool drifts, Instant& into) const {
  into.t_s = t;
  into.y = y;
  into.rate_known = false;
  if (accelerations) absolute_accelerations(t, y, into.accel);
  if (drifts) storey_drifts(y, into.drifts);
}

void Recorder::update_peaks(const Instant& at) {
  const double t = *at.t_s;
  const dynamics::VectorXd& y = at.y;
  for (int b = 0; b < 2; ++b) {
    const model::Point2 centre = system_.building(b).definition.centre_of_mass;
    for (FloorPeaks& floor : peaks_[b].floors) {
      const int i = system_.floor_index(b, floor.floor);
      if (outputs_.displacement_peaks) {
        floor.u_m.update(y[i], t);
        floor.v_m.update(y[i + 1], t);
        floor.phi_rad.update(y[i + 2], t);
        for (std::size_t k = 0; k < vertices_[b].size(); ++k) {
          floor.vertex_dx_m[k].update(vertex_dx(vertices_[b][k], centre, y[i], y[i + 2]), t);
        }
      }
      if (outputs_.acceleration_peaks) {
        floor.ax_abs_mps2.update(at.accel[i], t);
        floor.ay_abs_mps2.update(at.accel[i + 1], t);
        floor.phi_ddot_radps2.update(at.accel[i + 2], t);
      }
      if (outputs_.drift_peaks) {
        for (std::size_t slot = 0; slot < drift_slots(b); ++slot) {
          drift_peak(floor, slot).update(at.drifts.value[static_cast<Eigen::Index>(drift_index(b, floor.floor, slot))], t);
        }
      }
    }
  }
}

void Recorder::free_acceleration_rates(double t, const dynamics::VectorXd& y, const dynamics::VectorXd& accel,
                                       dynamics::VectorXd& rate) const {
  // Free motion: q̈ = A_v y − r a_g (A_v the acceleration rows of A), so q̈ + r a_g = A_v y and
  // its rate is A_v ẏ, the forcing's slope cancelling. The system's free rhs at the "state" ẏ
  // gives A_v ẏ − r a_g(t) in its acceleration rows (sparse, O(n)).
  const int n = system_.dof();
  const double a_g = system_.ground_motion().accel_at(t);
  y_dot_ << y.tail(n), accel - system_.influence() * a_g;
  system_.rhs(t, y_dot_, y_ddot_);
  rate = y_ddot_.tail(n) + system_.influence() * a_g;
}

void Recorder::locate_acceleration_peaks(double t_a, double t_b, const std::function<dynamics::VectorXd(double)>& at) {
  const dynamics::VectorXd &a_a = start_.accel, &a_b = last_.accel;
  auto accel = [&](double t, dynamics::VectorXd& into) { absolute_accelerations(t, at(t), into); };
  // Free motion: the rate is exact (free_acceleration_rates), and the end's carries over to the
  // next stretch. While contact forces act no rate comes with the state (it would need the
  // derivative of every contact force): a central difference on the interpolant, whose states
  // are smooth inside a stretch, stands in, one-sided at the ends. Its step, 1e-4 of the
  // stretch, keeps both truncation and round-off far below what moves the located peak's value
  // (a turning point: the value is flat there).
  const bool free = free_motion();
  const double h = 1e-4 * (t_b - t_a);
  auto rate = [&](double t, int j) {
    if (free) {
      const dynamics::VectorXd y = at(t);
      absolute_accelerations(t, y, accel_lo_);
      free_acceleration_rates(t, y, accel_lo_, accel_hi_);
      return accel_hi_[j];
    }
    const double lo = std::max(t_a, t - h), hi = std::min(t_b, t + h);
    accel(lo, accel_lo_);
    accel(hi, accel_hi_);
    return (accel_hi_[j] - accel_lo_[j]) / (hi - lo);
  };
  // In free motion a start rate already known is the previous stretch's end rate, exact here too.
  if (!free) {
    accel(t_a + h, accel_hi_);
    start_.accel_rate = (accel_hi_ - a_a) / h;
  } else if (!start_.rate_known) {
    free_acceleration_rates(t_a, start_.y, a_a, start_.accel_rate);
  }
  if (free) {
    free_acceleration_rates(t_b, last_.y, a_b, last_.accel_rate);
  } else {
    accel(t_b - h, accel_lo_);
    last_.accel_rate = (a_b - accel_lo_) / h;
  }
  last_.rate_known = free;
  const dynamics::VectorXd &rate_a = start_.accel_rate, &rate_b = last_.accel_rate;
  for (int b = 0; b < 2; ++b) {
    for (FloorPeaks& floor : peaks_[b].floors) {
      const int i = system_.floor_index(b, floor.floor);
      Peak* peaks[3] = {&floor.ax_abs_mps2, &floor.ay_abs_mps2, &floor.phi_ddot_radps2};
      for (int k = 0; k < 3; ++k) {
        const int j = i + k;
        if (!(rate_a[j] * rate_b[j] < 0.0)) continue;
        // As in locate_peak: skip a turning point that cannot beat the peak.
        const double bound = std::max(std::abs(a_a[j]), std::abs(a_b[j])) +
                             2.0 * (t_b - t_a) * std::max(std::abs(rate_a[j]), std::abs(rate_b[j]));
        if (bound <= std::abs(peaks[k]->value)) continue;
        const double t = find_root([&](double t_s) { return rate(t_s, j); }, t_a, t_b, rate_a[j], rate_b[j],
                                   peak_time_width(t_a, t_b));
        accel(t, accel_lo_);
        peaks[k]->update(accel_lo_[j], t);
      }
    }
  }
}

const dynamics::VectorXd& Recorder::read_components(double t, const std::vector<int>& indices,
                                                    const std::function<dynamics::VectorXd(double)>& at,
                                                    const ComponentsAt& components_at) {
  if (components_at) {
    components_at(t, indices, partial_);
  } else {
    partial_ = at(t);
  }
  return partial_;
}

template <class StateAt, class Value, class Rate>
void Recorder::locate_peak(Peak& peak, double t_a, double t_b, const StateAt& state_at, const Value& value,
                           const Rate& rate) {
  const dynamics::VectorXd &y_a = start_.y, &y_b = last_.y;
  const double rate_a = rate(y_a), rate_b = rate(y_b);
  if (!(rate_a * rate_b < 0.0)) return;  // no turning point inside (an even number is missed)
  // Skip turning points that cannot beat the peak: |x(t*)| ≤ max |x| at the ends + ∫|ẋ|, and the
  // factor 2 covers a rate that is not monotonic within the step (steps are short against the
  // periods that matter).
  const double bound = std::max(std::abs(value(y_a)), std::abs(value(y_b))) +
                       2.0 * (t_b - t_a) * std::max(std::abs(rate_a), std::abs(rate_b));
  if (bound <= std::abs(peak.value)) return;
  const double t = find_root([&](double t_s) { return rate(state_at(t_s)); }, t_a, t_b, rate_a, rate_b);
  peak.update(value(state_at(t)), t);
}

void Recorder::locate_peaks(double t_a, double t_b, const std::function<dynamics::VectorXd(double)>& at,
                            const ComponentsAt& components_at) {
  const int n = system_.dof();
  // The state at t with (at least) the components `indices` right.
  auto reading = [&](const std::vector<int>& indices) {
    return [&](double t) -> const dynamics::VectorXd& { return read_components(t, indices, at, components_at); };
  };
  for (int b = 0; b < 2; ++b) {
    const model::Point2 centre = system_.building(b).definition.centre_of_mass;
    for (std::size_t f = 0; f < peaks_[b].floors.size(); ++f) {
      FloorPeaks& floor = peaks_[b].floors[f];
      const FloorComponents& components = components_[b][f];
      const int i = system_.floor_index(b, floor.floor);
      Peak* coordinates[3] = {&floor.u_m, &floor.v_m, &floor.phi_rad};
      for (int k = 0; k < 3; ++k) {
        locate_peak(*coordinates[k], t_a, t_b, reading(components.coordinate[k]),
                    [&](const dynamics::VectorXd& y) { return y[i + k]; },
                    [&](const dynamics::VectorXd& y) { return y[n + i + k]; });
      }
      for (std::size_t k = 0; k < vertices_[b].size(); ++k) {
        const model::Point2& vertex = vertices_[b][k];
        locate_peak(
            floor.vertex_dx_m[k], t_a, t_b, reading(components.vertex),
            [&](const dynamics::VectorXd& y) { return vertex_dx(vertex, centre, y[i], y[i + 2]); },
            [&](const dynamics::VectorXd& y) { return vertex_dx_rate(vertex, centre, y[i + 2], y[n + i], y[n + i + 2]); });
      }
    }
  }
}

void Recorder::locate_drift_peaks(double t_a, double t_b, const std::function<dynamics::VectorXd(double)>& at,
                                  const ComponentsAt& components_at) {
  const Drifts &d_a = start_.drifts, &d_b = last_.drifts;
  for (int b = 0; b < 2; ++b) {
    for (std::size_t f = 0; f < peaks_[b].floors.size(); ++f) {
      FloorPeaks& floor = peaks_[b].floors[f];
      const std::vector<int>& indices = components_[b][f].drift;
      auto state_at = [&](double t) -> const dynamics::VectorXd& {
        return read_components(t, indices, at, components_at);
      };
      for (std::size_t slot = 0; slot < drift_slots(b); ++slot) {
        const auto j = static_cast<Eigen::Index>(drift_index(b, floor.floor, slot));
        Peak& peak = drift_peak(floor, slot);
        // As in locate_peak, on the table of every drift at once (one sin/cos per floor and state).
        if (!(d_a.rate[j] * d_b.rate[j] < 0.0)) continue;
        const double bound = std::max(std::abs(d_a.value[j]), std::abs(d_b.value[j])) +
                             2.0 * (t_b - t_a) * std::max(std::abs(d_a.rate[j]), std::abs(d_b.rate[j]));
        if (bound <= std::abs(peak.value)) continue;
        const double t = find_root([&](double t_s) { return storey_drift(state_at(t_s), b, floor.floor, slot).rate; },
                                   t_a, t_b, d_a.rate[j], d_b.rate[j], peak_time_width(t_a, t_b));
        peak.update(storey_drift(state_at(t), b, floor.floor, slot).value, t);
      }
    }
  }
}

void Recorder::append_row(const Instant& at) {
  const double t = *at.t_s;
  const dynamics::VectorXd& y = at.y;
  Eigen::Index c = 0;
  for (const contact::Level& level : history_levels_) {
    for (int b = 0; b < 2; ++b) {
      const int i = system_.floor_index(b, level.floors[b]);
      const SlabSample slab{.q = &y[i],
                            .accel = &at.accel[i],
                            .drift = &at.drifts.value[static_cast<Eigen::Index>(drift_index(b, level.floors[b], 0))],
                            .contact_vertices = vertices_[b],
                            .centre = system_.building(b).definition.centre_of_mass};
      for_each_slab_column(
          vertices_[b].size(), system_.building(b).definition.slab.size(),
          [&](const HistoryQuantity& quantity, std::size_t k) { row_[c++] = quantity.value(slab, k); });
    }
  }
  std::vector<ContactForceSample> forces;
  if (dynamics_.contact_forces) {
    for (const ContactForce& f : dynamics_.contact_forces(t, y)) {
      const contact::Candidate& c = system_.candidates()[f.candidate];
      const contact::GapState gap = system_.gap(y, f.candidate);
      forces.push_back({.t_s = t,
                        .candidate = f.candidate,
                        .level = c.level,
                        .striking_building = c.striking_building + 1,
                        .vertex = c.vertex_index + 1,
                        .struck_edge = c.edge_index + 1,
                        .gap_m = gap.gap_m,
                        .gap_rate_mps = gap.gap_rate_mps,
                        .force_kN = f.force_kN});
    }
  }
  if (sink_ != nullptr) {
    sink_->history_row(t, row_);
    for (const ContactForceSample& f : forces) sink_->contact_force(f);
  } else {
    history_.time_s.push_back(t);
    history_.rows.push_back(row_);
    history_.contact_forces.insert(history_.contact_forces.end(), forces.begin(), forces.end());
  }
  last_row_t_s_ = t;
}

void Recorder::sample(double t, const dynamics::VectorXd& y) {
  if (!started_ && sink_ != nullptr) {
    // Columns at the first sample, not at construction: by then the run has passed its checks.
    sink_->history_columns(history_.columns);
  }
  started_ = true;
  const bool row = outputs_.history && last_row_t_s_ != t;
  measure(t, y, row || outputs_.acceleration_peaks, row || outputs_.drift_peaks, last_);
  update_peaks(last_);
  if (row) append_row(last_);
}

void Recorder::advance(double t_a, double t_b, const dynamics::VectorXd& y_b,
                       const std::function<dynamics::VectorXd(double)>& at,
                       const std::function<double(double, const dynamics::VectorXd&)>& constraint_power,
                       const std::optional<StretchEnergy>& closed_form, const ComponentsAt& components_at) {
  if (!(t_b > t_a)) return;
  energy_.add_stretch(t_a, t_b, at, constraint_power, closed_form);
  // The stretch starts where the last instant recorded left off: the previous step's end or an
  // event's state after the event, with the dynamics that go on from there. Swapped out before the
  // samples inside the stretch take the place of the latest instant.
  const bool peaks = outputs_.any_peaks();
  if (peaks) {
    std::swap(start_, last_);
    if (start_.t_s != t_a) measure(t_a, at(t_a), outputs_.acceleration_peaks, outputs_.drift_peaks, start_);
  }
  // The peaks see the sample instants whether or not rows are written, so they do not depend on
  // the history (on HHT's Hermite interpolant a sample can beat the located turning points).
  if (outputs_.history || peaks) {
    while (next_sample_s_ <= t_b) {
      if (next_sample_s_ > t_a) sample(next_sample_s_, at(next_sample_s_));
      next_sample_s_ = system_.ground_motion().start_s() +
                       interval_s_ * std::round((next_sample_s_ - system_.ground_motion().start_s()) / interval_s_ + 1.0);
    }
  }
  if (!peaks) return;
  // Turning points are found from the rates at the piece ends, so a piece must be too short for
  // a rate to change sign twice unseen (peak_step_s_).
  const double length_s = t_b - t_a;
  const int pieces = peak_step_s_ > 0.0 ? std::max(1, static_cast<int>(std::ceil(length_s / peak_step_s_))) : 1;
  for (int k = 1; k <= pieces; ++k) {
    const double s_a = t_a + length_s * (k - 1) / pieces;
    const double s_b = k == pieces ? t_b : t_a + length_s * k / pieces;
    if (k > 1) std::swap(start_, last_);
    measure(s_b, k == pieces ? y_b : at(s_b), outputs_.acceleration_peaks, outputs_.drift_peaks, last_);
    if (outputs_.displacement_peaks) locate_peaks(s_a, s_b, at, components_at);
    if (outputs_.drift_peaks) locate_drift_peaks(s_a, s_b, at, components_at);
    if (outputs_.acceleration_peaks) locate_acceleration_peaks(s_a, s_b, at);
    update_peaks(last_);
  }
}

void Recorder::stream_new_impacts(const std::vector<ImpactRecord>& impacts) {
  if (sink_ == nullptr) return;
  for (; impacts_streamed_ < impacts.size(); ++impacts_streamed_) sink_->impact(impacts[impacts_streamed_]);
}

void Recorder::finish(const dynamics::VectorXd& final_state, RunResult& result) {
  stream_new_impacts(result.impacts);
  result.energy = energy_.close(final_state);
  result.outputs = outputs_;
  result.peaks = std::move(peaks_);
  result.history = std::move(history_);
}

}  // namespace pounding::solvers
