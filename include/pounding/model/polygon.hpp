#pragma once
// Plan geometry of a slab: a simple polygon in global plan coordinates (m), counter-clockwise.

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace pounding::model {

using Point2 = Eigen::Vector2d;

/// A closed polygon given by its vertices in order; the closing edge is implicit.
/// Edge i runs from vertex i to vertex (i + 1) mod n.
class Polygon {
 public:
  Polygon() = default;
  explicit Polygon(std::vector<Point2> vertices) : vertices_(std::move(vertices)) {}

  const std::vector<Point2>& vertices() const { return vertices_; }
  std::size_t size() const { return vertices_.size(); }
  const Point2& vertex(std::size_t i) const { return vertices_[i]; }
  const Point2& edge_end(std::size_t i) const { return vertices_[(i + 1) % size()]; }

  /// Signed area (m²): positive for counter-clockwise vertex order.
  double signed_area() const;
  /// Area centroid (m). @pre signed_area() != 0.
  Point2 centroid() const;
  /// Polar second moment of area about the centroid, Ix + Iy (m⁴). @pre counter-clockwise.
  double polar_area_moment_about_centroid() const;

  /// True when no two non-adjacent edges meet and no two vertices coincide.
  bool is_simple() const;
  /// True when `p` lies strictly inside (points on the boundary are not inside).
  bool contains_strictly(const Point2& p) const;
  /// True when `p` lies inside or on the boundary (to `tolerance_m`).
  bool contains(const Point2& p, double tolerance_m = 1e-12) const;

  /// The same polygon moved by `offset_m`.
  Polygon translated(const Point2& offset_m) const;

 private:
  std::vector<Point2> vertices_;
};

/// True when the interiors of `a` and `b` overlap (touching along an edge or at a vertex is
/// not an overlap). @pre both simple.
bool interiors_overlap(const Polygon& a, const Polygon& b);

/// Clear distance (m) that `right` can move along −x before it touches `left`, i.e. the
/// minimum horizontal distance from `left` to `right` over the heights (y) they share.
/// Empty when no horizontal line meets both polygons with `right` on the +x side, so no
/// motion along x can bring them together. Negative values mean the two overlap.
std::optional<double> horizontal_clearance(const Polygon& left, const Polygon& right);

/// How far apart two polygons stand: the shortest distance between their outlines (m) and the
/// unit direction in which `b` would move away from `a` to widen it: the outward normal of the
/// edge that holds the nearest point (`a`'s, or minus `b`'s); where several edges do (a nearest
/// corner lies on two), the one pointing most from a's centroid towards b's. @pre interiors not
/// overlapping, both counter-clockwise.
struct Clearance {
  double distance_m = 0.0;
  Point2 direction = Point2::UnitX();
};
Clearance clearance(const Polygon& a, const Polygon& b);

}  // namespace pounding::model
