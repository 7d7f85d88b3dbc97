#include "pounding/contact/gap.hpp"

#include <cmath>

#include "pounding/contact/column_contact.hpp"

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

/// The projection parameter of d = P − Q1 on `edge` (Q1Q2 as it stands), for candidate c.
double segment_param(const Candidate& c, const Point2& d, const Point2& edge) {
  const double length = edge.norm();
  // (An edge of a few micrometres, which no slab has, is taken whole.)
  if (!c.corner || length <= 4.0 * kCornerEdgeInset_m) return d.dot(edge) / edge.squaredNorm();
  return (d.dot(edge) / length - kCornerEdgeInset_m) / (length - 2.0 * kCornerEdgeInset_m);
}

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
  s.segment_param = segment_param(c, d, edge);
  s.contact_point = p;
  s.normal = n;
  s.striking_row << n.x(), n.y(), cross(arm_p, n);
  s.struck_row << -n.x(), -n.y(), -cross(arm_q + d, n);
  // g̈ = d̈·n + 2 ḋ·ṅ + d·n̈; the parts without accelerations are the centripetal terms of P and
  // Q1, the Coriolis-like 2 ḋ·ṅ, and −φ̇_B² d·n from n̈.
  s.curvature_mps2 = -spin_a * spin_a * arm_p.dot(n) + spin_b * spin_b * arm_q.dot(n) + 2.0 * d_dot.dot(n_dot) -
                     spin_b * spin_b * d.dot(n);
  return s;
}

// The edge side repeats evaluate_gap's lines rather than sharing a helper with it: regrouping
// evaluate_gap's sums would change its last bits, and so every slab-to-slab output.
GapState evaluate_column_gap(const Candidate& c, const SlabMotion* lower, const SlabMotion& upper,
                             const SlabMotion& b) {
  const auto [weight_lower, weight_upper] = column_shape(c.height_ratio);
  // The column point as each floor carries it; the ground's stays at rest.
  const Point2 arm_upper = rotation(upper.q[2]) * (c.vertex_rest - upper.centre_rest);
  const Point2 arm_lower =
      lower ? Point2(rotation(lower->q[2]) * (c.vertex_rest - lower->centre_rest)) : Point2::Zero();
  const Point2 p_upper = upper.centre_rest + upper.q.head<2>() + arm_upper;
  const Point2 p_lower = lower ? Point2(lower->centre_rest + lower->q.head<2>() + arm_lower) : c.vertex_rest;
  const Point2 v_upper = upper.q_dot.head<2>() + upper.q_dot[2] * perp(arm_upper);
  const Point2 v_lower = lower ? Point2(lower->q_dot.head<2>() + lower->q_dot[2] * perp(arm_lower)) : Point2::Zero();
  const double spin_upper = upper.q_dot[2], spin_lower = lower ? lower->q_dot[2] : 0.0;

  const Eigen::Matrix2d rot_b = rotation(b.q[2]);
  const Point2 arm_q = rot_b * (c.edge_start_rest - b.centre_rest);
  const Point2 p = weight_lower * p_lower + weight_upper * p_upper;
  const Point2 q1 = b.centre_rest + b.q.head<2>() + arm_q;
  const Point2 n = rot_b * c.normal_rest;
  const Point2 edge = rot_b * (c.edge_end_rest - c.edge_start_rest);
  const double spin_b = b.q_dot[2];
  const Point2 d = p - q1;
  const Point2 d_dot = weight_lower * v_lower + weight_upper * v_upper - (b.q_dot.head<2>() + spin_b * perp(arm_q));
  const Point2 n_dot = spin_b * perp(n);

  GapState s;
  s.gap_m = d.dot(n);
  s.gap_rate_mps = d_dot.dot(n) + d.dot(n_dot);
  s.segment_param = segment_param(c, d, edge);
  s.contact_point = p;
  s.normal = n;
  s.striking_row << weight_upper * n.x(), weight_upper * n.y(), weight_upper * cross(arm_upper, n);
  if (lower) s.striking_lower_row << weight_lower * n.x(), weight_lower * n.y(), weight_lower * cross(arm_lower, n);
  s.struck_row << -n.x(), -n.y(), -cross(arm_q + d, n);
  // As evaluate_gap, with the column point's centripetal terms weighted by its floors' shares.
  s.curvature_mps2 = -weight_lower * spin_lower * spin_lower * arm_lower.dot(n) -
                     weight_upper * spin_upper * spin_upper * arm_upper.dot(n) + spin_b * spin_b * arm_q.dot(n) +
                     2.0 * d_dot.dot(n_dot) - spin_b * spin_b * d.dot(n);
  return s;
}

}  // namespace pounding::contact
