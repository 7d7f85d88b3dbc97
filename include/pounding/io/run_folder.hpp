#pragma once
// What a run folder (`pounding run --out FOLDER`) says about the scene it ran, read back so that
// `pounding animate` and `pounding report` can draw the plan of the run without being told it.

#include <filesystem>
#include <optional>
#include <vector>
#include <string>

namespace pounding::io {

/// The scene of a run as its summary.json records it.
struct RunSceneReference {
  std::filesystem::path scene_file;  // absolute as the run wrote it; empty for a scene built in code
  std::string scene_sha256;          // of the file when the run read it; empty with scene_file
  std::optional<double> gap_m;       // the clear gap the run used (m), after any --gap; a row: none
  std::vector<std::string> gaps;     // a row: each pair's gap as "NAME:NAME=m" (io::SceneOverrides::gaps)
};

/// Reads FOLDER/summary.json's gap_m (a row: its pairs' gaps) and provenance.scene_file / scene_sha256.
/// @throws InputError naming the file and field when summary.json is missing, malformed or lacks one.
RunSceneReference read_run_scene_reference(const std::filesystem::path& folder);

}  // namespace pounding::io
