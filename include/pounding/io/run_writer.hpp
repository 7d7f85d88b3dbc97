#pragma once
// Writes a run: summary.json, impacts.csv (one row an impact) and history.csv (one row a sample).

#include <filesystem>
#include <ostream>
#include <nlohmann/json.hpp>

#include "pounding/analysis/run_scene.hpp"
#include "pounding/io/provenance.hpp"

namespace pounding::io {

/// The whole report as JSON (keys carry units), keys in a fixed order: scene, method, status,
/// status_detail, settings, ..., provenance last. See README.md, "Outputs of pounding run".
nlohmann::ordered_json run_json(const analysis::RunReport& report, const Provenance& provenance);

/// yielding.csv's text: a header, then one row per yielding column spring (building, storey,
/// column, direction, stiffness, hardening ratio, yield drift, peak drift and ductility, first
/// yield (empty: never), yielding phases, hysteretic energy, final drift and slip). Written only
/// for runs whose columns yield.
void write_yielding_rows(const analysis::RunReport& report, std::ostream& out);

/// Writes the three files into `folder` (created if missing), each atomically, summary.json
/// last: a folder holding a summary.json holds the complete outputs of that run.
/// @throws std::runtime_error naming a file that cannot be written.
void write_run(const analysis::RunReport& report, const Provenance& provenance, const std::filesystem::path& folder);

}  // namespace pounding::io
