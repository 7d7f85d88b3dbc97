#pragma once
// The output of `pounding plan`: plan.json, the scene's plan and elevation as analysis::scene_plan
// finds them (m, s), with provenance; tools/plot_plan.py draws it.

#include <filesystem>

#include <nlohmann/json.hpp>

#include "pounding/analysis/plan.hpp"
#include "pounding/io/provenance.hpp"

namespace pounding::io {

/// Keys: scene, gap_m, buildings [{name, slab [[x, y]...], centre_of_mass [x, y], columns
/// [{x_m, y_m, b_m, h_m}], floor_elevations_m, centres_of_stiffness [[x, y] per storey],
/// periods_s}], levels [{level, floors, elevation_m}], candidates [{level, striking_building,
/// vertex [x, y], edge [[x, y], [x, y]]}] (buildings numbered from 1).
nlohmann::ordered_json plan_json(const analysis::ScenePlan& plan);

/// Writes plan.json (plan_json() plus "provenance") into `folder` (created if missing).
/// @throws std::runtime_error naming the file if it cannot be written.
void write_plan(const analysis::ScenePlan& plan, const Provenance& provenance, const std::filesystem::path& folder);

}  // namespace pounding::io
