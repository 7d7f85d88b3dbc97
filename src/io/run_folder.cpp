#include "pounding/io/run_folder.hpp"

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
  if (!gap.is_number()) throw InputError("gap_m", gap.dump(), "must be a number", summary.string());
  // null for a scene built in code (provenance_json writes empty text as null)
  const auto text = [&](const nlohmann::json& value, const std::string& name) {
    if (value.is_null()) return std::string();
    if (!value.is_string()) throw InputError(name, value.dump(), "must be text or null", summary.string());
    return value.get<std::string>();
  };
  return {text(scene_file, "provenance.scene_file"), text(scene_sha, "provenance.scene_sha256"), gap.get<double>()};
}

}  // namespace pounding::io
