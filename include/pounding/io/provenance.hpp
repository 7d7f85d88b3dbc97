#pragma once
// Where an output came from: the program (version, git commit), its inputs (scene and record
// file, each with its SHA-256), the command line and the date. Written into summary.json,
// study.json and gap.json, so a result can be traced to, and reproduced from, what made it.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pounding/analysis/scene.hpp"

namespace pounding::io {

struct Provenance {
  std::string program_version;         // pounding::program_version()
  std::string git_commit;              // pounding::git_commit(); empty: unknown
  std::filesystem::path scene_file;    // absolute; empty for a scene built in code
  std::string scene_sha256;            // 64 hex digits; empty with scene_file
  std::filesystem::path record_file;   // absolute; empty when the scene names none
  std::string record_sha256;           // empty with record_file
  std::filesystem::path record2_file;  // a pair's second component (absolute); empty for one component
  std::string record2_sha256;          // empty with record2_file
  std::string command_line;  // as typed, arguments quoted for a POSIX shell where needed; empty: not a CLI run
  std::string date_utc;      // when the work started, ISO 8601 ("2026-11-21T19:42:44Z")
};

/// The provenance of work on `scene` starting now: hashes its scene file (unless scene.file is
/// empty) and its record file (scene.excitation.file, already resolved; unless empty), stamps
/// the date.
/// @throws std::runtime_error naming a file that cannot be read.
Provenance make_provenance(const analysis::Scene& scene, std::string command_line = {});

/// Now, as ISO 8601 UTC ("2026-11-21T19:42:44Z").
std::string utc_now_iso8601();

/// The arguments as one line a POSIX shell splits back into the same arguments: each argument
/// holding anything but letters, digits and -_./=:,+@% is put in single quotes.
std::string command_line_text(const std::vector<std::string>& arguments);

/// {"program_version", "git_commit", "scene_file", "scene_sha256", "record_file", "record_sha256",
/// ["record2_file", "record2_sha256" for a pair,] "command_line", "date_utc"} in this order;
/// unknown values (empty) are null.
nlohmann::ordered_json provenance_json(const Provenance& provenance);

}  // namespace pounding::io
