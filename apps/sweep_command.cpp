// `pounding sweep`: the sweep runs in Python (pounding.sweep, on Dask), so the command hands the
// process over to the interpreter the module was built for, with the build's module folder on
// PYTHONPATH; both are fixed when the program is configured.

#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "pounding/input_error.hpp"

namespace pounding::cli {

int run_sweep(const SweepCommand& command) {
#if defined(POUNDING_PYTHON_EXECUTABLE) && defined(POUNDING_PYTHON_DIR)
  const std::filesystem::path python = POUNDING_PYTHON_EXECUTABLE;
  const std::filesystem::path module_dir = POUNDING_PYTHON_DIR;
  std::error_code error;
  if (!std::filesystem::is_regular_file(python, error)) {
    throw InputError("", python.string(), "pounding sweep needs this Python interpreter, the module's (not found)");
  }
  if (!std::filesystem::is_regular_file(module_dir / "pounding" / "sweep.py", error)) {
    throw InputError("", (module_dir / "pounding").string(),
                     "pounding sweep needs the Python module built there (cmake --build build --target _pounding)");
  }
  std::vector<std::string> arguments{python.string(), "-m", "pounding.sweep", command.sweep_file};
  if (command.workers) arguments.insert(arguments.end(), {"--workers", std::to_string(*command.workers)});
  if (command.serial) arguments.emplace_back("--serial");
  if (!command.scheduler.empty()) arguments.insert(arguments.end(), {"--scheduler", command.scheduler});
  if (!command.out_dir.empty()) arguments.insert(arguments.end(), {"--out", command.out_dir});
  if (command.no_progress) arguments.emplace_back("--no-progress");

  const char* old_path = std::getenv("PYTHONPATH");
  const std::string path = module_dir.string() + (old_path && *old_path ? std::string(":") + old_path : "");
  if (setenv("PYTHONPATH", path.c_str(), 1) != 0) throw std::runtime_error("cannot set PYTHONPATH");
  std::vector<char*> argv;
  for (std::string& argument : arguments) argv.push_back(argument.data());
  argv.push_back(nullptr);
  std::fflush(stdout);
  execv(python.c_str(), argv.data());
  throw std::runtime_error(fmt::format("cannot start {}: {}", python.string(), std::strerror(errno)));
#else
  (void)command;
  throw InputError("", "", "pounding sweep needs the Python module, which this build left out (POUNDING_BUILD_PYTHON "
                           "is off: install pybind11-dev and configure again)");
#endif
}

}  // namespace pounding::cli
