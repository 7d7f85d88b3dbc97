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

/// x-displacement of a slab point given at rest, exact rotation.
double vertex_dx(const model::Point2& vertex, const model::Point2& centre, double u, double phi) {
  const model::Point2 arm = vertex - centre;
  return u + (std::cos(phi) - 1.0) * arm.x() - std::sin(phi) * arm.y();
}

/// Its rate (m/s).
double vertex_dx_rate(const model::Point2& vertex, const model::Point2& centre, double phi, double u_rate,
                      double phi_rate) {
  const model::Point2 arm = vertex - centre;
  return u_rate - phi_rate * (std::sin(phi) * arm.x() + std::cos(phi) * arm.y());
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

Recorder::Recorder(const dynamics::CoupledSystem& system, const std::vector<int>& history_levels,
                   double history_interval_s, RunSink* sink)
    : system_(system), interval_s_(history_interval_s), sink_(sink) {
  for (int level : history_levels) history_levels_.push_back(system.levels().at(static_cast<std::size_t>(level - 1)));
  if (history_levels.empty()) history_levels_ = system.levels();
  for (const contact::Level& level : history_levels_) history_.levels.push_back(level.index);
  next_sample_s_ = system.ground_motion().start_s();
  history_.interval_s = interval_s_;
  history_.columns.push_back("t_s");
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
      peaks.floors.push_back(floor);
    }
    peaks_.push_back(std::move(peaks));
  }
  for (const contact::Level& level : history_levels_) {
    for (int b = 0; b < 2; ++b) {
      const std::string prefix = fmt::format("B{}_f{}_", b + 1, level.floors[b]);
      history_.columns.push_back(prefix + "u_m");
      history_.columns.push_back(prefix + "v_m");
      history_.columns.push_back(prefix + "phi_rad");
      for (const int number : peaks_[b].contact_vertices) history_.columns.push_back(fmt::format("{}vtx{}_dx_m", prefix, number));
    }
  }
}

void Recorder::observe(double t, const dynamics::VectorXd& y) {
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

void Recorder::locate_peaks(double t_a, double t_b, const dynamics::VectorXd& y_b,
                            const std::function<dynamics::VectorXd(double)>& at, const ComponentsAt& components_at) {
  const dynamics::VectorXd y_a = at(t_a);  // the stretch's own start (after an impact there)
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

void Recorder::append_row(double t, const dynamics::VectorXd& y) {
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
    }
  }
  if (sink_ != nullptr) {
    // Columns at the first row, not at construction: by then the run has passed its checks.
    if (!last_row_t_s_) sink_->history_columns(history_.columns);
    sink_->history_row(t, row);
  } else {
    history_.time_s.push_back(t);
    history_.rows.push_back(std::move(row));
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
  locate_peaks(t_a, t_b, y_b, at, components_at);
  observe(t_b, y_b);
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
