#pragma once
// Reads a scene file (TOML) into an analysis::Scene. The format is documented key by key in
// docs/scene-format.md.

#include <filesystem>
#include <optional>

#include "pounding/analysis/scene.hpp"

namespace pounding::io {

/// Values given on the command line that replace the file's.
struct SceneOverrides {
  std::optional<double> gap_m{};      // moves building 2 along x
  std::optional<double> restitution{};
};

/// Reads, applies overrides and validates a scene. Relative record paths resolve against the
/// scene file's folder, and the record file must exist (it is read later, by
/// excitation::load_ground_motion).
/// @throws InputError naming the file (with line where known), the key and the value for a
///   syntax error, an unknown, missing or mistyped key, or any rule of Scene::validate().
analysis::Scene read_scene(const std::filesystem::path& file, const SceneOverrides& overrides = {});

}  // namespace pounding::io
