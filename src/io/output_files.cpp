#include "pounding/io/output_files.hpp"

#include <ext/stdio_filebuf.h>
#include <fmt/format.h>
#include <fstream>
#include <stdexcept>
#include <system_error>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "pounding/input_error.hpp"

namespace pounding::io {

namespace {

/// fsync of a file or folder by path; false (errno set) if it cannot be opened or synced.
bool sync_path(const std::filesystem::path& path, int flags) {
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0) return false;
  const bool synced = ::fsync(fd) == 0;
  ::close(fd);
  return synced;
}

/// Creates `path` afresh (see ExclusiveOutput); the descriptor, or throws. An entry that
/// reappears between the unlink and the open (a race in a shared folder) makes O_EXCL fail: try
/// again a few times, then give up rather than open it.
int create_exclusively(const std::filesystem::path& path) {
  constexpr int kAttempts = 5;
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    if (::unlink(path.c_str()) != 0 && errno != ENOENT) break;
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd >= 0) return fd;
    if (errno != EEXIST) break;
  }
  throw std::runtime_error(fmt::format("cannot write {}: {}", path.string(), std::strerror(errno)));
}

}  // namespace

struct ExclusiveOutput::Buffer {
  explicit Buffer(int fd) : file(fd, std::ios::out | std::ios::binary), stream(&file) {}
  __gnu_cxx::stdio_filebuf<char> file;  // owns the descriptor: closed with the buffer
  std::ostream stream;
};

ExclusiveOutput::ExclusiveOutput(std::filesystem::path path) : path_(std::move(path)) {
  const int fd = create_exclusively(path_);
  buffer_ = std::make_unique<Buffer>(fd);
  buffer_->stream.precision(17);
}

ExclusiveOutput::~ExclusiveOutput() = default;

std::ostream& ExclusiveOutput::stream() { return buffer_->stream; }

void ExclusiveOutput::close(const std::filesystem::path& shown_as) {
  buffer_->stream.flush();
  const bool written = static_cast<bool>(buffer_->stream) && buffer_->file.close() != nullptr;
  if (!written) throw std::runtime_error(fmt::format("cannot write {} (disk full?)", shown_as.string()));
}

void commit_partial(const std::filesystem::path& partial, const std::filesystem::path& file) {
  // Data first, then the name, then the folder entry: after a crash of the machine (not only of
  // the program) `file` is either the old one or the whole new one, never empty or torn.
  if (!sync_path(partial, O_RDONLY)) {
    throw std::runtime_error(fmt::format("cannot write {}: {}", file.string(), std::strerror(errno)));
  }
  std::error_code error;
  std::filesystem::rename(partial, file, error);
  if (error) throw std::runtime_error(fmt::format("cannot write {}: {}", file.string(), error.message()));
  const std::filesystem::path folder = file.has_parent_path() ? file.parent_path() : std::filesystem::path(".");
  sync_path(folder, O_RDONLY | O_DIRECTORY);  // best effort: some file systems refuse a folder fsync
}

void write_atomically(const std::filesystem::path& file, const std::function<void(std::ostream&)>& write) {
  std::filesystem::path partial = file;
  partial += ".partial";
  ExclusiveOutput out(partial);
  write(out.stream());
  out.close(file);
  commit_partial(partial, file);
}

std::filesystem::path require_writable_folder(const std::filesystem::path& folder, const std::string& option) {
  const std::string value = folder.string();
  std::error_code error;
  std::filesystem::path created;  // the outermost missing ancestor, which create_directories makes
  for (std::filesystem::path p = std::filesystem::absolute(folder, error).lexically_normal();
       !p.empty() && !std::filesystem::exists(p, error) && p != p.parent_path(); p = p.parent_path()) {
    created = p;
  }
  std::filesystem::create_directories(folder, error);
  if (error) throw InputError(option, value, fmt::format("cannot create this folder: {}", error.message()));
  if (!std::filesystem::is_directory(folder)) throw InputError(option, value, "is not a folder");
  const std::filesystem::path probe = folder / fmt::format(".pounding-write-test-{}", ::getpid());
  bool writable = true;
  try {
    ExclusiveOutput(probe).close(probe);  // never truncates a file a link planted here points to
  } catch (const std::runtime_error&) {
    writable = false;
  }
  std::filesystem::remove(probe, error);
  if (!writable) throw InputError(option, value, "cannot write files into this folder");
  return created;
}

void require_writable_file(const std::filesystem::path& file, const std::string& option) {
  if (std::filesystem::is_directory(file)) throw InputError(option, file.string(), "is a folder, not a file");
  try {
    require_writable_folder(file.has_parent_path() ? file.parent_path() : ".", option);
  } catch (const InputError& error) {
    throw InputError(option, file.string(), fmt::format("its folder {}: {}", error.value(), error.reason()));
  }
}

std::string folder_name(std::string_view scene_name) {
  constexpr std::size_t kMaxLength = 100;
  std::string name;
  for (char c : scene_name.substr(0, kMaxLength)) {
    const bool safe =
        (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.';
    name += safe ? c : '_';
  }
  if (name.empty()) name.assign(1, '_');        // assign: GCC 12 warns (-Wrestrict, a false positive) on = "_"
  if (name.front() == '.') name.front() = '_';  // neither "." nor ".." nor a hidden folder
  return name;
}

}  // namespace pounding::io
