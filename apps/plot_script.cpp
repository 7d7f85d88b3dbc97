#include "plot_script.hpp"

#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>

namespace pounding::cli {

std::optional<int> run_script(const std::string& script, const std::vector<std::string>& arguments) {
#if defined(POUNDING_PYTHON_EXECUTABLE) && defined(POUNDING_TOOLS_DIR)
  const std::string python = POUNDING_PYTHON_EXECUTABLE;
  const std::string path = std::string(POUNDING_TOOLS_DIR) + "/" + script;
  if (!std::filesystem::is_regular_file(python) || !std::filesystem::is_regular_file(path)) return std::nullopt;
  std::vector<char*> argv = {const_cast<char*>(python.c_str()), const_cast<char*>(path.c_str())};
  for (const std::string& argument : arguments) argv.push_back(const_cast<char*>(argument.c_str()));
  argv.push_back(nullptr);
  std::fflush(stdout);
  const pid_t child = fork();
  if (child == 0) {
    execv(python.c_str(), argv.data());
    _exit(127);
  }
  int status = 0;
  if (child < 0 || waitpid(child, &status, 0) != child) return 1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
#else
  (void)script;
  (void)arguments;
  return std::nullopt;
#endif
}

void draw_with_script(const std::string& script, const std::string& folder, const std::string& image) {
  const std::optional<int> status = run_script(script, {folder});
  if (!status) {
    fmt::print("No plot: this build has no Python with tools/{} (run it on {} by hand)\n", script, folder);
  } else if (*status != 0) {
    fmt::print(stderr, "warning: tools/{} {} failed: no {}\n", script, folder, image);
  }
}

}  // namespace pounding::cli
