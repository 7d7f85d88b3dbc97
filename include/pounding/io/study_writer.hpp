#pragma once
// Writes a work–precision study: study.csv (one row a run), stiffness.csv, truncation.csv and study.json.

#include <filesystem>
#include <nlohmann/json.hpp>

#include "pounding/analysis/study.hpp"
#include "pounding/io/provenance.hpp"

namespace pounding::io {

nlohmann::json study_json(const analysis::StudyResult& study);

/// Writes study.csv, stiffness.csv, truncation.csv and study.json (study_json() plus "provenance") into `folder`
/// (created if missing).
/// @throws std::runtime_error naming a file that cannot be written.
void write_study(const analysis::StudyResult& study, const Provenance& provenance, const std::filesystem::path& folder);

}  // namespace pounding::io
