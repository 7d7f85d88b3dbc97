#pragma once
// Runs a scene: assembles the model, finds the contact candidates, builds the coupled system and
// integrates it with the scene's solver settings.

#include <vector>

#include "pounding/analysis/scene.hpp"
#include "pounding/contact/candidates.hpp"
#include "pounding/dynamics/coupled_system.hpp"
#include "pounding/solvers/event_driven.hpp"
#include "pounding/solvers/hht.hpp"
#include "pounding/solvers/run_result.hpp"

namespace pounding::analysis {

/// The candidates the scene's geometry allows (DESIGN.md §2), on every level (Scene::levels()).
std::vector<contact::Candidate> scene_candidates(const Scene& scene);

/// The coupled system of a scene (assembles both buildings, loads the record).
/// @throws InputError for bad buildings or a bad record.
dynamics::CoupledSystem build_system(const Scene& scene);

/// The event-driven integrator that `solver` names (CVODE or ARKODE).
solvers::IntegratorFactory integrator_factory(const SolverSettings& solver);

/// The HHT-α options that scene.solver and scene.output describe.
solvers::HhtOptions hht_options(const Scene& scene);

/// A run together with what it was run on, for writers and printers.
struct RunReport {
  std::string scene;
  double gap_m = 0.0;
  double restitution = 0.0;
  SolverSettings solver;
  double hold_velocity_mps = 0.0;
  std::vector<contact::Level> levels;
  std::vector<contact::Candidate> candidates;
  solvers::RunResult result;
};

/// Integrates the scene with scene.solver (method, rtol, atol) and scene.output.
/// @throws InputError for invalid settings; numerical trouble comes back in the status.
RunReport run_scene(const Scene& scene);

}  // namespace pounding::analysis
