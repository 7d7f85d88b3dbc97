#pragma once
// Machine-readable reports. Every quantity's key carries its unit.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "pounding/analysis/modal_summary.hpp"

namespace pounding::io {

/// {"buildings": [{"name", "frame_factor", "periods_s": [...], "modes": [{"mode", "period_s",
/// "frequency_hz", "dominant", "effective_mass_ratio": {"x", "y", "rz"}}]}]}
nlohmann::json modes_json(const std::vector<analysis::BuildingSummary>& buildings);

/// Writes `document` (indented) to `file`, creating its folder; atomically (write_atomically).
/// @throws std::runtime_error naming the file if it cannot be written.
void write_json(const nlohmann::json& document, const std::filesystem::path& file);
void write_json(const nlohmann::ordered_json& document, const std::filesystem::path& file);

}  // namespace pounding::io
