#include "pounding/io/provenance.hpp"

#include <fmt/chrono.h>
#include <fmt/format.h>

#include <chrono>
#include <ctime>

#include "pounding/io/sha256.hpp"
#include "pounding/version.hpp"

namespace pounding::io {

std::string utc_now_iso8601() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  return fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", utc);
}

namespace {

nlohmann::ordered_json text_or_null(const std::string& text) {
  return text.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(text);
}

}  // namespace

Provenance make_provenance(const analysis::Scene& scene, std::string command_line) {
  Provenance p;
  p.program_version = std::string(program_version());
  p.git_commit = std::string(git_commit());
  if (!scene.file.empty()) {
    p.scene_file = std::filesystem::absolute(scene.file).lexically_normal();
    p.scene_sha256 = sha256_file_hex(scene.file);
  }
  if (!scene.excitation.file.empty()) {
    p.record_file = std::filesystem::absolute(scene.excitation.file).lexically_normal();
    p.record_sha256 = sha256_file_hex(scene.excitation.file);
  }
  if (scene.excitation.second) {
    p.record2_file = std::filesystem::absolute(scene.excitation.second->file).lexically_normal();
    p.record2_sha256 = sha256_file_hex(scene.excitation.second->file);
  }
  p.command_line = std::move(command_line);
  p.date_utc = utc_now_iso8601();
  return p;
}

std::string command_line_text(const std::vector<std::string>& arguments) {
  std::string line;
  for (const std::string& argument : arguments) {
    const bool plain = !argument.empty() && argument.find_first_not_of(
                                                "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789"
                                                "-_./=:,+@%") == std::string::npos;
    if (!line.empty()) line += ' ';
    if (plain) {
      line += argument;
      continue;
    }
    line += '\'';
    for (const char c : argument) line += c == '\'' ? std::string("'\\''") : std::string(1, c);
    line += '\'';
  }
  return line;
}

nlohmann::ordered_json provenance_json(const Provenance& p) {
  nlohmann::ordered_json document;
  document["program_version"] = p.program_version;
  document["git_commit"] = text_or_null(p.git_commit);
  document["scene_file"] = text_or_null(p.scene_file.string());
  document["scene_sha256"] = text_or_null(p.scene_sha256);
  document["record_file"] = text_or_null(p.record_file.string());
  document["record_sha256"] = text_or_null(p.record_sha256);
  if (!p.record2_file.empty()) {
    document["record2_file"] = p.record2_file.string();
    document["record2_sha256"] = p.record2_sha256;
  }
  document["command_line"] = text_or_null(p.command_line);
  document["date_utc"] = p.date_utc;
  return document;
}

}  // namespace pounding::io
