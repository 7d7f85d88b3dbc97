// `pounding sweep`, `pounding verify` and `pounding bracket`: they run in Python (pounding.sweep,
// on Dask; pounding.verify; pounding.bracket), so the command hands the process over to the interpreter the module was
// built for, with the build's module folder on PYTHONPATH; both are fixed when the program is configured.

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

namespace {

/// Replaces this process by the module's interpreter running `python -m module arguments...`, with
/// the build's module folder on PYTHONPATH. Returns only by throwing.
[[noreturn]] void exec_module(const std::string& module, const std::string& command,
                              std::vector<std::string> arguments) {
#if defined(POUNDING_PYTHON_EXECUTABLE) && defined(POUNDING_PYTHON_DIR)
  const std::filesystem::path python = POUNDING_PYTHON_EXECUTABLE;
  const std::filesystem::path module_dir = POUNDING_PYTHON_DIR;
  // The module is a file (pounding/verify.py) or a package that -m runs (pounding/sweep/__main__.py).
  const std::string name = module.substr(module.find('.') + 1);
  std::error_code error;
  if (!std::filesystem::is_regular_file(python, error)) {
    throw InputError("", python.string(), command + " needs this Python interpreter, the module's (not found)");
  }
  if (!std::filesystem::is_regular_file(module_dir / "pounding" / (name + ".py"), error) &&
      !std::filesystem::is_regular_file(module_dir / "pounding" / name / "__main__.py", error)) {
    throw InputError("", (module_dir / "pounding").string(),
                     command + " needs the Python module built there (cmake --build build --target _pounding)");
  }
  arguments.insert(arguments.begin(), {python.string(), "-m", module});
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
  (void)module;
  (void)arguments;
  throw InputError("", "",
                   command +
                       " needs the Python module, which this build left out (POUNDING_BUILD_PYTHON "
                       "is off: install pybind11-dev and configure again)");
#endif
}

}  // namespace

int run_sweep(const SweepCommand& command) {
  std::vector<std::string> arguments{command.sweep_file};
  if (command.workers) arguments.insert(arguments.end(), {"--workers", std::to_string(*command.workers)});
  if (command.serial) arguments.emplace_back("--serial");
  if (!command.scheduler.empty()) arguments.insert(arguments.end(), {"--scheduler", command.scheduler});
  if (!command.out_dir.empty()) arguments.insert(arguments.end(), {"--out", command.out_dir});
  if (command.no_progress) arguments.emplace_back("--no-progress");
  exec_module("pounding.sweep", "pounding sweep", arguments);
}

int run_verify(const VerifyCommand& command) {
  std::vector<std::string> arguments{command.manifest};
  if (command.bless) arguments.emplace_back("--bless");
  if (command.jobs) arguments.insert(arguments.end(), {"--jobs", std::to_string(*command.jobs)});
  if (!command.out_dir.empty()) arguments.insert(arguments.end(), {"--out", command.out_dir});
  if (command.no_progress) arguments.emplace_back("--no-progress");
  exec_module("pounding.verify", "pounding verify", arguments);
}

int run_bracket(const BracketCommand& command) {
  std::vector<std::string> arguments{command.scene};
  const auto add = [&arguments](const char* option, const std::string& value) {
    if (!value.empty()) arguments.insert(arguments.end(), {option, value});
  };
  add("--laws", command.laws);
  add("--restitutions", command.restitutions);
  add("--stiffness-factors", command.stiffness_factors);
  add("--method", command.method.value_or(""));
  add("--out", command.out_dir);
  if (command.no_progress) arguments.emplace_back("--no-progress");
  exec_module("pounding.bracket", "pounding bracket", arguments);
}

}  // namespace pounding::cli
