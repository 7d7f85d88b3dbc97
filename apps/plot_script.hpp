#pragma once
// Figures, animations and reports drawn by the source tree's tools/*.py under the Python the
// build knows.

#include <optional>
#include <string>
#include <vector>

namespace pounding::cli {

/// Runs tools/`script` with `arguments` and returns its exit status; nullopt when this build has
/// no Python or the tools are absent (an installed program without the source tree). Never throws.
std::optional<int> run_script(const std::string& script, const std::vector<std::string>& arguments);

/// Runs tools/`script` FOLDER (it writes `image` there); says why not when run_script() cannot,
/// and warns when the script fails. A figure is an extra, the files are the result.
void draw_with_script(const std::string& script, const std::string& folder, const std::string& image);

}  // namespace pounding::cli
