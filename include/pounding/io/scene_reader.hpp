#pragma once
// Reads a scene file (TOML) into an analysis::Scene. The format is documented key by key in
// docs/scene-format.md.

#include <filesystem>
#include <map>
#include <cstdint>
#include <optional>
#include <string_view>

#include "pounding/analysis/scene.hpp"
#include "pounding/excitation/record_choice.hpp"

namespace pounding::io {

/// Values given on the command line that replace the file's.
struct SceneOverrides {
  std::optional<double> gap_m{};  // moves building 2 along x
  /// `--gap` as typed, each a gap in m (two buildings: as gap_m) or "NAME:NAME=m", a neighbouring
  /// pair's gap (Scene::set_pair_gap), applied in order after gap_m.
  std::vector<std::string> gaps{};
  /// [contact] keys' options as given, by option (`--restitution`, `--contact-law`,
  /// `--contact-stiffness`: the option column of analysis::contact_setting_specs()), applied in the
  /// table's order after the gaps.
  std::map<std::string, analysis::KeyValue, std::less<>> contact{};
  /// Another record or scaling (`--record`, `--pga-g`, ...; excitation::with_record says what
  /// it keeps of the scene's). When set, the record is read once here, so that a record that
  /// cannot be read or scales beyond 10 g is refused before any run, naming the option.
  excitation::RecordChoice record{};
};

/// The largest scene file read (1 MiB): a scene is a page of text; more is the wrong file.
inline constexpr std::uintmax_t kMaxSceneBytes = 1 << 20;

/// Reads, applies overrides and validates a scene. Relative record paths in the file resolve
/// against the scene file's folder (an override's record path is used as given), and the record
/// file must exist (it is read later, by excitation::load_ground_motion).
/// An override's error names its option (`--gap`, `--pga-g`, ...) and value instead of the key.
/// @throws InputError naming the file (with line where known), the key and the value for a
///   syntax error, an unknown, missing or mistyped key, or any rule of Scene::validate().
///   A file over kMaxSceneBytes or not valid UTF-8 is refused before it is parsed.
analysis::Scene read_scene(const std::filesystem::path& file, const SceneOverrides& overrides = {});

/// read_scene() on text already in memory; `file` names it in errors and anchors relative
/// record paths (the fuzz target's entry point).
analysis::Scene parse_scene(std::string_view text, const std::filesystem::path& file,
                            const SceneOverrides& overrides = {});

}  // namespace pounding::io
