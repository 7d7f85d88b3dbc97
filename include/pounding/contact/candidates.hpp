#pragma once
// Contact candidates: (vertex of one slab, edge of the other slab at the same level) pairs that
// the scene can actually bring together. Everything else stays out of the root functions.
// Slabs meet slab to slab where floors of the two buildings stand at a common elevation (a
// level); a slab between two floors of the other building meets that building's facade columns
// (column_contact.hpp), with the column point in the vertex's role.

#include <array>
#include <string>
#include <vector>

#include "pounding/model/polygon.hpp"

namespace pounding::contact {

/// Two floors, one of each building of a pair, at a common elevation.
struct Level {
  int index = 1;                    // 1-based among the common levels, lowest first (a row: pair by pair)
  std::array<int, 2> floors{1, 1};  // 1-based floor of the pair's first building and of its second
  double elevation_m = 0.0;         // of the first building's floor above the ground (m)
  std::array<int, 2> pair{0, 1};    // the pair's buildings (0-based in the scene, first < second)
};

/// The levels of two buildings whose floors stand at `elevations` (m above the ground, floor 1
/// first, ascending): each floor of building 1 paired with the floor of building 2 within
/// `tolerance_m` of it, lowest first. Empty when no floors coincide.
/// @pre 0 < tolerance_m < half of every storey height, so a floor meets at most one floor.
std::vector<Level> common_levels(const std::array<std::vector<double>, 2>& elevations, double tolerance_m);

/// One vertex–edge pair at one level, in rest geometry (global plan coordinates, m). For a
/// slab-to-column pair (`column` true) the vertex is the facade point of a column of
/// `striking_building` at the slab's elevation, which moves with the column's two floors, and the
/// edge is the slab's: "striking" and "struck" name the gap's roles, not which body moves.
struct Candidate {
  int level = 1;                    // 1-based level index: the contacts solved together
  std::array<int, 2> floors{1, 1};  // the level's floor of the pair's first building and of its second
  double elevation_m = 0.0;         // the level's elevation (m)
  int striking_building = 0;        // owns the vertex P (0-based in the scene; one of `pair`)
  int struck_building = 1;          // the other one of `pair`: owns the edge Q1→Q2
  std::size_t vertex_index = 0;     // index of P in the striking slab's outline
  std::size_t edge_index = 0;       // edge i runs from vertex i to vertex i + 1
  model::Point2 vertex_rest;        // P
  model::Point2 edge_start_rest;    // Q1
  model::Point2 edge_end_rest;      // Q2
  model::Point2 normal_rest;        // outward unit normal of the struck edge at rest
  // Slab to column only (level 0): the column `column_index` (0-based in its building's list)
  // spans its storey from `lower_floor` (0: the ground) to floors[striking_building], of height
  // `storey_height_m`; the slab meets it at `height_ratio` ξ ∈ (0, 1) up that storey, where the
  // member's local flexibility along the normal is `flexibility_m_per_kN` (column_flexibility).
  bool column = false;
  /// A corner candidate: the vertex can reach the edge only around a corner of the struck slab
  /// (a side edge of facades in line, or an edge that faces away at rest). It is dormant (no root
  /// function) until its vertex comes onto the edge (docs/model.md §4).
  bool corner = false;
  int lower_floor = 0;
  std::size_t column_index = 0;
  double storey_height_m = 0.0;
  double height_ratio = 0.0;
  double flexibility_m_per_kN = 0.0;
  std::array<int, 2> pair{0, 1};  // the two buildings, first < second (0-based in the scene; two buildings: {0, 1})

  /// The floor of `building` (one of `pair`) this candidate reads.
  int floor_of(int building) const { return floors[building == pair[0] ? 0 : 1]; }
};

/// `candidates` found for two buildings (indices 0 and 1) moved onto the scene's buildings `pair`
/// with their levels numbered after `level_offset` (slab to column keeps level 0).
void place_in_pair(std::vector<Candidate>& candidates, const std::array<int, 2>& pair, int level_offset);

/// Rest geometry of the two slab outlines (the same on every floor) and their CMs.
struct PairGeometry {
  std::array<model::Polygon, 2> slabs;
  std::array<model::Point2, 2> centres_of_mass;
};

struct CandidateOptions {
  /// The largest relative displacement (m) of two facing slabs that the search must cover:
  /// a vertex is kept when, at rest, it lies in front of the edge at most gap + margin away and
  /// its projection falls on the edge or at most `margin_m` beyond an end. Default 1 m: far
  /// above the storey drifts of ordinary buildings, far below slab dimensions.
  double margin_m = 1.0;
  double gap_m = 0.0;  // the scene's clear gap
};

/// All candidates on `levels`, level by level: the facing ones (building 1's vertices first),
/// then the corner ones (corner_reach). Each level repeats the same vertex–edge pairs because all
/// floors of a building share its outline. @pre both slabs simple and counter-clockwise.
std::vector<Candidate> find_candidates(const PairGeometry& geometry, const std::vector<Level>& levels,
                                       const CandidateOptions& options);

/// Whether `vertex`, at rest, lies in front of the edge q1→q2 (outward unit `normal`) within
/// options.gap_m + margin and projects onto it or within the margin beyond an end: the rule that
/// keeps a vertex–edge pair (slab corners and column points alike).
bool within_reach(const model::Point2& vertex, const model::Point2& q1, const model::Point2& q2,
                  const model::Point2& normal, const CandidateOptions& options);
/// Whether `vertex`, at rest, lies within options.gap_m + margin of the segment q1→q2 (Euclidean),
/// whatever side of the edge's line it is on: the rule that adds corner candidates, the pairs the
/// facing rule (within_reach on a facing edge) leaves out.
bool corner_reach(const model::Point2& vertex, const model::Point2& q1, const model::Point2& q2,
                  const CandidateOptions& options);
/// The outward unit normal of the edge q1→q2 of a counter-clockwise outline.
model::Point2 outward_normal(const model::Point2& q1, const model::Point2& q2);
/// Whether some vertex of `other` lies in front of the edge from q1 with outward `normal`.
bool faces(const model::Point2& q1, const model::Point2& normal, const model::Polygon& other);

/// The striking vertex's 1-based number in its slab outline, as outputs name it; 0 for a column
/// point, which is no slab vertex.
inline std::size_t vertex_number(const Candidate& c) { return c.column ? 0 : c.vertex_index + 1; }

/// The buildings as the outputs name them (0-based in the scene): the one whose slab strikes, then
/// the one struck. Slab to slab these are the gap's striking and struck buildings; slab to column
/// the slab's building strikes (the gap's struck_building, which owns the edge) and the column's
/// is struck.
inline std::array<int, 2> striker_and_struck(const Candidate& c) {
  return c.column ? std::array{c.struck_building, c.striking_building}
                  : std::array{c.striking_building, c.struck_building};
}

/// Whether any candidate is slab to column (the outputs then carry the column's fields).
bool has_column_pairs(const std::vector<Candidate>& candidates);

/// "B1 vertex 3 (0, 20) -> B2 edge 4 (0.2, 33)-(0.2, 8)" style label (1-based indices); for a
/// slab-to-column pair "B2 column 4 (0.2, 13) storey 2 at 0.5 -> B1 edge 2 (0, 0)-(0, 20)".
std::string describe(const Candidate& candidate);

}  // namespace pounding::contact
