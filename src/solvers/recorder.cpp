#include "pounding/solvers/recorder.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

#include "pounding/solvers/root_finding.hpp"

namespace pounding::solvers {
namespace {

void add_unique(std::vector<model::Point2>& points, const model::Point2& p) {
  if (std::find(points.begin(), points.end(), p) == points.end()) points.push_back(p);
}

/// Displacement (m) of a slab point given at rest, `arm` from the CM, with exact rotation, and
/// its rate (m/s), from the slab's (u, v), its rates and φ̇; c, s: cos φ and sin φ, which the
/// caller takes once per slab.
model::Point2 point_displacement(const model::Point2& arm, double u, double v, double c, double s) {
  return {u + (c - 1.0) * arm.x() - s * arm.y(), v + s * arm.x() + (c - 1.0) * arm.y()};
}

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
      for (const char* name : {"u_m", "v_m", "phi_rad"}) columns.push_back(prefix + name);
      for (const int number : numbers[b]) columns.push_back(fmt::format("{}vtx{}_dx_m", prefix, number));
      for (const char* name : {"ax_abs_mps2", "ay_abs_mps2", "phi_ddot_radps2", "drift_x", "drift_y"}) {
        columns.push_back(prefix + name);
      }
      for (std::size_t corner = 1; corner <= system.building(b).definition.slab.size(); ++corner) {
        columns.push_back(fmt::format("{}c{}_drift_x", prefix, corner));
        columns.push_back(fmt::format("{}c{}_drift_y", prefix, corner));
      }
    }
  }
  return columns;
}

Recorder::Recorder(const dynamics::CoupledSystem& system, RecordedDynamics dynamics,
                   const std::vector<int>& history_levels, double history_interval_s, RunSink* sink)
    : system_(system),
      dynamics_(std::move(dynamics)),
      history_levels_(chosen_levels(system, history_levels)),
      interval_s_(history_interval_s),
      sink_(sink) {
  for (const contact::Level& level : history_levels_) history_.levels.push_back(level.index);
  next_sample_s_ = system.ground_motion().start_s();
  history_.interval_s = interval_s_;
  history_.columns = history_columns(system, history_levels);
  drift_offset_ = {0, drift_slots(0) * static_cast<std::size_t>(system.building(0).storeys()), 0};
  drift_offset_[2] = drift_offset_[1] + drift_slots(1) * static_cast<std::size_t>(system.building(1).storeys());
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
    }
    peaks_.push_back(std::move(peaks));
  }
}

std::size_t Recorder::drift_index(int b, int floor, std::size_t slot) const {
  return drift_offset_[b] + static_cast<std::size_t>(floor - 1) * drift_slots(b) + slot;
}

std::size_t Recorder::drift_slots(int b) const { return 2 * (system_.building(b).definition.slab.size() + 1); }

Recorder::Drifts Recorder::storey_drifts(const dynamics::VectorXd& y) const {
  Drifts d{dynamics::VectorXd(static_cast<Eigen::Index>(drift_offset_[2])),
           dynamics::VectorXd(static_cast<Eigen::Index>(drift_offset_[2]))};
  const int n = system_.dof();
  for (int b = 0; b < 2; ++b) {
    const model::BuildingDefinition& def = system_.building(b).definition;
    const std::size_t points = def.slab.size() + 1;  // the CM, then the corners
    // Each floor's point motions once (one sin/cos per floor), then differences of floors.
    std::vector<model::Point2> below(points, model::Point2::Zero()), below_rate(points, model::Point2::Zero());
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
          d.value[j] = (here[axis] - below[k][axis]) / height_m;
          d.rate[j] = (here_rate[axis] - below_rate[k][axis]) / height_m;
        }
        below[k] = here;
        below_rate[k] = here_rate;
      }
    }
  }
  return d;
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

dynamics::VectorXd Recorder::absolute_accelerations(double t, const dynamics::VectorXd& y) const {
  dynamics::VectorXd y_dot(system_.state_size());
  dynamics_.derivative(t, y, y_dot);
  return y_dot.tail(system_.dof()) + system_.influence() * system_.ground_motion().accel_at(t);
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

void Recorder::observe(double t, const dynamics::VectorXd& y) { observe(t, y, absolute_accelerations(t, y), storey_drifts(y)); }

void Recorder::observe(double t, const dynamics::VectorXd& y, const dynamics::VectorXd& accel, const Drifts& drifts) {
  observed_t_s_ = t;
  observed_accel_ = accel;
  for (int b = 0; b < 2; ++b) {
    const model::Point2 centre = system_.building(b).definition.centre_of_mass;
    for (FloorPeaks& floor : peaks_[b].floors) {
      const int i = system_.floor_index(b, floor.floor);
      floor.u_m.update(y[i], t);
      floor.v_m.update(y[i + 1], t);
      floor.phi_rad.update(y[i + 2], t);
      for (std::size_t k = 0; k < vertices_[b].size(); ++k) {
        floor.vertex_dx_m[k].update(vertex_dx(vertices_[b][k], centre, y[i], y[i + 2]), t);
      }
      floor.ax_abs_mps2.update(accel[i], t);
      floor.ay_abs_mps2.update(accel[i + 1], t);
      floor.phi_ddot_radps2.update(accel[i + 2], t);
      for (std::size_t slot = 0; slot < drift_slots(b); ++slot) {
        drift_peak(floor, slot).update(drifts.value[static_cast<Eigen::Index>(drift_index(b, floor.floor, slot))], t);
      }
    }
  }
}

dynamics::VectorXd Recorder::free_acceleration_rates(double t, const dynamics::VectorXd& y,
                                                     const dynamics::VectorXd& accel) const {
  // Free motion: q̈ = A_v y − r a_g (A_v the acceleration rows of A), so q̈ + r a_g = A_v y and
  // its rate is A_v ẏ, the forcing's slope cancelling. The system's free rhs at the "state" ẏ
  // gives A_v ẏ − r a_g(t) in its acceleration rows (sparse, O(n)).
  const int n = system_.dof();
  const dynamics::VectorXd r_ag = system_.influence() * system_.ground_motion().accel_at(t);
  dynamics::VectorXd y_dot(system_.state_size()), y_ddot(system_.state_size());
  y_dot << y.tail(n), accel - r_ag;
  system_.rhs(t, y_dot, y_ddot);
  return y_ddot.tail(n) + r_ag;
}

void Recorder::locate_acceleration_peaks(double t_a, double t_b, const dynamics::VectorXd& y_a,
                                         const dynamics::VectorXd& y_b, const dynamics::VectorXd& a_a,
                                         const dynamics::VectorXd& a_b,
                                         const std::function<dynamics::VectorXd(double)>& at) {
  auto accel = [&](double t) { return absolute_accelerations(t, at(t)); };
  // Free motion: the rate is exact (free_acceleration_rates). While contact forces act no rate
  // comes with the state (it would need the derivative of every contact force): a central
  // difference on the interpolant, whose states are smooth inside a stretch, stands in, one-sided
  // at the ends. Its step, 1e-4 of the stretch, keeps both truncation and round-off far below
  // what moves the located peak's value (a turning point: the value is flat there).
  const bool free = free_motion();
  const double h = 1e-4 * (t_b - t_a);
  auto rate = [&](double t) {
    if (free) {
      const dynamics::VectorXd y = at(t);
      return free_acceleration_rates(t, y, absolute_accelerations(t, y));
    }
    const double lo = std::max(t_a, t - h), hi = std::min(t_b, t + h);
    return dynamics::VectorXd((accel(hi) - accel(lo)) / (hi - lo));
  };
  const dynamics::VectorXd rate_a = free ? free_acceleration_rates(t_a, y_a, a_a) : (accel(t_a + h) - a_a) / h;
  const dynamics::VectorXd rate_b = free ? free_acceleration_rates(t_b, y_b, a_b) : (a_b - accel(t_b - h)) / h;
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
        const double t = find_root([&](double t_s) { return rate(t_s)[j]; }, t_a, t_b, rate_a[j], rate_b[j],
                                   peak_time_width(t_a, t_b));
        peaks[k]->update(accel(t)[j], t);
      }
    }
  }
}

template <class Value, class Rate>
void Recorder::locate_peak(Peak& peak, double t_a, double t_b, const dynamics::VectorXd& y_a,
                           const dynamics::VectorXd& y_b, const std::function<dynamics::VectorXd(double)>& at,
                           const Value& value, const Rate& rate) {
  const double rate_a = rate(y_a), rate_b = rate(y_b);
  if (!(rate_a * rate_b < 0.0)) return;  // no turning point inside (an even number is missed)
  // Skip turning points that cannot beat the peak: |x(t*)| ≤ max |x| at the ends + ∫|ẋ|, and the
  // factor 2 covers a rate that is not monotonic within the step (steps are short against the
  // periods that matter).
  const double bound = std::max(std::abs(value(y_a)), std::abs(value(y_b))) +
                       2.0 * (t_b - t_a) * std::max(std::abs(rate_a), std::abs(rate_b));
  if (bound <= std::abs(peak.value)) return;
  const double t = find_root([&](double t_s) { return rate(at(t_s)); }, t_a, t_b, rate_a, rate_b);
  peak.update(value(at(t)), t);
}

void Recorder::locate_peaks(double t_a, double t_b, const dynamics::VectorXd& y_a, const dynamics::VectorXd& y_b,
                            const std::function<dynamics::VectorXd(double)>& at, const ComponentsAt& components_at) {
  const int n = system_.dof();
  dynamics::VectorXd partial = y_b;
  auto reading = [&](std::vector<int> indices) -> std::function<dynamics::VectorXd(double)> {
    if (!components_at) return at;
    return [&, indices](double t) {
      components_at(t, indices, partial);
      return partial;
    };
  };
  for (int b = 0; b < 2; ++b) {
    const model::Point2 centre = system_.building(b).definition.centre_of_mass;
    for (FloorPeaks& floor : peaks_[b].floors) {
      const int i = system_.floor_index(b, floor.floor);
      auto coordinate = [&](Peak& peak, int k) {
        locate_peak(peak, t_a, t_b, y_a, y_b, reading({i + k, n + i + k}), [&](const dynamics::VectorXd& y) { return y[i + k]; },
                    [&](const dynamics::VectorXd& y) { return y[n + i + k]; });
      };
      coordinate(floor.u_m, 0);
      coordinate(floor.v_m, 1);
      coordinate(floor.phi_rad, 2);
      for (std::size_t k = 0; k < vertices_[b].size(); ++k) {
        const model::Point2& vertex = vertices_[b][k];
        locate_peak(
            floor.vertex_dx_m[k], t_a, t_b, y_a, y_b, reading({i, i + 2, n + i, n + i + 2}),
            [&](const dynamics::VectorXd& y) { return vertex_dx(vertex, centre, y[i], y[i + 2]); },
            [&](const dynamics::VectorXd& y) { return vertex_dx_rate(vertex, centre, y[i + 2], y[n + i], y[n + i + 2]); });
      }
    }
  }
}

void Recorder::locate_drift_peaks(double t_a, double t_b, const Drifts& d_a, const Drifts& d_b,
                                  const dynamics::VectorXd& y_b, const std::function<dynamics::VectorXd(double)>& at,
                                  const ComponentsAt& components_at) {
  const int n = system_.dof();
  dynamics::VectorXd partial = y_b;
  for (int b = 0; b < 2; ++b) {
    for (FloorPeaks& floor : peaks_[b].floors) {
      // A drift reads the (u, v, φ) and rates of its floor and the floor below.
      std::vector<int> indices;
      for (int f = std::max(1, floor.floor - 1); f <= floor.floor; ++f) {
        const int i = system_.floor_index(b, f);
        for (int k = 0; k < 3; ++k) indices.insert(indices.end(), {i + k, n + i + k});
      }
      auto state_at = [&](double t) -> dynamics::VectorXd {
        if (!components_at) return at(t);
        components_at(t, indices, partial);
        return partial;
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

void Recorder::append_row(double t, const dynamics::VectorXd& y) {
  const dynamics::VectorXd accel = absolute_accelerations(t, y);
  const Drifts drifts = storey_drifts(y);
  Eigen::VectorXd row(static_cast<Eigen::Index>(history_.columns.size()) - 1);
  Eigen::Index c = 0;
  for (const contact::Level& level : history_levels_) {
    for (int b = 0; b < 2; ++b) {
      const int i = system_.floor_index(b, level.floors[b]);
      row[c++] = y[i];
      row[c++] = y[i + 1];
      row[c++] = y[i + 2];
      const model::Point2 centre = system_.building(b).definition.centre_of_mass;
      for (const model::Point2& vertex : vertices_[b]) row[c++] = vertex_dx(vertex, centre, y[i], y[i + 2]);
      for (int k = 0; k < 3; ++k) row[c++] = accel[i + k];
      for (std::size_t slot = 0; slot < drift_slots(b); ++slot) {
        row[c++] = drifts.value[static_cast<Eigen::Index>(drift_index(b, level.floors[b], slot))];
      }
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
    // Columns at the first row, not at construction: by then the run has passed its checks.
    if (!last_row_t_s_) sink_->history_columns(history_.columns);
    sink_->history_row(t, row);
    for (const ContactForceSample& f : forces) sink_->contact_force(f);
  } else {
    history_.time_s.push_back(t);
    history_.rows.push_back(std::move(row));
    history_.contact_forces.insert(history_.contact_forces.end(), forces.begin(), forces.end());
  }
  last_row_t_s_ = t;
}

void Recorder::sample(double t, const dynamics::VectorXd& y) {
  observe(t, y);
  if (last_row_t_s_ == t) return;
  append_row(t, y);
}

void Recorder::advance(double t_a, double t_b, const dynamics::VectorXd& y_b,
                       const std::function<dynamics::VectorXd(double)>& at,
                       const std::function<double(double, const dynamics::VectorXd&)>& constraint_power,
                       const std::optional<StretchEnergy>& closed_form, const ComponentsAt& components_at) {
  if (!(t_b > t_a)) return;
  const dynamics::VectorXd y_a = at(t_a);  // the stretch's own start (after an impact there)
  // The last state observed at t_a is where this stretch starts: the step end before it, or an
  // event's state after the event, with the dynamics that go on from there.
  const dynamics::VectorXd a_a = observed_t_s_ == t_a ? observed_accel_ : absolute_accelerations(t_a, y_a);
  if (closed_form) {
    energy_.input_kJ += closed_form->input_kJ;
    energy_.damping_kJ += closed_form->damping_kJ;
  }
  // 3-point Gauss–Legendre on [t_a, t_b]: exact for the input power of a degree-5 interpolant
  // times the linear a_g of one record interval.
  static constexpr double kNodes[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
  static constexpr double kWeights[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  const double half = 0.5 * (t_b - t_a), mid = 0.5 * (t_a + t_b);
  for (int k = 0; k < (closed_form ? 0 : 3); ++k) {
    const double t = mid + half * kNodes[k];
    const dynamics::VectorXd y = at(t);
    energy_.input_kJ += half * kWeights[k] * system_.input_power(t, y);
    energy_.damping_kJ += half * kWeights[k] * system_.damping_power(y);
    energy_.constraint_work_kJ += half * kWeights[k] * constraint_power(t, y);
  }
  while (next_sample_s_ <= t_b) {
    if (next_sample_s_ > t_a) sample(next_sample_s_, at(next_sample_s_));
    next_sample_s_ = system_.ground_motion().start_s() +
                     interval_s_ * std::round((next_sample_s_ - system_.ground_motion().start_s()) / interval_s_ + 1.0);
  }
  const dynamics::VectorXd a_b = absolute_accelerations(t_b, y_b);
  const Drifts d_a = storey_drifts(y_a), d_b = storey_drifts(y_b);
  locate_peaks(t_a, t_b, y_a, y_b, at, components_at);
  locate_drift_peaks(t_a, t_b, d_a, d_b, y_b, at, components_at);
  locate_acceleration_peaks(t_a, t_b, y_a, y_b, a_a, a_b, at);
  observe(t_b, y_b, a_b, d_b);
}

void Recorder::stream_new_impacts(const std::vector<ImpactRecord>& impacts) {
  if (sink_ == nullptr) return;
  for (; impacts_streamed_ < impacts.size(); ++impacts_streamed_) sink_->impact(impacts[impacts_streamed_]);
}

void Recorder::finish(const dynamics::VectorXd& final_state, RunResult& result) {
  stream_new_impacts(result.impacts);
  energy_.kinetic_kJ = system_.kinetic_energy(final_state);
  energy_.strain_kJ = system_.strain_energy(final_state);
  result.energy = energy_;
  result.peaks = std::move(peaks_);
  result.history = std::move(history_);
}

}  // namespace pounding::solvers
