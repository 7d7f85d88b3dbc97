#pragma once
// What `pounding modes` and `pounding check` report about a scene, computed once here so the
// command-line program only prints it.

#include <string>
#include <vector>

#include "pounding/analysis/scene.hpp"
#include "pounding/model/mode.hpp"

namespace pounding::analysis {

struct BuildingSummary {
  std::string name;
  int storeys = 0;
  int dof = 0;
  double total_mass_t = 0.0;
  double frame_factor = 1.0;  // the one used (solved when a target period was given)
  bool frame_factor_solved = false;
  model::RayleighCoefficients rayleigh;
  std::vector<model::Mode> modes;  // all 3N, longest period first
};

/// Assembles both buildings of `scene` and runs their modal analyses. @throws InputError.
std::vector<BuildingSummary> summarise_buildings(const Scene& scene);

}  // namespace pounding::analysis
