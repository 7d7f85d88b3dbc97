#include "fixtures.hpp"

#include <fstream>
#include <unistd.h>

namespace pounding::fuzz {

namespace {

/// Removed with everything in it when the process exits.
struct Folder {
  std::filesystem::path path;
  Folder() : path(std::filesystem::temp_directory_path() / ("pounding-fuzz-" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(path);
    std::ofstream(path / "record.txt") << "0 0\n0.01 1\n0.02 -1\n0.03 0.5\n0.04 0\n";
    std::ofstream(path / "record.AT2") << "PEER NGA STRONG MOTION DATABASE RECORD\nfuzz\nUNITS OF G\n"
                                          "NPTS=    5, DT=   .0100 SEC\n0.0 0.01 -0.02 0.005 0.0\n";
  }
  ~Folder() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

}  // namespace

const std::filesystem::path& fixture_folder() {
  static const Folder folder;
  return folder.path;
}

}  // namespace pounding::fuzz
