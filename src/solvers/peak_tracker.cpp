#include "pounding/solvers/peak_tracker.hpp"

#include <algorithm>
#include <cmath>

#include "pounding/solvers/history_schema.hpp"
#include "pounding/solvers/root_finding.hpp"

namespace pounding::solvers {

namespace {

double vertex_dx(const model::Point2& vertex, const model::Point2& centre, double u, double phi) {
  return point_displacement(vertex - centre, u, 0.0, std::cos(phi), std::sin(phi)).x();
}

double vertex_dx_rate(const model::Point2& vertex, const model::Point2& centre, double phi, double u_rate,
                      double phi_rate) {
  return point_velocity(vertex - centre, std::cos(phi), std::sin(phi), u_rate, 0.0, phi_rate).x();
}

/// How closely the drift and acceleration peaks' instants are located: at a turning point the
/// value is flat, so an instant 1e-7 of the stretch off moves it by ~10⁻¹⁴ of its change over
/// the stretch, while the root finder stops several costly interpolations earlier.
double peak_time_width(double t_a, double t_b) { return 1e-7 * (t_b - t_a); }

Peak& drift_peak(FloorPeaks& floor, std::size_t slot) {
  if (slot < 2) return slot == 0 ? floor.drift_x : floor.drift_y;
  return (slot % 2 == 0 ? floor.corner_drift_x : floor.corner_drift_y)[slot / 2 - 1];
}

}  // namespace

PeakTracker::PeakTracker(const RunKinematics& kinematics, const OutputSelection& outputs)
    : kinematics_(kinematics), system_(kinematics.system()), outputs_(outputs) {
  const dynamics::CoupledSystem& system = system_;
  const int n = system.dof();
  components_.resize(static_cast<std::size_t>(system.building_count()));
  for (int b = 0; b < system_.building_count(); ++b) {
    BuildingPeaks peaks;
    peaks.name = system.building(b).definition.name;
    // Outputs name a vertex by its number in the slab outline, as impacts and candidates do.
    peaks.contact_vertices = kinematics.contact_vertex_numbers(b);
    peaks.contact_vertices_rest = kinematics.contact_vertices(b);
    for (int f = 1; f <= system.building(b).storeys(); ++f) {
      FloorPeaks floor;
      floor.floor = f;
      floor.vertex_dx_m.resize(kinematics.contact_vertices(b).size());
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
  partial_ = dynamics::VectorXd::Zero(system.state_size());
}

void PeakTracker::locate(double t_a, double t_b, Instant& start, Instant& end, const StateAt& at,
                         const ComponentsAt& components_at) {
  if (outputs_.displacement_peaks) locate_displacements(t_a, t_b, start, end, at, components_at);
  if (outputs_.drift_peaks) locate_drifts(t_a, t_b, start, end, at, components_at);
  if (outputs_.acceleration_peaks) locate_accelerations(t_a, t_b, start, end, at);
}

void PeakTracker::update(const Instant& at) {
  const double t = *at.t_s;
  const dynamics::VectorXd& y = at.y;
  for (int b = 0; b < system_.building_count(); ++b) {
    const model::Point2 centre = system_.building(b).definition.centre_of_mass;
    for (FloorPeaks& floor : peaks_[b].floors) {
      const int i = system_.floor_index(b, floor.floor);
      if (outputs_.displacement_peaks) {
        floor.u_m.update(y[i], t);
        floor.v_m.update(y[i + 1], t);
        floor.phi_rad.update(y[i + 2], t);
        for (std::size_t k = 0; k < kinematics_.contact_vertices(b).size(); ++k) {
          floor.vertex_dx_m[k].update(vertex_dx(kinematics_.contact_vertices(b)[k], centre, y[i], y[i + 2]), t);
        }
      }
      if (outputs_.acceleration_peaks) {
        floor.ax_abs_mps2.update(at.accel[i], t);
        floor.ay_abs_mps2.update(at.accel[i + 1], t);
        floor.phi_ddot_radps2.update(at.accel[i + 2], t);
      }
      if (outputs_.drift_peaks) {
        for (std::size_t slot = 0; slot < kinematics_.drift_slots(b); ++slot) {
          drift_peak(floor, slot)
              .update(at.drifts.value[static_cast<Eigen::Index>(kinematics_.drift_index(b, floor.floor, slot))], t);
        }
      }
    }
  }
}

void PeakTracker::locate_accelerations(double t_a, double t_b, Instant& start, Instant& end, const StateAt& at) {
  const dynamics::VectorXd &a_a = start.accel, &a_b = end.accel;
  auto accel = [&](double t, dynamics::VectorXd& into) { kinematics_.absolute_accelerations(t, at(t), into); };
  // Free motion: the rate is exact (free_acceleration_rates), and the end's carries over to the
  // next stretch. While contact forces act no rate comes with the state (it would need the
  // derivative of every contact force): a central difference on the interpolant, whose states
  // are smooth inside a stretch, stands in, one-sided at the ends. Its step, 1e-4 of the
  // stretch, keeps both truncation and round-off far below what moves the located peak's value
  // (a turning point: the value is flat there).
  const bool free = kinematics_.free_motion();
  const double h = 1e-4 * (t_b - t_a);
  auto rate = [&](double t, int j) {
    if (free) {
      const dynamics::VectorXd y = at(t);
      kinematics_.absolute_accelerations(t, y, accel_lo_);
      kinematics_.free_acceleration_rates(t, y, accel_lo_, accel_hi_);
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
    start.accel_rate = (accel_hi_ - a_a) / h;
  } else if (!start.rate_known) {
    kinematics_.free_acceleration_rates(t_a, start.y, a_a, start.accel_rate);
  }
  if (free) {
    kinematics_.free_acceleration_rates(t_b, end.y, a_b, end.accel_rate);
  } else {
    accel(t_b - h, accel_lo_);
    end.accel_rate = (a_b - accel_lo_) / h;
  }
  end.rate_known = free;
  const dynamics::VectorXd &rate_a = start.accel_rate, &rate_b = end.accel_rate;
  for (int b = 0; b < system_.building_count(); ++b) {
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

const dynamics::VectorXd& PeakTracker::read_components(double t, const std::vector<int>& indices, const StateAt& at,
                                                       const ComponentsAt& components_at) {
  if (components_at) {
    components_at(t, indices, partial_);
  } else {
    partial_ = at(t);
  }
  return partial_;
}

template <class State, class Value, class Rate>
void PeakTracker::locate_peak(Peak& peak, double t_a, double t_b, const dynamics::VectorXd& y_a,
                              const dynamics::VectorXd& y_b, const State& state_at, const Value& value,
                              const Rate& rate) {
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

void PeakTracker::locate_displacements(double t_a, double t_b, const Instant& start, const Instant& end,
                                       const StateAt& at, const ComponentsAt& components_at) {
  const int n = system_.dof();
  // The state at t with (at least) the components `indices` right.
  auto reading = [&](const std::vector<int>& indices) {
    return [&](double t) -> const dynamics::VectorXd& { return read_components(t, indices, at, components_at); };
  };
  for (int b = 0; b < system_.building_count(); ++b) {
    const model::Point2 centre = system_.building(b).definition.centre_of_mass;
    for (std::size_t f = 0; f < peaks_[b].floors.size(); ++f) {
      FloorPeaks& floor = peaks_[b].floors[f];
      const FloorComponents& components = components_[b][f];
      const int i = system_.floor_index(b, floor.floor);
      Peak* coordinates[3] = {&floor.u_m, &floor.v_m, &floor.phi_rad};
      for (int k = 0; k < 3; ++k) {
        locate_peak(
            *coordinates[k], t_a, t_b, start.y, end.y, reading(components.coordinate[k]),
            [&](const dynamics::VectorXd& y) { return y[i + k]; },
            [&](const dynamics::VectorXd& y) { return y[n + i + k]; });
      }
      for (std::size_t k = 0; k < kinematics_.contact_vertices(b).size(); ++k) {
        const model::Point2& vertex = kinematics_.contact_vertices(b)[k];
        locate_peak(
            floor.vertex_dx_m[k], t_a, t_b, start.y, end.y, reading(components.vertex),
            [&](const dynamics::VectorXd& y) { return vertex_dx(vertex, centre, y[i], y[i + 2]); },
            [&](const dynamics::VectorXd& y) {
              return vertex_dx_rate(vertex, centre, y[i + 2], y[n + i], y[n + i + 2]);
            });
      }
    }
  }
}

void PeakTracker::locate_drifts(double t_a, double t_b, const Instant& start, const Instant& end, const StateAt& at,
                                const ComponentsAt& components_at) {
  const Drifts &d_a = start.drifts, &d_b = end.drifts;
  for (int b = 0; b < system_.building_count(); ++b) {
    for (std::size_t f = 0; f < peaks_[b].floors.size(); ++f) {
      FloorPeaks& floor = peaks_[b].floors[f];
      const std::vector<int>& indices = components_[b][f].drift;
      auto state_at = [&](double t) -> const dynamics::VectorXd& {
        return read_components(t, indices, at, components_at);
      };
      for (std::size_t slot = 0; slot < kinematics_.drift_slots(b); ++slot) {
        const auto j = static_cast<Eigen::Index>(kinematics_.drift_index(b, floor.floor, slot));
        Peak& peak = drift_peak(floor, slot);
        // As in locate_peak, on the table of every drift at once (one sin/cos per floor and state).
        if (!(d_a.rate[j] * d_b.rate[j] < 0.0)) continue;
        const double bound = std::max(std::abs(d_a.value[j]), std::abs(d_b.value[j])) +
                             2.0 * (t_b - t_a) * std::max(std::abs(d_a.rate[j]), std::abs(d_b.rate[j]));
        if (bound <= std::abs(peak.value)) continue;
        const double t =
            find_root([&](double t_s) { return kinematics_.storey_drift(state_at(t_s), b, floor.floor, slot).rate; },
                      t_a, t_b, d_a.rate[j], d_b.rate[j], peak_time_width(t_a, t_b));
        peak.update(kinematics_.storey_drift(state_at(t), b, floor.floor, slot).value, t);
      }
    }
  }
}

}  // namespace pounding::solvers
