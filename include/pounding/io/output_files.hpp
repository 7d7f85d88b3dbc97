#pragma once
// How outputs reach the disk: checked before a run starts, written whole or not at all.

#include <filesystem>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <string_view>

namespace pounding::io {

/// An output file created afresh, never through a link: whatever entry already stands at `path`
/// (a file, or a symbolic link planted in a shared folder) is removed first — unlink removes a
/// link itself, never its target — and the file is created with O_CREAT | O_EXCL | O_NOFOLLOW,
/// which refuses to open anything that reappeared under the name. Mode 0666 less the umask.
class ExclusiveOutput {
 public:
  /// @throws std::runtime_error naming `path` if it cannot be created.
  explicit ExclusiveOutput(std::filesystem::path path);
  ~ExclusiveOutput();
  ExclusiveOutput(const ExclusiveOutput&) = delete;
  ExclusiveOutput& operator=(const ExclusiveOutput&) = delete;

  std::ostream& stream();
  const std::filesystem::path& path() const { return path_; }
  /// Flushes and closes. @throws std::runtime_error naming `shown_as` if a write failed (disk full).
  void close(const std::filesystem::path& shown_as);

 private:
  struct Buffer;
  std::filesystem::path path_;
  std::unique_ptr<Buffer> buffer_;
};

/// Writes `file` into `file.partial` (an ExclusiveOutput) and renames it over `file` once complete,
/// so a reader or a killed run never sees a truncated file (a leftover `.partial` marks a write
/// that was cut off), and a crash of the machine leaves the old file or the whole new one
/// (commit_partial). A symbolic link standing at `file` is replaced by the file, never followed.
/// @throws std::runtime_error naming the file if it cannot be written.
void write_atomically(const std::filesystem::path& file, const std::function<void(std::ostream&)>& write);

/// Makes a finished `partial` file durable (fsync) and renames it over `file` (rename replaces a
/// link at `file` and never writes through it), then syncs the folder. @throws std::runtime_error naming `file` if the
/// data cannot be synced or renamed.
void commit_partial(const std::filesystem::path& partial, const std::filesystem::path& file);

/// Creates `folder` if missing and proves that files can be created in it (writes and removes
/// a probe file), before any work is done. Returns the outermost folder it created (empty if
/// none), for the caller to remove if the run is refused after all.
/// @throws InputError (key `option`, value the folder, the system's reason) if not.
std::filesystem::path require_writable_folder(const std::filesystem::path& folder, const std::string& option);

/// The same for a file to be written later: its folder must take files and the path must not
/// be a folder. @throws InputError (key `option`, value the file).
void require_writable_file(const std::filesystem::path& file, const std::string& option);

/// A scene name made safe as one folder name: characters other than ASCII letters, digits,
/// '-', '_' and '.' become '_', and so does a leading '.' (so never "." or ".." or a hidden
/// folder); at most 100 characters. A scene name is text, never a path.
std::string folder_name(std::string_view scene_name);

}  // namespace pounding::io
