#pragma once
// What a scene's plan and elevation hold, for `pounding plan` to draw before anything is run:
// the slab outlines, columns, centres of mass and of stiffness, the levels where floors meet and
// the contact candidates there. Units: m, s; global plan coordinates at rest.

#include <array>
#include <string>
#include <vector>

#include "pounding/analysis/scene.hpp"
#include "pounding/contact/candidates.hpp"
#include "pounding/model/building.hpp"

namespace pounding::analysis {

struct BuildingPlan {
  std::string name;
  model::Polygon slab;
  model::Point2 centre_of_mass = model::Point2::Zero();
  std::vector<model::Column> columns;      // empty for storeys given as 3×3 matrices
  std::vector<double> floor_elevations_m;  // floor 1 first
  /// Per storey (storey 1 first): where a storey shear acts without twisting it, from its 3×3
  /// stiffness K about the CM, CM + (K_φv/K_vv, −K_φu/K_uu).
  std::vector<model::Point2> centres_of_stiffness;
  std::vector<double> periods_s;  // the first three modes' (P-Δ included when the scene asks)
};

struct ScenePlan {
  std::string scene;
  double gap_m = 0.0;
  std::vector<BuildingPlan> buildings;
  std::vector<BuildingPair> pairs;  // a row's neighbouring pairs; empty for two buildings
  std::vector<contact::Level> levels;
  std::vector<contact::Candidate> candidates;
};

/// @throws InputError for a building that cannot be assembled (as a run would).
ScenePlan scene_plan(const Scene& scene);

}  // namespace pounding::analysis
