#pragma once
// SHA-256 (FIPS 180-4), for the provenance of outputs: which scene and record file a result came
// from. Small and self-contained; not meant for secrets (no constant-time guarantees needed here).

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace pounding::io {

/// Incremental SHA-256: update() with the bytes in order, then hex() once.
class Sha256 {
 public:
  Sha256();
  void update(std::string_view bytes);
  /// The digest as 64 lowercase hex digits (as sha256sum prints it). Ends the hashing.
  std::string hex();

 private:
  void compress(const unsigned char* block);

  std::array<std::uint32_t, 8> state_;
  std::array<unsigned char, 64> buffer_{};
  std::size_t buffered_ = 0;
  std::uint64_t length_bytes_ = 0;
};

/// SHA-256 of `bytes`, 64 lowercase hex digits.
std::string sha256_hex(std::string_view bytes);

/// SHA-256 of a file's contents, read in blocks. @throws std::runtime_error naming the file if it
/// cannot be read.
std::string sha256_file_hex(const std::filesystem::path& file);

}  // namespace pounding::io
