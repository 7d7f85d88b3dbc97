#include "pounding/analysis/modal_summary.hpp"

#include <fmt/format.h>

#include "pounding/input_error.hpp"

namespace pounding::analysis {

std::vector<BuildingSummary> summarise_buildings(const Scene& scene) {
  std::vector<BuildingSummary> summaries;
  for (std::size_t i = 0; i < scene.buildings.size(); ++i) {
    const model::BuildingDefinition& definition = scene.buildings[i];
    model::Building building;
    try {
      building = model::make_building(definition);
    } catch (const InputError& error) {
      throw error.in_context(scene.file.string(), fmt::format("building[{}]", i + 1));
    }
    BuildingSummary summary;
    summary.name = definition.name;
    summary.storeys = definition.storeys;
    summary.dof = building.dof();
    for (double m : definition.mass_t) summary.total_mass_t += m;
    summary.frame_factor = building.frame_factor;
    summary.frame_factor_solved = definition.uses_columns() && definition.target_period_s.has_value();
    summary.rayleigh = building.rayleigh;
    summary.modes = std::move(building.modes);
    summaries.push_back(std::move(summary));
  }
  return summaries;
}

}  // namespace pounding::analysis
