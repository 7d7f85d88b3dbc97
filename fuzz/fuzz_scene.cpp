// Fuzz target: the scene reader. Any bytes as a scene file: parsed, validated, then what
// `check` does next (both buildings assembled, the record processed, the candidates found).
// Bad input must end in InputError; anything else (a crash, a sanitizer report, another
// exception) is a finding.

#include <string_view>

#include "fixtures.hpp"
#include "pounding/analysis/run_scene.hpp"
#include "pounding/input_error.hpp"
#include "pounding/io/scene_reader.hpp"
#include "pounding/model/building.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace pounding;
  static const std::filesystem::path scene_file = fuzz::fixture_folder() / "scene.toml";
  if (size > io::kMaxSceneBytes) return 0;  // read_scene refuses these unread
  try {
    const analysis::Scene scene =
        io::parse_scene(std::string_view(reinterpret_cast<const char*>(data), size), scene_file);
    analysis::build_system(scene);
  } catch (const InputError&) {
  }
  return 0;
}
