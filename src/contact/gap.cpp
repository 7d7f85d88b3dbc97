#include "pounding/contact/gap.hpp"

#include <cmath>

namespace pounding::contact {
namespace {

using model::Point2;

Eigen::Matrix2d rotation(double phi) {
  const double c = std::cos(phi), s = std::sin(phi);
  return (Eigen::Matrix2d() << c, -s, s, c).finished();
}

/// J a with J the rotation by +90°: the velocity direction of a point at arm a for φ̇ = 1.
Point2 perp(const Point2& a) { return {-a.y(), a.x()}; }

/// Planar cross product a × b (scalar).
double cross(const Point2& a, const Point2& b) { return a.x() * b.y() - a.y() * b.x(); }

}  // namespace

GapState evaluate_gap(const Candidate& c, const SlabMotion& a, const SlabMotion& b) {
  const Eigen::Matrix2d rot_a = rotation(a.q[2]), rot_b = rotation(b.q[2]);
  const Point2 arm_p = rot_a * (c.vertex_rest - a.centre_rest);      // P from A's CM
  const Point2 arm_q = rot_b * (c.edge_start_rest - b.centre_rest);  // Q1 from B's CM
  const Point2 p = a.centre_rest + a.q.head<2>() + arm_p;
  const Point2 q1 = b.centre_rest + b.q.head<2>() + arm_q;
  const Point2 n = rot_b * c.normal_rest;
  const Point2 edge = rot_b * (c.edge_end_rest - c.edge_start_rest);

  const double spin_a = a.q_dot[2], spin_b = b.q_dot[2];
  const Point2 d = p - q1;
  const Point2 d_dot = (a.q_dot.head<2>() + spin_a * perp(arm_p)) - (b.q_dot.head<2>() + spin_b * perp(arm_q));
  const Point2 n_dot = spin_b * perp(n);

  GapState s;
  s.gap_m = d.dot(n);
  s.gap_rate_mps = d_dot.dot(n) + d.dot(n_dot);
  s.segment_param = d.dot(edge) / edge.squaredNorm();
  s.contact_point = p;
  s.normal = n;
  s.striking_row << n.x(), n.y(), cross(arm_p, n);
  s.struck_row << -n.x(), -n.y(), -cross(arm_q + d, n);
  // g̈ = d̈·n + 2 ḋ·ṅ + d·n̈; the parts without accelerations are the centripetal terms of P and
  // Q1, the Coriolis-like 2 ḋ·ṅ, and −φ̇_B² d·n from n̈.
  s.curvature_mps2 = -spin_a * spin_a * arm_p.dot(n) + spin_b * spin_b * arm_q.dot(n) +
                     2.0 * d_dot.dot(n_dot) - spin_b * spin_b * d.dot(n);
  return s;
}

}  // namespace pounding::contact
