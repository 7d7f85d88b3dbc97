#pragma once
// Writes a work–precision study: study.csv (one row a run) and study.json.

#include <filesystem>
#include <nlohmann/json.hpp>

#include "pounding/analysis/study.hpp"

namespace pounding::io {

nlohmann::json study_json(const analysis::StudyResult& study);

/// Writes study.csv and study.json into `folder` (created if missing).
/// @throws std::runtime_error naming a file that cannot be written.
void write_study(const analysis::StudyResult& study, const std::filesystem::path& folder);

}  // namespace pounding::io
