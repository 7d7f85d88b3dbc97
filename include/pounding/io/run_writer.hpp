#pragma once
// Writes a run: summary.json, impacts.csv (one row an impact) and history.csv (one row a sample).

#include <filesystem>
#include <nlohmann/json.hpp>

#include "pounding/analysis/run_scene.hpp"

namespace pounding::io {

/// The whole report as JSON (keys carry units). See README.md, "Outputs of pounding run".
nlohmann::json run_json(const analysis::RunReport& report);

/// Writes the three files into `folder` (created if missing), each atomically, summary.json
/// last: a folder holding a summary.json holds the complete outputs of that run.
/// @throws std::runtime_error naming a file that cannot be written.
void write_run(const analysis::RunReport& report, const std::filesystem::path& folder);

}  // namespace pounding::io
