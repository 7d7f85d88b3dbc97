#include "pounding/contact/candidates.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace pounding::contact {

using model::Point2;

Point2 outward_normal(const Point2& q1, const Point2& q2) {
  // For a counter-clockwise outline the interior lies to the left of each edge.
  const Point2 tangent = (q2 - q1).normalized();
  return {tangent.y(), -tangent.x()};
}

bool faces(const Point2& q1, const Point2& normal, const model::Polygon& other) {
  for (const Point2& v : other.vertices()) {
    if ((v - q1).dot(normal) > 0.0) return true;
  }
  return false;
}

bool within_reach(const Point2& p, const Point2& q1, const Point2& q2, const Point2& normal,
                  const CandidateOptions& options) {
  const double length = (q2 - q1).norm();
  const Point2 tangent = (q2 - q1) / length;
  const double distance = (p - q1).dot(normal);
  const double along = (p - q1).dot(tangent);
  const bool in_front = distance >= -1e-9 && distance <= options.gap_m + options.margin_m;
  const bool over_edge = along >= -options.margin_m && along <= length + options.margin_m;
  return in_front && over_edge;
}

bool corner_reach(const Point2& p, const Point2& q1, const Point2& q2, const CandidateOptions& options) {
  const Point2 edge = q2 - q1;
  const double along = std::clamp((p - q1).dot(edge) / edge.squaredNorm(), 0.0, 1.0);
  return (p - (q1 + along * edge)).norm() <= options.gap_m + options.margin_m;
}

namespace {

void add_pairs(const PairGeometry& geometry, int striking, const Level& level, const CandidateOptions& options,
               std::vector<Candidate>& out) {
  const int struck = 1 - striking;
  const model::Polygon& vertices = geometry.slabs[striking];
  const model::Polygon& edges = geometry.slabs[struck];
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const Point2& q1 = edges.vertex(e);
    const Point2& q2 = edges.edge_end(e);
    const Point2 normal = outward_normal(q1, q2);
    if (!faces(q1, normal, vertices)) continue;
    for (std::size_t v = 0; v < vertices.size(); ++v) {
      const Point2& p = vertices.vertex(v);
      if (within_reach(p, q1, q2, normal, options)) {
        out.push_back({level.index, level.floors, level.elevation_m, striking, struck, v, e, p, q1, q2, normal});
      }
    }
  }
}

/// The corner candidates of `striking`'s vertices at `level`: every vertex–edge pair within
/// corner_reach that `facing` (the level's facing candidates) does not hold.
void add_corner_pairs(const PairGeometry& geometry, int striking, const Level& level, const CandidateOptions& options,
                      const std::vector<Candidate>& facing, std::vector<Candidate>& out) {
  const int struck = 1 - striking;
  const model::Polygon& vertices = geometry.slabs[striking];
  const model::Polygon& edges = geometry.slabs[struck];
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const Point2& q1 = edges.vertex(e);
    const Point2& q2 = edges.edge_end(e);
    for (std::size_t v = 0; v < vertices.size(); ++v) {
      const auto same = [&](const Candidate& c) {
        return c.striking_building == striking && c.vertex_index == v && c.edge_index == e;
      };
      if (std::any_of(facing.begin(), facing.end(), same) || !corner_reach(vertices.vertex(v), q1, q2, options))
        continue;
      out.push_back({level.index, level.floors, level.elevation_m, striking, struck, v, e, vertices.vertex(v), q1, q2,
                     outward_normal(q1, q2)});
      out.back().corner = true;
    }
  }
}

}  // namespace

std::vector<Level> common_levels(const std::array<std::vector<double>, 2>& elevations, double tolerance_m) {
  // Both lists ascend: walk them together, advancing the lower floor until the two meet.
  const std::vector<double>& z1 = elevations[0];
  const std::vector<double>& z2 = elevations[1];
  std::vector<Level> levels;
  std::size_t i = 0, j = 0;
  while (i < z1.size() && j < z2.size()) {
    if (std::abs(z1[i] - z2[j]) <= tolerance_m) {
      levels.push_back(
          {static_cast<int>(levels.size()) + 1, {static_cast<int>(i) + 1, static_cast<int>(j) + 1}, z1[i]});
      ++i;
      ++j;
    } else if (z1[i] < z2[j]) {
      ++i;
    } else {
      ++j;
    }
  }
  return levels;
}

std::vector<Candidate> find_candidates(const PairGeometry& geometry, const std::vector<Level>& levels,
                                       const CandidateOptions& options) {
  std::vector<Candidate> candidates;
  for (const Level& level : levels) {
    const std::size_t first = candidates.size();
    add_pairs(geometry, 0, level, options, candidates);
    add_pairs(geometry, 1, level, options, candidates);
    const std::vector<Candidate> facing(candidates.begin() + static_cast<std::ptrdiff_t>(first), candidates.end());
    add_corner_pairs(geometry, 0, level, options, facing, candidates);
    add_corner_pairs(geometry, 1, level, options, facing, candidates);
  }
  return candidates;
}

void place_in_pair(std::vector<Candidate>& candidates, const std::array<int, 2>& pair, int level_offset) {
  for (Candidate& c : candidates) {
    c.pair = pair;
    c.striking_building = pair[static_cast<std::size_t>(c.striking_building)];
    c.struck_building = pair[static_cast<std::size_t>(c.struck_building)];
    if (c.level > 0) c.level += level_offset;
  }
}

bool has_column_pairs(const std::vector<Candidate>& candidates) {
  return std::any_of(candidates.begin(), candidates.end(), [](const Candidate& c) { return c.column; });
}

std::string describe(const Candidate& c) {
  if (c.column) {
    return fmt::format("B{} column {} ({:g}, {:g}) storey {} at {:.4g} -> B{} edge {} ({:g}, {:g})-({:g}, {:g})",
                       c.striking_building + 1, c.column_index + 1, c.vertex_rest.x(), c.vertex_rest.y(),
                       c.floor_of(c.striking_building), c.height_ratio, c.struck_building + 1, c.edge_index + 1,
                       c.edge_start_rest.x(), c.edge_start_rest.y(), c.edge_end_rest.x(), c.edge_end_rest.y());
  }
  return fmt::format("B{} vertex {} ({:g}, {:g}) -> B{} {}edge {} ({:g}, {:g})-({:g}, {:g})", c.striking_building + 1,
                     c.vertex_index + 1, c.vertex_rest.x(), c.vertex_rest.y(), c.struck_building + 1,
                     c.corner ? "corner " : "", c.edge_index + 1, c.edge_start_rest.x(), c.edge_start_rest.y(),
                     c.edge_end_rest.x(), c.edge_end_rest.y());
}

}  // namespace pounding::contact
