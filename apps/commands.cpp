#include "commands.hpp"

#include <fmt/format.h>

#include "pounding/analysis/modal_summary.hpp"
#include "pounding/excitation/ground_motion.hpp"
#include "pounding/io/json_report.hpp"
#include "pounding/io/scene_reader.hpp"

namespace pounding::cli {
namespace {

void print_modes_table(const analysis::BuildingSummary& building, int count) {
  fmt::print("{} ({} storeys, {} DOF, frame factor {:.8f}{})\n", building.name, building.storeys,
             building.dof, building.frame_factor, building.frame_factor_solved ? ", solved" : "");
  fmt::print("  {:>4}  {:>10}  {:>10}  {:>8}  {:>8}  {:>8}  {:>8}\n", "mode", "T [s]", "f [Hz]",
             "dominant", "Meff,x", "Meff,y", "Meff,rz");
  const int shown = std::min<int>(count, static_cast<int>(building.modes.size()));
  for (int k = 0; k < shown; ++k) {
    const model::Mode& mode = building.modes[k];
    fmt::print("  {:>4}  {:>10.5f}  {:>10.5f}  {:>8}  {:>7.1f}%  {:>7.1f}%  {:>7.1f}%\n", k + 1,
               mode.period_s, 1.0 / mode.period_s, model::to_string(mode.dominant),
               100 * mode.effective_mass_ratio_x, 100 * mode.effective_mass_ratio_y,
               100 * mode.effective_mass_ratio_rz);
  }
}

std::string_view format_name(excitation::RecordFormat format) {
  switch (format) {
    case excitation::RecordFormat::peer_at2: return "peer-at2";
    case excitation::RecordFormat::columns: return "columns";
    case excitation::RecordFormat::single: return "single";
  }
  return "?";
}

void print_excitation(const analysis::Scene& scene, const excitation::GroundMotion& motion) {
  const auto& spec = scene.excitation;
  const auto& t = motion.time_s();
  fmt::print("Excitation: {} ({})\n", spec.file.string(), format_name(spec.read.format));
  fmt::print("  {} samples from {:.4f} s to {:.4f} s (first step {:.4f} s)\n", t.size(), t.front(),
             t.back(), t[1] - t[0]);
  fmt::print("  peak |a_g| = {:.4f} m/s² = {:.4f} g at t = {:.4f} s, direction β = {} deg\n",
             motion.peak_mps2(), motion.peak_mps2() / spec.g_mps2, motion.peak_time_s(),
             spec.direction_deg);
}

}  // namespace

int run_modes(const ModesCommand& command) {
  const analysis::Scene scene = io::read_scene(command.scene);
  const auto buildings = analysis::summarise_buildings(scene);
  for (const auto& building : buildings) print_modes_table(building, command.count);
  if (!command.json_file.empty()) {
    io::write_json(io::modes_json(buildings), command.json_file);
    fmt::print("Wrote {}\n", command.json_file);
  }
  return 0;
}

int run_check(const CheckCommand& command) {
  const analysis::Scene scene =
      io::read_scene(command.scene, {.gap_m = command.gap_m, .restitution = command.restitution});
  const auto buildings = analysis::summarise_buildings(scene);
  const excitation::GroundMotion motion = excitation::load_ground_motion(scene.excitation);

  fmt::print("Scene '{}' ({}) is valid.\n", scene.name, scene.file.string());
  int total_dof = 0;
  for (std::size_t i = 0; i < buildings.size(); ++i) {
    const auto& b = buildings[i];
    const auto& definition = scene.buildings[i];
    total_dof += b.dof;
    fmt::print("Building {} '{}': {} storeys of {} m, {} DOF, total mass {:.1f} t, frame factor "
               "{:.8f}{}\n",
               i + 1, b.name, b.storeys, definition.storey_height_m, b.dof, b.total_mass_t,
               b.frame_factor, b.frame_factor_solved ? " (solved for the target period)" : "");
    fmt::print("  floor mass {:.1f} t (top {:.1f} t), polar moment {:.1f} t·m² (top {:.1f} t·m²)\n",
               definition.mass_t.front(), definition.mass_t.back(),
               definition.polar_moment_tm2.front(), definition.polar_moment_tm2.back());
    fmt::print("  T1 = {:.4f} s, T2 = {:.4f} s, T3 = {:.4f} s; Rayleigh a0 = {:.5f} 1/s, "
               "a1 = {:.6f} s\n",
               b.modes[0].period_s, b.modes[1].period_s, b.modes[2].period_s, b.rayleigh.a0_per_s,
               b.rayleigh.a1_s);
  }
  fmt::print("Coupled system: {} DOF ({} first-order states); floors 1..{} can touch\n", total_dof,
             2 * total_dof, scene.common_floors());
  print_excitation(scene, motion);
  fmt::print("Contact: gap {} m, restitution k = {}\n", scene.contact.gap_m, scene.contact.restitution);
  fmt::print("Solver: {}, rtol {}, atol {}\n", scene.solver.method, scene.solver.rtol, scene.solver.atol);
  return 0;
}

}  // namespace pounding::cli
