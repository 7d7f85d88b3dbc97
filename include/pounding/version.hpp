#pragma once
// What this build of pounding is: for `pounding --version` and the provenance of every output.

#include <string_view>

namespace pounding {

/// The program version, from the CMake project version ("0.1.0").
std::string_view program_version();
/// The git commit the library was built from (40 hex digits, "-dirty" appended when tracked files
/// differed from it); empty when unknown (no git, or not built from a git checkout). Refreshed at
/// every build, not only when CMake configures.
std::string_view git_commit();

}  // namespace pounding
