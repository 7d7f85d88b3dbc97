#pragma once
// Contact candidates: (vertex of one slab, edge of the other slab at the same level) pairs that
// the scene can actually bring together. Everything else stays out of the root functions.
// Slabs meet only where floors of the two buildings stand at a common elevation (a level); a
// slab striking the other building's columns between floors is outside this model.

#include <array>
#include <string>
#include <vector>

#include "pounding/model/polygon.hpp"

namespace pounding::contact {

/// Two floors, one of each building, at a common elevation.
struct Level {
  int index = 1;                    // 1-based among the common levels, lowest first
  std::array<int, 2> floors{1, 1};  // 1-based floor of building 1 and of building 2
  double elevation_m = 0.0;         // of building 1's floor above the ground (m)
};

/// The levels of two buildings whose floors stand at `elevations` (m above the ground, floor 1
/// first, ascending): each floor of building 1 paired with the floor of building 2 within
/// `tolerance_m` of it, lowest first. Empty when no floors coincide.
/// @pre 0 < tolerance_m < half of every storey height, so a floor meets at most one floor.
std::vector<Level> common_levels(const std::array<std::vector<double>, 2>& elevations, double tolerance_m);

/// One vertex–edge pair at one level, in rest geometry (global plan coordinates, m).
struct Candidate {
  int level = 1;                    // 1-based level index: the contacts solved together
  std::array<int, 2> floors{1, 1};  // the level's floor of building 1 and of building 2
  double elevation_m = 0.0;         // the level's elevation (m)
  int striking_building = 0;      // 0 or 1: owns the vertex P
  int struck_building = 1;        // the other one: owns the edge Q1→Q2
  std::size_t vertex_index = 0;   // index of P in the striking slab's outline
  std::size_t edge_index = 0;     // edge i runs from vertex i to vertex i + 1
  model::Point2 vertex_rest;      // P
  model::Point2 edge_start_rest;  // Q1
  model::Point2 edge_end_rest;    // Q2
  model::Point2 normal_rest;      // outward unit normal of the struck edge at rest
};

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

/// All candidates on `levels`, level by level, building 1's vertices first. Each level repeats
/// the same vertex–edge pairs because all floors of a building share its outline.
/// @pre both slabs simple and counter-clockwise.
std::vector<Candidate> find_candidates(const PairGeometry& geometry, const std::vector<Level>& levels,
                                       const CandidateOptions& options);

/// "B1 vertex 3 (0, 20) -> B2 edge 4 (0.2, 33)-(0.2, 8)" style label (1-based indices).
std::string describe(const Candidate& candidate);

}  // namespace pounding::contact
