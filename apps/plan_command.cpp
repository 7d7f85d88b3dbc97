// `pounding plan`: the scene's plan and elevation, written and drawn before anything is run;
// `pounding animate` and `pounding report`: a run's folder, with the plan of its scene, drawn by
// the tools' scripts.

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <optional>
#include <vector>

#include "commands.hpp"
#include "plot_script.hpp"
#include "pounding/analysis/plan.hpp"
#include "pounding/io/output_files.hpp"
#include "pounding/input_error.hpp"
#include "pounding/io/plan_writer.hpp"
#include "pounding/io/run_folder.hpp"
#include "pounding/io/scene_reader.hpp"
#include "pounding/io/sha256.hpp"

namespace pounding::cli {

namespace {

void print_building(const analysis::BuildingPlan& b, int number) {
  const model::Point2& cm = b.centre_of_mass;
  fmt::print("Building {} '{}': {} slab vertices, {} columns, CM ({:.3f}, {:.3f}) m\n", number, b.name, b.slab.size(),
             b.columns.size(), cm.x(), cm.y());
  if (b.centres_of_stiffness.empty()) return;
  const model::Point2& cs = b.centres_of_stiffness.front();
  fmt::print("  centre of stiffness of storey 1 ({:.3f}, {:.3f}) m: eccentricity e_x = {:.3f} m, e_y = {:.3f} m\n",
             cs.x(), cs.y(), cs.x() - cm.x(), cs.y() - cm.y());
  double spread_m = 0.0;  // storeys whose centre of stiffness moves up the building
  for (const model::Point2& c : b.centres_of_stiffness) spread_m = std::max(spread_m, (c - cs).norm());
  if (spread_m > 1e-9)
    fmt::print("  the centres of stiffness of the other storeys lie within {:.3f} m of it\n", spread_m);
}

/// tools/`script` run with `arguments`: its exit status, or 1 when there is no Python to run it.
int run_tool(const std::string& script, const std::vector<std::string>& arguments) {
  const std::optional<int> status = run_script(script, arguments);
  if (status) return *status;
  fmt::print(stderr, "error: this build has no Python with tools/{} (a build with the Python module has)\n", script);
  return 1;
}

/// The scene a run folder ran, at the run's gap: `scene_file` if given, else the file its
/// summary.json names, refused when it has gone or changed since the run (its plan would not be
/// the run's).
analysis::Scene scene_of_run(const std::string& run_dir, const std::string& scene_file) {
  const io::RunSceneReference run = io::read_run_scene_reference(run_dir);
  const std::string summary = (std::filesystem::path(run_dir) / "summary.json").string();
  if (!scene_file.empty()) {
    if (!run.scene_sha256.empty() && std::filesystem::is_regular_file(scene_file) &&
        io::sha256_file_hex(scene_file) != run.scene_sha256) {
      fmt::print(stderr,
                 "warning: --scene {} is not the file the run read (its sha256 differs from {}'s): the plan "
                 "drawn is this file's\n",
                 scene_file, summary);
    }
    return io::read_scene(scene_file, {.gap_m = run.gap_m, .gaps = run.gaps});
  }
  if (run.scene_file.empty()) {
    throw InputError("provenance.scene_file", "null", "the run's scene was built in code: give its file with --scene",
                     summary);
  }
  if (!std::filesystem::is_regular_file(run.scene_file)) {
    throw InputError("provenance.scene_file", run.scene_file.string(), "no longer exists: give the scene with --scene",
                     summary);
  }
  if (io::sha256_file_hex(run.scene_file) != run.scene_sha256) {
    throw InputError("provenance.scene_sha256", run.scene_sha256,
                     "the scene file has changed since the run: give the scene the run used with --scene", summary);
  }
  return io::read_scene(run.scene_file, {.gap_m = run.gap_m, .gaps = run.gaps});
}

/// Writes the plan of the run's scene into its folder (the scripts draw from plan.json) and runs
/// tools/`script` on the folder; the script's exit status, or 1 when there is no Python to run it.
int draw_run(const std::string& run_dir, const std::string& scene_file, const std::string& command_line,
             const std::string& script, std::vector<std::string> arguments) {
  const analysis::Scene scene = scene_of_run(run_dir, scene_file);
  io::write_plan(analysis::scene_plan(scene), io::make_provenance(scene, command_line), run_dir);
  arguments.insert(arguments.begin(), run_dir);
  return run_tool(script, arguments);
}

}  // namespace

int run_animate(const AnimateCommand& command, const std::string& command_line) {
  std::vector<std::string> arguments = {
      "--fps", fmt::format("{}", command.fps), "--speed", fmt::format("{}", command.speed), "--format", command.format};
  const auto add = [&arguments](const char* option, const auto& value) {
    if (value) arguments.insert(arguments.end(), {option, fmt::format("{}", *value)});
  };
  add("--level", command.level);
  add("--scale", command.scale);
  add("--start", command.start_s);
  add("--end", command.end_s);
  if (!command.out_file.empty()) arguments.insert(arguments.end(), {"--out", command.out_file});
  return draw_run(command.run_dir, command.scene, command_line, "animate_run.py", arguments);
}

int run_report(const ReportCommand& command, const std::string& command_line) {
  std::vector<std::string> arguments;
  if (!command.out_file.empty()) arguments = {"--out", command.out_file};
  if (!command.bracket.empty()) arguments.insert(arguments.end(), {"--bracket", command.bracket});
  return draw_run(command.run_dir, command.scene, command_line, "report_run.py", arguments);
}

int run_compare(const CompareCommand& command) {
  std::vector<std::string> arguments = {command.run_a, command.run_b};
  if (command.window_s) arguments.insert(arguments.end(), {"--window", fmt::format("{}", *command.window_s)});
  if (!command.json_file.empty()) arguments.insert(arguments.end(), {"--json", command.json_file});
  return run_tool("compare_runs.py", arguments);
}

int run_plan(const PlanCommand& command, const std::string& command_line) {
  const analysis::Scene scene = io::read_scene(command.scene, {.gaps = command.gaps});
  const std::string folder = command.out_dir.empty() ? "out/" + io::folder_name(scene.name + "-plan") : command.out_dir;
  io::require_writable_folder(folder, "--out");
  const analysis::ScenePlan plan = analysis::scene_plan(scene);
  fmt::print("Plan of '{}': {}, {} levels where floors meet, {} contact candidates\n", plan.scene,
             plan.pairs.empty() ? fmt::format("gap {} m", plan.gap_m)
                                : fmt::format("a row of {} buildings, {} neighbouring pairs", plan.buildings.size(),
                                              plan.pairs.size()),
             plan.levels.size(), plan.candidates.size());
  for (std::size_t b = 0; b < plan.buildings.size(); ++b) print_building(plan.buildings[b], static_cast<int>(b) + 1);
  io::write_plan(plan, io::make_provenance(scene, command_line), folder);
  fmt::print("Wrote {}/plan.json\n", folder);
  if (!command.no_plot) draw_with_script("plot_plan.py", folder, "plan.png");
  return 0;
}

}  // namespace pounding::cli
