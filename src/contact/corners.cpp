#include "pounding/contact/corners.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <tuple>

namespace pounding::contact {

using model::Point2;

namespace {

/// What identifies a contact point: its level (floors), the striking building and vertex (or,
/// for a column point, column, storey and point), and the struck building.
using PointKey = std::tuple<int, int, int, int, bool, std::size_t, double, double, int>;

PointKey point_key(const Candidate& c) {
  const bool column = c.column;
  return PointKey(c.level, c.floors[0], c.floors[1], c.striking_building, column,
                  column ? c.column_index : c.vertex_index, column ? c.vertex_rest.x() : 0.0,
                  column ? c.vertex_rest.y() : 0.0, c.struck_building);
}

/// The struck edge's vertex index at `end` (0: its start, 1: its end) in an outline of `size`.
std::size_t edge_vertex(const Candidate& c, int end, std::size_t size) {
  return end == 0 ? c.edge_index : (c.edge_index + 1) % size;
}

}  // namespace

CornerLinks link_corners(const std::vector<Candidate>& candidates, const std::vector<std::size_t>& outline_sizes) {
  const std::size_t n = candidates.size();
  CornerLinks links{std::vector<std::array<long, 2>>(n, {kNoCandidate, kNoCandidate}),
                    std::vector<std::array<long, 2>>(n, {kNoCandidate, kNoCandidate}),
                    std::vector<std::size_t>(n),
                    {},
                    std::vector<std::array<long, 2>>(n, {kNoCandidate, kNoCandidate})};
  std::map<PointKey, std::size_t> groups;
  for (std::size_t i = 0; i < n; ++i) {
    const auto [at, added] = groups.emplace(point_key(candidates[i]), links.members.size());
    if (added) links.members.emplace_back();
    links.group[i] = at->second;
    links.members[at->second].push_back(i);
  }
  // Links only ever join candidates of one level (floors): look within each.
  std::map<std::tuple<int, int, int>, std::vector<std::size_t>> at_floors;
  for (std::size_t i = 0; i < n; ++i) {
    const Candidate& c = candidates[i];
    at_floors[{c.level, c.floors[0], c.floors[1]}].push_back(i);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Candidate& c = candidates[i];
    const std::size_t struck_size = outline_sizes[static_cast<std::size_t>(c.struck_building)];
    for (int end = 0; end < 2; ++end) {
      const std::size_t corner = edge_vertex(c, end, struck_size);
      const std::size_t next_edge = end == 0 ? (c.edge_index + struck_size - 1) % struck_size : corner;
      double most_opposed = -std::cos(std::numbers::pi / 4.0);
      for (std::size_t j : at_floors[{c.level, c.floors[0], c.floors[1]}]) {
        const Candidate& o = candidates[j];
        if (j == i) continue;
        if (o.striking_building == c.striking_building && o.struck_building == c.struck_building &&
            point_key(o) == point_key(c) && o.edge_index == next_edge) {
          links.next[i][end] = static_cast<long>(j);
        }
        if (c.column || o.column || o.striking_building != c.struck_building || o.vertex_index != corner) continue;
        if (o.struck_building == c.striking_building) {
          // The striking slab's edges that meet at the striking vertex.
          const std::size_t size = outline_sizes[static_cast<std::size_t>(c.striking_building)];
          const bool at_vertex = o.edge_index == c.vertex_index || (o.edge_index + 1) % size == c.vertex_index;
          const double alignment = o.normal_rest.dot(c.normal_rest);
          if (at_vertex && alignment < most_opposed) {
            most_opposed = alignment;
            links.twin[i][end] = static_cast<long>(j);
          }
          const auto group = groups.find(point_key(o));
          if (group != groups.end()) links.edge_end_group[i][end] = static_cast<long>(group->second);
        }
      }
    }
  }
  return links;
}

double depth_inside(const std::vector<Point2>& outline, const Point2& p) {
  bool inside = false;  // even-odd ray casting towards +x
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const Point2& a = outline[i];
    const Point2& b = outline[(i + 1) % outline.size()];
    if ((a.y() > p.y()) != (b.y() > p.y())) {
      const double x_cross = a.x() + (p.y() - a.y()) / (b.y() - a.y()) * (b.x() - a.x());
      if (p.x() < x_cross) inside = !inside;
    }
    const Point2 edge = b - a;
    const double along = std::clamp((p - a).dot(edge) / edge.squaredNorm(), 0.0, 1.0);
    nearest = std::min(nearest, (a + along * edge - p).norm());
  }
  return inside ? nearest : 0.0;
}

}  // namespace pounding::contact
