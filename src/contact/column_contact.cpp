#include "pounding/contact/column_contact.hpp"

#include <algorithm>
#include <cmath>

namespace pounding::contact {

using model::Point2;

std::array<double, 2> column_shape(double xi) {
  const double upper = xi * xi * (3.0 - 2.0 * xi);
  return {1.0 - upper, upper};
}

double column_flexibility(const model::Column& column, double elastic_modulus_kPa, double length_m, double height_ratio,
                          const Point2& normal) {
  const double a = height_ratio * length_m, b = length_m - a;
  const double inertia_x = column.h_m * std::pow(column.b_m, 3) / 12.0;  // deflection along x
  const double inertia_y = column.b_m * std::pow(column.h_m, 3) / 12.0;
  const double direction = normal.x() * normal.x() / inertia_x + normal.y() * normal.y() / inertia_y;
  return std::pow(a * b, 3) / (3.0 * elastic_modulus_kPa * std::pow(length_m, 3)) * direction;
}

ColumnDemand column_demand(double force_kN, double length_m, double height_ratio) {
  const double l = length_m, a = height_ratio * l, b = l - a, p = force_kN;
  const double shear = std::max(p * b * b * (3.0 * a + b), p * a * a * (a + 3.0 * b)) / (l * l * l);
  const double moment =
      std::max({p * a * b * b / (l * l), p * a * a * b / (l * l), 2.0 * p * a * a * b * b / (l * l * l)});
  return {shear, moment};
}

std::vector<ColumnLevel> column_levels(const std::array<std::vector<double>, 2>& elevations, double tolerance_m) {
  std::vector<ColumnLevel> levels;
  for (int slab = 0; slab < 2; ++slab) {
    const std::vector<double>& own = elevations[slab];
    const std::vector<double>& other = elevations[1 - slab];
    for (std::size_t f = 0; f < own.size(); ++f) {
      const double z = own[f];
      // The other building's first floor above z (its storey), or none above its roof.
      const auto upper = std::upper_bound(other.begin(), other.end(), z);
      if (upper == other.end()) continue;
      const double below = upper == other.begin() ? 0.0 : *(upper - 1);
      if (std::abs(*upper - z) <= tolerance_m || (upper != other.begin() && z - below <= tolerance_m)) continue;
      const double height = *upper - below;
      levels.push_back({slab, static_cast<int>(f) + 1, z, static_cast<int>(upper - other.begin()) + 1, height,
                        (z - below) / height});
    }
  }
  return levels;
}

std::vector<FacadeColumn> facade_columns(const model::BuildingDefinition& own, const model::Polygon& other) {
  std::vector<FacadeColumn> facade;
  const model::Polygon& slab = own.slab;
  for (std::size_t k = 0; k < own.columns.size(); ++k) {
    const model::Column& column = own.columns[k];
    const double reach = std::max(column.b_m, column.h_m) / 2.0;
    const std::size_t first = facade.size();
    for (std::size_t e = 0; e < slab.size(); ++e) {
      const Point2& q1 = slab.vertex(e);
      const Point2& q2 = slab.edge_end(e);
      const Point2 normal = outward_normal(q1, q2);
      if (!faces(q1, normal, other)) continue;
      const Point2 edge = q2 - q1;
      const double along = (column.position_m - q1).dot(edge) / edge.squaredNorm();
      if (std::abs((column.position_m - q1).dot(normal)) > reach || along < 0.0 || along > 1.0) continue;
      // A column near a corner stands on both faces: a point on each, once if they coincide (a
      // column centred on the corner projects onto the corner from either edge).
      const Point2 point = q1 + along * edge;
      const auto same = [&](const FacadeColumn& f) { return (f.point - point).norm() <= 1e-9; };
      if (std::none_of(facade.begin() + static_cast<std::ptrdiff_t>(first), facade.end(), same)) {
        facade.push_back({k, point});
      }
    }
  }
  return facade;
}

std::vector<Candidate> find_column_candidates(const std::array<const model::BuildingDefinition*, 2>& buildings,
                                              const std::vector<ColumnLevel>& levels, const CandidateOptions& options) {
  std::vector<Candidate> candidates;
  std::array<std::vector<FacadeColumn>, 2> facade;
  for (int b = 0; b < 2; ++b) facade[b] = facade_columns(*buildings[b], buildings[1 - b]->slab);
  for (const ColumnLevel& level : levels) {
    const int struck = level.slab_building, striking = 1 - struck;  // the column point is the vertex
    const model::BuildingDefinition& columns = *buildings[striking];
    const model::Polygon& slab = buildings[struck]->slab;
    const auto add = [&](std::size_t e, const FacadeColumn& point, bool corner) {
      const Point2& q1 = slab.vertex(e);
      const Point2& q2 = slab.edge_end(e);
      const Point2 normal = outward_normal(q1, q2);
      Candidate c{0, {0, 0}, level.elevation_m, striking, struck, 0, e, point.point, q1, q2, normal};
      c.floors[struck] = level.slab_floor;
      c.floors[striking] = level.storey;
      c.column = true;
      c.corner = corner;
      c.lower_floor = level.storey - 1;
      c.column_index = point.column;
      c.storey_height_m = level.storey_height_m;
      c.height_ratio = level.height_ratio;
      c.flexibility_m_per_kN = column_flexibility(columns.columns[point.column], columns.E_kPa, level.storey_height_m,
                                                  level.height_ratio, normal);
      candidates.push_back(c);
    };
    // The facing pairs, then (as for slabs) the corner ones: a column standing at a slab corner
    // may come round onto the other slab's side edge.
    std::vector<std::array<std::size_t, 2>> facing;  // (edge, facade point) pairs taken
    for (std::size_t e = 0; e < slab.size(); ++e) {
      const Point2& q1 = slab.vertex(e);
      const Point2 normal = outward_normal(q1, slab.edge_end(e));
      if (!faces(q1, normal, columns.slab)) continue;
      for (std::size_t k = 0; k < facade[striking].size(); ++k) {
        if (!within_reach(facade[striking][k].point, q1, slab.edge_end(e), normal, options)) continue;
        add(e, facade[striking][k], false);
        facing.push_back({e, k});
      }
    }
    for (std::size_t e = 0; e < slab.size(); ++e) {
      for (std::size_t k = 0; k < facade[striking].size(); ++k) {
        const bool taken = std::find(facing.begin(), facing.end(), std::array<std::size_t, 2>{e, k}) != facing.end();
        if (!taken && corner_reach(facade[striking][k].point, slab.vertex(e), slab.edge_end(e), options))
          add(e, facade[striking][k], true);
      }
    }
  }
  return candidates;
}

}  // namespace pounding::contact
