#include "pounding/analysis/run_scene.hpp"

#include <fmt/format.h>

#include "pounding/input_error.hpp"
#include "pounding/solvers/arkode_integrator.hpp"
#include "pounding/solvers/cvode_integrator.hpp"
#include "pounding/solvers/exact_integrator.hpp"
#include "pounding/solvers/event_driven.hpp"
#include "pounding/solvers/hht.hpp"

namespace pounding::analysis {

namespace {
constexpr double kExactSubdivisionsPerPeriod = 16.0;
}  // namespace

std::vector<contact::Candidate> scene_candidates(const Scene& scene) {
  contact::PairGeometry geometry{{scene.buildings[0].slab, scene.buildings[1].slab},
                                 {scene.buildings[0].centre_of_mass, scene.buildings[1].centre_of_mass}};
  return contact::find_candidates(geometry, scene.levels(),
                                  {.margin_m = scene.contact.candidate_margin_m, .gap_m = scene.contact.gap_m});
}

dynamics::CoupledSystem build_system(const Scene& scene) {
  std::array<model::Building, 2> buildings;
  for (std::size_t b = 0; b < 2; ++b) {
    try {
      buildings[b] = model::make_building(scene.buildings[b]);
    } catch (const InputError& error) {
      throw error.in_context(scene.file.string(), fmt::format("building[{}]", b + 1));
    }
  }
  return dynamics::CoupledSystem(std::move(buildings), excitation::load_ground_motion(scene.excitation),
                                 scene.levels(), scene_candidates(scene));
}

solvers::HhtOptions hht_options(const Scene& scene) {
  solvers::HhtOptions options;
  options.dt_s = scene.solver.dt_s;
  options.alpha = scene.solver.alpha;
  options.contact_tolerance_m = scene.solver.contact_tolerance_m;
  options.max_halvings = scene.solver.max_halvings;
  const std::string& location = scene.solver.event_location;
  options.location = location == "end-of-step"   ? solvers::HhtEventLocation::end_of_step
                     : location == "interpolate" ? solvers::HhtEventLocation::interpolate
                                                 : solvers::HhtEventLocation::halving;
  options.restitution = scene.contact.restitution;
  options.history_floors = scene.output.history_floors;
  options.history_interval_s = scene.output.history_interval_s;
  return options;
}

namespace {

solvers::NewtonSolver newton_solver(const SolverSettings& solver) {
  return solver.newton == "dense" ? solvers::NewtonSolver::dense : solvers::NewtonSolver::second_order;
}

solvers::EventOptions event_options(const Scene& scene) {
  solvers::EventOptions options;
  options.restitution = scene.contact.restitution;
  options.hold_velocity_mps = scene.contact.hold_velocity_mps;
  options.history_floors = scene.output.history_floors;
  options.history_interval_s = scene.output.history_interval_s;
  if (scene.solver.method == "exact") {
    // Bracket roots on a subdivision fine against the shortest period that moves a gap.
    options.steps_per_period = kExactSubdivisionsPerPeriod;
  }
  return options;
}

}  // namespace

RunReport run_scene(const Scene& scene) {
  const dynamics::CoupledSystem system = build_system(scene);
  RunReport report{scene.name, scene.contact.gap_m, scene.contact.restitution, scene.solver,
                   scene.contact.hold_velocity_mps, system.levels(), system.candidates(), {}};
  report.result = scene.solver.method == "hht"
                      ? solvers::run_hht(system, hht_options(scene), "hht")
                      : solvers::run_event_driven(system, event_options(scene),
                                                  integrator_factory(scene.solver), scene.solver.method);
  return report;
}

solvers::IntegratorFactory integrator_factory(const SolverSettings& solver) {
  using IntegratorPtr = std::unique_ptr<solvers::Integrator>;
  if (solver.method == "exact") {
    const solvers::ExactSettings settings{solver.hold_rtol, solver.hold_rtol / 100};
    return [settings](solvers::OdeFunctions& functions, double t0, const Eigen::VectorXd& y0) -> IntegratorPtr {
      return std::make_unique<solvers::ExactIntegrator>(functions, t0, y0, settings);
    };
  }
  if (solver.method.starts_with("arkode")) {
    solvers::ArkodeSettings settings;
    settings.method = solver.method == "arkode-erk" ? solvers::ArkodeMethod::erk : solvers::ArkodeMethod::dirk;
    settings.order = solver.order;
    settings.newton_solver = newton_solver(solver);
    settings.rtol = solver.rtol;
    settings.atol = solver.atol;
    return [settings](solvers::OdeFunctions& functions, double t0, const Eigen::VectorXd& y0) {
      return solvers::make_arkode_integrator(functions, settings, t0, y0);
    };
  }
  solvers::CvodeSettings settings;
  settings.method = solver.method == "cvode-adams" ? solvers::CvodeMethod::adams : solvers::CvodeMethod::bdf;
  settings.rtol = solver.rtol;
  settings.atol = solver.atol;
  settings.newton_solver = newton_solver(solver);
  return [settings](solvers::OdeFunctions& functions, double t0, const Eigen::VectorXd& y0) -> IntegratorPtr {
    return std::make_unique<solvers::CvodeIntegrator>(functions, settings, t0, y0);
  };
}

}  // namespace pounding::analysis
