#pragma once
// Writes what `pounding gap` finds: gap.json (the needed gap, its pair and instant, the levels,
// the modes and the code rules), gap.csv (one row a level), gap_history.csv (the touch gap of each
// level's governing pair over time) and, with a severity curve, gap_curve.csv (one row a gap);
// for a record set, records.csv (one row a record) and records.json (the rows and statistics).

#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "pounding/analysis/needed_gap.hpp"
#include "pounding/analysis/record_set.hpp"
#include "pounding/io/provenance.hpp"

namespace pounding::io {

/// Top-level keys: scene, scene_gap_m, needed_gap_m, level, floor (the level's floors of
/// building 1 and 2), t_s, pair, levels, modes, rho, rules {abs_m, srss_m, ddc_m},
/// unconservative, extrema, steps, wall_time_s, curve when `curve` is not empty, and all_angles
/// when gap.all_angles is set (gap_angles.csv is then written beside).
nlohmann::json gap_json(const std::string& scene, const analysis::NeededGap& gap,
                        const std::vector<analysis::SeverityPoint>& curve = {});

/// Writes the files into `folder` (created if missing); gap.json is gap_json() plus "provenance".
/// @throws std::runtime_error naming a file that cannot be written.
void write_gap(const std::string& scene, const analysis::NeededGap& gap,
               const std::vector<analysis::SeverityPoint>& curve, const Provenance& provenance,
               const std::filesystem::path& folder);

/// Top-level keys: scene, records (one object a record: record, source, status, message,
/// pga_g, duration_s, needed_gap_m, level, floor, t_s, rules {abs_m, srss_m, ddc_m}, steps,
/// wall_time_s), statistics {needed_gap_m, abs_m, srss_m, ddc_m: {count, mean, median, log_mean,
/// log_std, p84_lognormal}, lognormal_std}, worst (the record with the largest needed gap),
/// failed, wall_time_s. Numbers that do not exist (a failed record's) are null.
nlohmann::json record_set_json(const std::string& scene, const analysis::RecordSetResult& set);

/// Writes records.csv and records.json (record_set_json() plus "provenance") into `folder`
/// (created if missing). @throws std::runtime_error naming a file that cannot be written.
void write_record_set(const std::string& scene, const analysis::RecordSetResult& set, const Provenance& provenance,
                      const std::filesystem::path& folder);

}  // namespace pounding::io
