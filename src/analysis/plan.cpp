#include "pounding/analysis/plan.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "pounding/analysis/run_scene.hpp"
#include "pounding/input_error.hpp"

namespace pounding::analysis {

namespace {

/// The storey's centre of stiffness, from its stiffness about the CM (u, v, φ): a unit u produces
/// a torque K_φu, so the x shear acts at y = −K_φu/K_uu from the CM; likewise x = K_φv/K_vv.
model::Point2 centre_of_stiffness(const Eigen::Matrix3d& storey, const model::Point2& centre_of_mass) {
  return centre_of_mass + model::Point2(storey(2, 1) / storey(1, 1), -storey(2, 0) / storey(0, 0));
}

BuildingPlan building_plan(const model::Building& building) {
  const model::BuildingDefinition& d = building.definition;
  BuildingPlan plan{.name = d.name,
                    .slab = d.slab,
                    .centre_of_mass = d.centre_of_mass,
                    .columns = d.columns,
                    .floor_elevations_m = model::floor_elevations(d),
                    .centres_of_stiffness = {},
                    .periods_s = {}};
  const std::vector<Eigen::Matrix3d> storeys =
      d.uses_columns() ? model::column_storey_matrices(d, d.frame_factor) : d.storey_stiffness;
  for (const Eigen::Matrix3d& storey : storeys)
    plan.centres_of_stiffness.push_back(centre_of_stiffness(storey, d.centre_of_mass));
  for (std::size_t k = 0; k < std::min<std::size_t>(3, building.modes.size()); ++k) {
    plan.periods_s.push_back(building.modes[k].period_s);
  }
  return plan;
}

}  // namespace

ScenePlan scene_plan(const Scene& scene) {
  ScenePlan plan{.scene = scene.name,
                 .gap_m = scene.contact.gap_m,
                 .buildings = {},
                 .levels = scene.levels(),
                 .candidates = scene_candidates(scene)};
  if (scene.is_row()) plan.pairs = scene.pairs();
  for (std::size_t b = 0; b < scene.buildings.size(); ++b) {
    try {
      plan.buildings.push_back(building_plan(model::make_building(scene.buildings[b])));
    } catch (const InputError& error) {
      throw error.in_context(scene.file.string(), fmt::format("building[{}]", b + 1));
    }
  }
  return plan;
}

}  // namespace pounding::analysis
