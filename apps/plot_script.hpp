#pragma once
// Figures drawn by the source tree's tools/*.py under the Python the build knows.

#include <string>

namespace pounding::cli {

/// Runs tools/`script` FOLDER (it writes `image` there); says why not when this build has no
/// Python or the tools are absent (an installed program without the source tree), and warns when
/// the script fails. Never throws: a figure is an extra, the files are the result.
void draw_with_script(const std::string& script, const std::string& folder, const std::string& image);

}  // namespace pounding::cli
