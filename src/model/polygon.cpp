#include "pounding/model/polygon.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pounding::model {
namespace {

double cross(const Point2& a, const Point2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Orientation of c relative to the directed line a→b: +1 left, −1 right, 0 collinear.
int orientation(const Point2& a, const Point2& b, const Point2& c) {
  const double value = cross(b - a, c - a);
  const double scale = (b - a).norm() * (c - a).norm();
  if (std::abs(value) <= 1e-12 * scale) return 0;
  return value > 0 ? 1 : -1;
}

bool on_segment(const Point2& a, const Point2& b, const Point2& p) {
  return orientation(a, b, p) == 0 && p.x() >= std::min(a.x(), b.x()) - 1e-12 &&
         p.x() <= std::max(a.x(), b.x()) + 1e-12 && p.y() >= std::min(a.y(), b.y()) - 1e-12 &&
         p.y() <= std::max(a.y(), b.y()) + 1e-12;
}

/// Closed segments a1a2 and b1b2 share at least one point.
bool segments_meet(const Point2& a1, const Point2& a2, const Point2& b1, const Point2& b2) {
  const int o1 = orientation(a1, a2, b1), o2 = orientation(a1, a2, b2);
  const int o3 = orientation(b1, b2, a1), o4 = orientation(b1, b2, a2);
  if (o1 != o2 && o3 != o4 && o1 != 0 && o2 != 0 && o3 != 0 && o4 != 0) return true;
  return on_segment(a1, a2, b1) || on_segment(a1, a2, b2) || on_segment(b1, b2, a1) || on_segment(b1, b2, a2);
}

/// Segments cross at a single interior point of both (a proper crossing).
bool segments_cross_properly(const Point2& a1, const Point2& a2, const Point2& b1, const Point2& b2) {
  const int o1 = orientation(a1, a2, b1), o2 = orientation(a1, a2, b2);
  const int o3 = orientation(b1, b2, a1), o4 = orientation(b1, b2, a2);
  return o1 * o2 < 0 && o3 * o4 < 0;
}

/// Distances t ≥ 0... along direction ±x from `origin` to the non-horizontal edges of `target`.
void horizontal_hits(const Point2& origin, double direction, const Polygon& target, double& best) {
  for (std::size_t i = 0; i < target.size(); ++i) {
    const Point2& a = target.vertex(i);
    const Point2& b = target.edge_end(i);
    if (a.y() == b.y()) continue;  // parallel: its end points are cast from the other side
    const double y_low = std::min(a.y(), b.y()), y_high = std::max(a.y(), b.y());
    if (origin.y() < y_low || origin.y() > y_high) continue;
    const double s = (origin.y() - a.y()) / (b.y() - a.y());
    const double x_hit = a.x() + s * (b.x() - a.x());
    best = std::min(best, direction * (x_hit - origin.x()));
  }
}

}  // namespace

double Polygon::signed_area() const {
  double twice_area = 0.0;
  for (std::size_t i = 0; i < size(); ++i) twice_area += cross(vertex(i), edge_end(i));
  return 0.5 * twice_area;
}

Point2 Polygon::centroid() const {
  Point2 sum = Point2::Zero();
  for (std::size_t i = 0; i < size(); ++i) {
    sum += (vertex(i) + edge_end(i)) * cross(vertex(i), edge_end(i));
  }
  return sum / (6.0 * signed_area());
}

double Polygon::polar_area_moment_about_centroid() const {
  // Second moments about the origin by the shoelace-type formulas, then moved to the centroid.
  // Vertices are shifted to the first vertex first to keep the sums well conditioned.
  const Point2 origin = vertex(0);
  double ixx = 0.0, iyy = 0.0;
  for (std::size_t i = 0; i < size(); ++i) {
    const Point2 p = vertex(i) - origin, q = edge_end(i) - origin;
    const double c = cross(p, q);
    ixx += c * (p.y() * p.y() + p.y() * q.y() + q.y() * q.y());
    iyy += c * (p.x() * p.x() + p.x() * q.x() + q.x() * q.x());
  }
  const double area = signed_area();
  const Point2 offset = centroid() - origin;
  return (ixx + iyy) / 12.0 - area * offset.squaredNorm();
}

bool Polygon::is_simple() const {
  const std::size_t n = size();
  if (n < 3) return false;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      if ((vertex(i) - vertex(j)).norm() == 0.0) return false;
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
      if (adjacent) {
        // Adjacent edges share one vertex; they must not fold back onto each other.
        const std::size_t shared = (j == i + 1) ? j : i;
        const Point2& before = vertex((shared + n - 1) % n);
        const Point2& after = edge_end(shared);
        if (orientation(before, vertex(shared), after) == 0 &&
            (after - vertex(shared)).dot(before - vertex(shared)) > 0) {
          return false;
        }
        continue;
      }
      if (segments_meet(vertex(i), edge_end(i), vertex(j), edge_end(j))) return false;
    }
  }
  return std::abs(signed_area()) > 0.0;
}

bool Polygon::contains(const Point2& p, double tolerance_m) const {
  for (std::size_t i = 0; i < size(); ++i) {
    const Point2& a = vertex(i);
    const Point2& b = edge_end(i);
    const double length = (b - a).norm();
    const double s = std::clamp((p - a).dot(b - a) / (length * length), 0.0, 1.0);
    if ((a + s * (b - a) - p).norm() <= tolerance_m) return true;
  }
  return contains_strictly(p);
}

bool Polygon::contains_strictly(const Point2& p) const {
  for (std::size_t i = 0; i < size(); ++i) {
    if (on_segment(vertex(i), edge_end(i), p)) return false;
  }
  bool inside = false;  // even-odd ray casting towards +x
  for (std::size_t i = 0; i < size(); ++i) {
    const Point2& a = vertex(i);
    const Point2& b = edge_end(i);
    if ((a.y() > p.y()) != (b.y() > p.y())) {
      const double x_cross = a.x() + (p.y() - a.y()) / (b.y() - a.y()) * (b.x() - a.x());
      if (p.x() < x_cross) inside = !inside;
    }
  }
  return inside;
}

Polygon Polygon::translated(const Point2& offset_m) const {
  std::vector<Point2> moved = vertices_;
  for (Point2& v : moved) v += offset_m;
  return Polygon(std::move(moved));
}

bool interiors_overlap(const Polygon& a, const Polygon& b) {
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) {
      if (segments_cross_properly(a.vertex(i), a.edge_end(i), b.vertex(j), b.edge_end(j))) {
        return true;
      }
    }
  }
  // No proper crossing: either disjoint, touching, or one holds the other (or shares its
  // outline). An interior point of an edge midpoint region decides the nested cases.
  for (const Point2& v : a.vertices()) {
    if (b.contains_strictly(v)) return true;
  }
  for (const Point2& v : b.vertices()) {
    if (a.contains_strictly(v)) return true;
  }
  return b.contains_strictly(a.centroid()) || a.contains_strictly(b.centroid());
}

std::optional<double> horizontal_clearance(const Polygon& left, const Polygon& right) {
  constexpr double kNone = std::numeric_limits<double>::infinity();
  double best = kNone;
  for (const Point2& v : left.vertices()) horizontal_hits(v, +1.0, right, best);
  for (const Point2& v : right.vertices()) horizontal_hits(v, -1.0, left, best);
  if (best == kNone) return std::nullopt;
  return best;
}

namespace {

/// Each vertex of `points` against each edge of counter-clockwise `edges`: its distance, and
/// `sign` times the edge's outward normal (+: `points` is the second polygon).
struct Approach {
  double distance_m;
  Point2 direction;
};
void approaches(const Polygon& points, const Polygon& edges, double sign, std::vector<Approach>& out) {
  const std::vector<Point2>& q = edges.vertices();
  for (std::size_t i = 0; i < q.size(); ++i) {
    const Point2& q1 = q[i];
    const Point2& q2 = q[(i + 1) % q.size()];
    const Point2 along = q2 - q1;
    const Point2 normal = Point2(along.y(), -along.x()).normalized();
    for (const Point2& p : points.vertices()) {
      const double s = std::clamp((p - q1).dot(along) / along.squaredNorm(), 0.0, 1.0);
      out.push_back({(p - (q1 + s * along)).norm(), sign * normal});
    }
  }
}

}  // namespace

Clearance clearance(const Polygon& a, const Polygon& b) {
  std::vector<Approach> all;
  approaches(b, a, +1.0, all);  // a's edge nearest to a vertex of b: b moves out along its normal
  approaches(a, b, -1.0, all);
  double nearest = std::numeric_limits<double>::infinity();
  for (const Approach& x : all) nearest = std::min(nearest, x.distance_m);
  // A nearest corner lies on two edges (facades in line, corners face to face): of the edges at the
  // nearest distance, the one whose normal points most from a's centroid towards b's.
  const Point2 towards = b.centroid() - a.centroid();
  Clearance best{nearest, Point2::UnitX()};
  double best_alignment = -std::numeric_limits<double>::infinity();
  for (const Approach& x : all) {
    if (x.distance_m > nearest + 1e-9) continue;
    const double alignment = x.direction.dot(towards);
    if (alignment > best_alignment) {
      best_alignment = alignment;
      best.direction = x.direction;
    }
  }
  return best;
}

}  // namespace pounding::model
