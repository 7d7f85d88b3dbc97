#include "pounding/solvers/run_kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "pounding/solvers/history_schema.hpp"

namespace pounding::solvers {

namespace {

void add_unique(std::vector<model::Point2>& points, const model::Point2& p) {
  if (std::find(points.begin(), points.end(), p) == points.end()) points.push_back(p);
}

}  // namespace

std::vector<model::Point2> contact_vertices(const std::vector<contact::Candidate>& candidates, int building) {
  std::vector<model::Point2> points;
  for (const contact::Candidate& c : candidates) {
    if (c.striking_building == building && !c.column) add_unique(points, c.vertex_rest);  // a column point is no corner
    // A corner candidate's edge is a side edge: its far end moves away from the joint, not into it.
    if (c.struck_building == building && !c.corner) {
      add_unique(points, c.edge_start_rest);
      add_unique(points, c.edge_end_rest);
    }
  }
  return points;
}

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

RunKinematics::RunKinematics(const dynamics::CoupledSystem& system, RecordedDynamics dynamics)
    : system_(system), dynamics_(std::move(dynamics)) {
  const int buildings = system.building_count();
  drift_offset_ = {0};
  std::size_t points = 0;
  for (int b = 0; b < buildings; ++b) {
    drift_offset_.push_back(drift_offset_.back() +
                            drift_slots(b) * static_cast<std::size_t>(system.building(b).storeys()));
    vertices_.push_back(solvers::contact_vertices(system.candidates(), b));
    vertex_numbers_.push_back(outline_numbers(system.building(b).definition.slab, vertices_.back()));
    points = std::max(points, 1 + system.building(b).definition.slab.size());
  }
  y_dot_.resize(system.state_size());
  y_ddot_.resize(system.state_size());
  below_.resize(points);
  below_rate_.resize(points);
}

std::size_t RunKinematics::drift_index(int b, int floor, std::size_t slot) const {
  return drift_offset_[b] + static_cast<std::size_t>(floor - 1) * drift_slots(b) + slot;
}

std::size_t RunKinematics::drift_slots(int b) const { return 2 * (system_.building(b).definition.slab.size() + 1); }

void RunKinematics::storey_drifts(const dynamics::VectorXd& y, Drifts& d) const {
  d.value.resize(static_cast<Eigen::Index>(drift_offset_.back()));
  d.rate.resize(static_cast<Eigen::Index>(drift_offset_.back()));
  const int n = system_.dof();
  for (int b = 0; b < system_.building_count(); ++b) {
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
        const model::Point2 arm =
            k == 0 ? model::Point2::Zero() : model::Point2(def.slab.vertex(k - 1) - def.centre_of_mass);
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

RunKinematics::Drift RunKinematics::storey_drift(const dynamics::VectorXd& y, int b, int floor,
                                                 std::size_t slot) const {
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

void RunKinematics::absolute_accelerations(double t, const dynamics::VectorXd& y, dynamics::VectorXd& accel) const {
  dynamics_.derivative(t, y, y_dot_);
  accel = y_dot_.segment(system_.dof(), system_.dof()) + system_.ground_acceleration(t);
}

void RunKinematics::measure(double t, const dynamics::VectorXd& y, bool accelerations, bool drifts,
                            Instant& into) const {
  into.t_s = t;
  into.y = y;
  into.rate_known = false;
  if (accelerations) absolute_accelerations(t, y, into.accel);
  if (drifts) storey_drifts(y, into.drifts);
}

void RunKinematics::free_acceleration_rates(double t, const dynamics::VectorXd& y, const dynamics::VectorXd& accel,
                                            dynamics::VectorXd& rate) const {
  // Free motion: q̈ = A_v y − r a_g (A_v the acceleration rows of A), so q̈ + r a_g = A_v y and
  // its rate is A_v ẏ, the forcing's slope cancelling. The system's free rhs at the "state" ẏ
  // gives A_v ẏ − r a_g(t) in its acceleration rows (sparse, O(n)). r a_g: summed over components.
  const int n = system_.dof();
  const dynamics::VectorXd ground = system_.ground_acceleration(t);
  y_dot_ << y.segment(n, n), accel - ground;  // free motion: no Bouc–Wen states
  system_.rhs(t, y_dot_, y_ddot_);
  rate = y_ddot_.segment(n, n) + ground;
}

}  // namespace pounding::solvers
