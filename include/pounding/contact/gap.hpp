#pragma once
// Signed gap of one candidate in the current configuration, with exact planar rotation, and its
// first and second time derivatives.

#include <Eigen/Core>

#include "pounding/contact/candidates.hpp"

namespace pounding::contact {

/// How far beyond an edge's ends (fraction of the edge) a vertex still counts as on the edge.
inline constexpr double kOnSegmentTolerance = 1e-9;
/// A corner candidate's edge is taken this much (m) short of either end: a vertex at the struck
/// slab's corner itself lies on the facing edge there, whose candidate holds it; it meets the
/// side edge only once over it (docs/model.md §5a).
inline constexpr double kCornerEdgeInset_m = 1e-6;

/// Motion of one slab: displacements of its CM and rotation, and their rates.
struct SlabMotion {
  model::Point2 centre_rest = model::Point2::Zero();  // CM at rest (m)
  Eigen::Vector3d q = Eigen::Vector3d::Zero();        // u (m), v (m), φ (rad)
  Eigen::Vector3d q_dot = Eigen::Vector3d::Zero();    // m/s, m/s, rad/s
};

/// Everything about one candidate at one instant.
/// Sign convention: g > 0 separated, g = 0 contact, g < 0 overlap; ġ < 0 approaching.
struct GapState {
  double gap_m = 0.0;
  double gap_rate_mps = 0.0;    // ġ = G q̇
  double segment_param = 0.0;   // projection of P on Q1Q2: 0 at Q1, 1 at Q2 (a corner
                                // candidate's: on its edge less kCornerEdgeInset_m at each end)
  model::Point2 contact_point;  // current position of P (m)
  model::Point2 normal;         // current outward unit normal of the struck edge
  /// ġ = striking_row · q̇_striking + struck_row · q̇_struck. striking_row = (n_x, n_y, ρ_A × n),
  /// struck_row = −(n_x, n_y, ρ_B × n), ρ = arm from each slab's CM to the current P.
  Eigen::RowVector3d striking_row;
  Eigen::RowVector3d struck_row;
  /// Slab to column: striking_row is over the column's upper floor, times its weight N₂, and this
  /// over its lower floor, times N₁ (zero for the ground, which does not move).
  Eigen::RowVector3d striking_lower_row = Eigen::RowVector3d::Zero();
  double curvature_mps2 = 0.0;  // h in g̈ = G q̈ + h (centripetal and normal-rotation terms)

  bool on_segment(double tolerance = kOnSegmentTolerance) const {
    return segment_param >= -tolerance && segment_param <= 1.0 + tolerance;
  }
};

/// Evaluates the candidate for the given slab motions. No preconditions; O(1).
GapState evaluate_gap(const Candidate& candidate, const SlabMotion& striking, const SlabMotion& struck);

/// Evaluates a slab-to-column candidate: the column point P = N₁ p_lower + N₂ p_upper
/// (column_shape at the candidate's height ratio), p the point carried by each floor's motion;
/// `lower` null for the ground (p = the point at rest). @pre candidate.column.
GapState evaluate_column_gap(const Candidate& candidate, const SlabMotion* lower, const SlabMotion& upper,
                             const SlabMotion& struck);

}  // namespace pounding::contact
