#pragma once
// How outputs reach the disk: checked before a run starts, written whole or not at all.

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <string_view>

namespace pounding::io {

/// Writes `file` into `file.partial` and renames it over `file` once complete, so a reader or a
/// killed run never sees a truncated file (a leftover `.partial` marks a write that was cut off),
/// and a crash of the machine leaves the old file or the whole new one (commit_partial).
/// @throws std::runtime_error naming the file if it cannot be written.
void write_atomically(const std::filesystem::path& file, const std::function<void(std::ostream&)>& write);

/// Makes a finished `partial` file durable (fsync) and renames it over `file`, then syncs the
/// folder. @throws std::runtime_error naming `file` if the data cannot be synced or renamed.
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
