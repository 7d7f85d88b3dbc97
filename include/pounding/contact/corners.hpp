#pragma once
// How contacts continue round the corners of slabs (docs/model.md §5a): which candidate takes a
// contact over when its vertex slides off the end of its edge, which candidates share a contact
// point, and how deep a point lies inside a slab. Found once from the candidate list (rest
// geometry); the event loop applies them (solvers/contact_states.hpp, CornerCover).

#include <array>
#include <vector>

#include "pounding/contact/candidates.hpp"
#include "pounding/model/polygon.hpp"

namespace pounding::contact {

inline constexpr long kNoCandidate = -1;

/// Per candidate (indices into the candidate list; kNoCandidate where there is none), for each
/// end of its struck edge (0: Q1, 1: Q2):
struct CornerLinks {
  /// The twin: the struck slab's corner at that end against the striking slab's edge that ends at
  /// the striking vertex and faces the struck edge back (normals more than 45° apart from
  /// parallel, same direction). When the vertex slides past the corner while the slabs still
  /// press, the corner carries on the contact with nearly the same normal. Slab to slab only.
  std::vector<std::array<long, 2>> twin;
  /// The next edge: the same vertex (or column point) against the struck slab's edge that meets
  /// the struck edge at that end (a contact that passes an obtuse or reflex corner of the struck
  /// slab stays inside it).
  std::vector<std::array<long, 2>> next;
  /// Per candidate, its contact point's group: the candidates that share its vertex (or column
  /// point), level (floors) and struck slab, which one contact at that point covers.
  std::vector<std::size_t> group;
  std::vector<std::vector<std::size_t>> members;  // per group, its candidates in list order
  /// Per candidate, for each end of its struck edge: the group of that corner of the struck slab
  /// against the striking slab (kNoCandidate if that corner has no candidate there). A contact at
  /// this candidate's vertex lying at that corner covers that group (docs/model.md §5a).
  std::vector<std::array<long, 2>> edge_end_group;
};

/// The links of `candidates`, whose buildings (0-based in the scene) have slab outlines of
/// `outline_sizes[b]` vertices.
CornerLinks link_corners(const std::vector<Candidate>& candidates, const std::vector<std::size_t>& outline_sizes);

/// The depth (m) of `p` inside the polygon `outline` (vertices in order, either sense): its
/// distance to the nearest edge when strictly inside, 0 on the boundary or outside.
double depth_inside(const std::vector<model::Point2>& outline, const model::Point2& p);

}  // namespace pounding::contact
