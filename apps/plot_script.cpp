#include "plot_script.hpp"

#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>

namespace pounding::cli {

void draw_with_script(const std::string& script, const std::string& folder, const std::string& image) {
#if defined(POUNDING_PYTHON_EXECUTABLE) && defined(POUNDING_TOOLS_DIR)
  const std::string python = POUNDING_PYTHON_EXECUTABLE;
  const std::string path = std::string(POUNDING_TOOLS_DIR) + "/" + script;
  if (std::filesystem::is_regular_file(python) && std::filesystem::is_regular_file(path)) {
    std::fflush(stdout);
    const pid_t child = fork();
    if (child == 0) {
      execl(python.c_str(), python.c_str(), path.c_str(), folder.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    int status = 0;
    if (child > 0 && waitpid(child, &status, 0) == child && WIFEXITED(status) && WEXITSTATUS(status) == 0) return;
    fmt::print(stderr, "warning: {} {} {} failed: no {}\n", python, path, folder, image);
    return;
  }
#endif
  fmt::print("No plot: this build has no Python with tools/{} (run it on {} by hand)\n", script, folder);
}

}  // namespace pounding::cli
