#include "pounding/dynamics/yielding_springs.hpp"

#include <fmt/format.h>

#include <cmath>

namespace pounding::dynamics {

namespace {

/// The springs of one building (empty if its columns stay elastic).
void add_building_springs(const model::Building& building, int b, int offset, std::vector<YieldingSpring>& springs) {
  const model::BuildingDefinition& d = building.definition;
  if (!d.hysteresis.yields()) return;
  for (int storey = 1; storey <= d.storeys; ++storey) {
    const double height_m = d.storey_height_m[storey - 1];
    for (std::size_t c = 0; c < d.columns.size(); ++c) {
      const model::Column& column = d.columns[c];
      const Eigen::Vector2d k = model::column_stiffness(column, d.E_kPa, height_m, building.frame_factor);
      const model::Point2 arm = column.position_m - d.centre_of_mass;
      // Row of T = [[1, 0, −Δy], [0, 1, Δx]] for each direction, upper floor minus lower floor.
      const std::array<std::array<double, 3>, 2> t_rows{{{1.0, 0.0, -arm.y()}, {0.0, 1.0, arm.x()}}};
      for (int direction = 0; direction < 2; ++direction) {
        YieldingSpring spring{.building = b,
                              .storey = storey,
                              .direction = direction,
                              .column = column.key.empty() ? fmt::format("columns[{}]", c + 1) : column.key,
                              .stiffness_kN_per_m = k[direction],
                              .hardening_ratio = d.hysteresis.hardening_ratio,
                              .yield_drift_m = d.hysteresis.yield_drift_of(height_m),
                              .storey_height_m = height_m};
        for (int floor : {storey, storey - 1}) {
          if (floor == 0) continue;  // the ground does not move relative to the base
          const double sign = floor == storey ? 1.0 : -1.0;
          for (int i = 0; i < 3; ++i) {
            if (t_rows[direction][i] == 0.0) continue;
            spring.indices.push_back(offset + 3 * (floor - 1) + i);
            spring.coefficients.push_back(sign * t_rows[direction][i]);
          }
        }
        springs.push_back(std::move(spring));
      }
    }
  }
}

}  // namespace

YieldingSprings::YieldingSprings(const std::array<model::Building, 2>& buildings, const std::array<int, 2>& offsets) {
  for (int b = 0; b < 2; ++b) add_building_springs(buildings[b], b, offsets[b], springs_);
}

double YieldingSprings::drift(const Eigen::Ref<const Eigen::VectorXd>& q, std::size_t j) const {
  const YieldingSpring& s = springs_[j];
  double d = 0.0;
  for (std::size_t i = 0; i < s.indices.size(); ++i) d += s.coefficients[i] * q[s.indices[i]];
  return d;
}

double YieldingSprings::slip(const Eigen::Ref<const Eigen::VectorXd>& q, const SpringStates& states,
                             std::size_t j) const {
  switch (states[j].branch) {
    case SpringBranch::elastic:
      return states[j].slip_m;
    case SpringBranch::yielding_up:
      return drift(q, j) - springs_[j].yield_drift_m;
    case SpringBranch::yielding_down:
      return drift(q, j) + springs_[j].yield_drift_m;
  }
  return 0.0;
}

void YieldingSprings::add_slip_force(const Eigen::Ref<const Eigen::VectorXd>& q, const SpringStates& states,
                                     Eigen::Ref<Eigen::VectorXd> force) const {
  for (std::size_t j = 0; j < springs_.size(); ++j) {
    const double s = slip(q, states, j);
    if (s == 0.0) continue;
    const YieldingSpring& spring = springs_[j];
    const double magnitude = spring.plastic_stiffness() * s;
    for (std::size_t i = 0; i < spring.indices.size(); ++i)
      force[spring.indices[i]] += magnitude * spring.coefficients[i];
  }
}

void YieldingSprings::add_tangent_rows(const SpringStates& states, const Eigen::VectorXd& inverse_mass,
                                       Eigen::SparseMatrix<double>& rows) const {
  std::vector<Eigen::Triplet<double>> terms;
  for (std::size_t j = 0; j < springs_.size(); ++j) {
    if (states[j].branch == SpringBranch::elastic) continue;
    const YieldingSpring& spring = springs_[j];
    // s_j = d_j ∓ d_y: the slip force (1 − α) k t tᵀ q adds to q̈ through M⁻¹.
    for (std::size_t a = 0; a < spring.indices.size(); ++a) {
      for (std::size_t c = 0; c < spring.indices.size(); ++c) {
        terms.emplace_back(spring.indices[a], spring.indices[c],
                           inverse_mass[spring.indices[a]] * spring.plastic_stiffness() * spring.coefficients[a] *
                               spring.coefficients[c]);
      }
    }
  }
  if (terms.empty()) return;
  Eigen::SparseMatrix<double> tangent(rows.rows(), rows.cols());
  tangent.setFromTriplets(terms.begin(), terms.end());
  rows += tangent;
}

double YieldingSprings::witness(const Eigen::Ref<const Eigen::VectorXd>& y, const SpringStates& states,
                                std::size_t j) const {
  const Eigen::Index n = y.size() / 2;
  switch (states[j].branch) {
    case SpringBranch::elastic:
      return springs_[j].yield_drift_m - std::abs(drift(y.head(n), j) - states[j].slip_m);
    case SpringBranch::yielding_up:
      return drift(y.tail(n), j);
    case SpringBranch::yielding_down:
      return -drift(y.tail(n), j);
  }
  return 1.0;
}

double YieldingSprings::stored_energy_change(const Eigen::Ref<const Eigen::VectorXd>& q,
                                             const SpringStates& states) const {
  double change_kJ = 0.0;
  for (std::size_t j = 0; j < springs_.size(); ++j) {
    const double s = slip(q, states, j);
    change_kJ += springs_[j].plastic_stiffness() * s * (0.5 * s - drift(q, j));
  }
  return change_kJ;
}

}  // namespace pounding::dynamics
