#include "pounding/contact/candidates.hpp"

#include <fmt/format.h>

namespace pounding::contact {
namespace {

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

void add_pairs(const PairGeometry& geometry, int striking, int floor, const CandidateOptions& options,
               std::vector<Candidate>& out) {
  const int struck = 1 - striking;
  const model::Polygon& vertices = geometry.slabs[striking];
  const model::Polygon& edges = geometry.slabs[struck];
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const Point2& q1 = edges.vertex(e);
    const Point2& q2 = edges.edge_end(e);
    const Point2 normal = outward_normal(q1, q2);
    if (!faces(q1, normal, vertices)) continue;
    const double length = (q2 - q1).norm();
    const Point2 tangent = (q2 - q1) / length;
    for (std::size_t v = 0; v < vertices.size(); ++v) {
      const Point2& p = vertices.vertex(v);
      const double distance = (p - q1).dot(normal);
      const double along = (p - q1).dot(tangent);
      const bool in_front = distance >= -1e-9 && distance <= options.gap_m + options.margin_m;
      const bool over_edge = along >= -options.margin_m && along <= length + options.margin_m;
      if (in_front && over_edge) {
        out.push_back({floor, striking, struck, v, e, p, q1, q2, normal});
      }
    }
  }
}

}  // namespace

std::vector<Candidate> find_candidates(const PairGeometry& geometry, int common_floors,
                                       const CandidateOptions& options) {
  std::vector<Candidate> candidates;
  for (int floor = 1; floor <= common_floors; ++floor) {
    add_pairs(geometry, 0, floor, options, candidates);
    add_pairs(geometry, 1, floor, options, candidates);
  }
  return candidates;
}

std::string describe(const Candidate& c) {
  return fmt::format("B{} vertex {} ({:g}, {:g}) -> B{} edge {} ({:g}, {:g})-({:g}, {:g})",
                     c.striking_building + 1, c.vertex_index + 1, c.vertex_rest.x(), c.vertex_rest.y(),
                     c.struck_building + 1, c.edge_index + 1, c.edge_start_rest.x(),
                     c.edge_start_rest.y(), c.edge_end_rest.x(), c.edge_end_rest.y());
}

}  // namespace pounding::contact
