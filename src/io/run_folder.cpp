#include "pounding/io/run_folder.hpp"

#include <fmt/format.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "pounding/input_error.hpp"

namespace pounding::io {

namespace {

const nlohmann::json& field(const nlohmann::json& object, const std::string& key, const std::string& name,
                            const std::string& file) {
  if (!object.is_object() || !object.contains(key)) {
    throw InputError(name, "", "is missing (not a pounding run's summary.json?)", file);
  }
  return object.at(key);
}

}  // namespace

RunSceneReference read_run_scene_reference(const std::filesystem::path& folder) {
  const std::filesystem::path summary = folder / "summary.json";
  std::ifstream in(summary);
  if (!in) {
    throw InputError("RUN_DIR", folder.string(), "holds no summary.json (is it the output folder of `pounding run`?)");
  }
  const nlohmann::json document = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (document.is_discarded()) throw InputError("summary.json", "", "is not valid JSON", summary.string());
  const nlohmann::json& gap = field(document, "gap_m", "gap_m", summary.string());
  const nlohmann::json& provenance = field(document, "provenance", "provenance", summary.string());
  const nlohmann::json& scene_file = field(provenance, "scene_file", "provenance.scene_file", summary.string());
  const nlohmann::json& scene_sha = field(provenance, "scene_sha256", "provenance.scene_sha256", summary.string());
  RunSceneReference reference;
  if (const auto pairs = document.find("pairs"); gap.is_null() && pairs != document.end() && pairs->is_array()) {
    for (const nlohmann::json& pair : *pairs) {  // a row: its pairs' gaps, by name
      const nlohmann::json& names = field(pair, "names", "pairs[].names", summary.string());
      const nlohmann::json& pair_gap = field(pair, "gap_m", "pairs[].gap_m", summary.string());
      if (!names.is_array() || names.size() != 2 || !names[0].is_string() || !names[1].is_string() ||
          !pair_gap.is_number()) {
        throw InputError("pairs[]", pair.dump(), "must name two buildings and a gap_m", summary.string());
      }
      // The shortest text that reads back to the same gap, so the scene is moved to it exactly.
      reference.gaps.push_back(
          fmt::format("{}:{}={}", names[0].get<std::string>(), names[1].get<std::string>(), pair_gap.get<double>()));
    }
  } else if (!gap.is_number()) {
    throw InputError("gap_m", gap.dump(), "must be a number", summary.string());
  } else {
    reference.gap_m = gap.get<double>();
  }
  // null for a scene built in code (provenance_json writes empty text as null)
  const auto text = [&](const nlohmann::json& value, const std::string& name) {
    if (value.is_null()) return std::string();
    if (!value.is_string()) throw InputError(name, value.dump(), "must be text or null", summary.string());
    return value.get<std::string>();
  };
  reference.scene_file = text(scene_file, "provenance.scene_file");
  reference.scene_sha256 = text(scene_sha, "provenance.scene_sha256");
  return reference;
}

}  // namespace pounding::io
