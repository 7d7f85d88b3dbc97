// `pounding plan`: the scene's plan and elevation, written and drawn before anything is run.

#include <fmt/format.h>

#include <cmath>

#include "commands.hpp"
#include "plot_script.hpp"
#include "pounding/analysis/plan.hpp"
#include "pounding/io/output_files.hpp"
#include "pounding/io/plan_writer.hpp"
#include "pounding/io/scene_reader.hpp"

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

}  // namespace

int run_plan(const PlanCommand& command, const std::string& command_line) {
  const analysis::Scene scene = io::read_scene(command.scene, {.gap_m = command.gap_m});
  const std::string folder = command.out_dir.empty() ? "out/" + io::folder_name(scene.name + "-plan") : command.out_dir;
  io::require_writable_folder(folder, "--out");
  const analysis::ScenePlan plan = analysis::scene_plan(scene);
  fmt::print("Plan of '{}': gap {} m, {} levels where floors meet, {} contact candidates\n", plan.scene, plan.gap_m,
             plan.levels.size(), plan.candidates.size());
  for (int b = 0; b < 2; ++b) print_building(plan.buildings[b], b + 1);
  io::write_plan(plan, io::make_provenance(scene, command_line), folder);
  fmt::print("Wrote {}/plan.json\n", folder);
  if (!command.no_plot) draw_with_script("plot_plan.py", folder, "plan.png");
  return 0;
}

}  // namespace pounding::cli
