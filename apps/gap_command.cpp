// `pounding gap`: prints what analysis::needed_gap and analysis::severity_curve find.

#include <fmt/format.h>

#include <cmath>

#include "commands.hpp"
#include "pounding/analysis/needed_gap.hpp"
#include "pounding/contact/candidates.hpp"
#include "pounding/input_error.hpp"
#include "pounding/io/gap_writer.hpp"
#include "pounding/io/output_files.hpp"
#include "pounding/io/provenance.hpp"
#include "pounding/io/scene_reader.hpp"

namespace pounding::cli {
namespace {

std::string metres(double value) { return std::isfinite(value) ? fmt::format("{:.6f} m", value) : "never closes"; }

void print_levels(const analysis::NeededGap& gap) {
  fmt::print("{:>5} {:>9} {:>8} {:>15} {:>9} {:>10} {:>10} {:>10} {:>10} {:>10}\n", "level", "floors", "z [m]",
             "needed gap [m]", "t [s]", "d1 [m]", "d2 [m]", "ABS [m]", "SRSS [m]", "DDC [m]");
  for (const analysis::LevelGap& l : gap.levels) {
    const bool closes = l.candidate >= 0;
    fmt::print("{:>5} {:>9} {:>8.2f} {:>15} {:>9} {:>10.6f} {:>10.6f} {:>10.6f} {:>10.6f} {:>10.6f}\n", l.level.index,
               fmt::format("{}/{}", l.level.floors[0], l.level.floors[1]), l.level.elevation_m,
               closes ? fmt::format("{:.6f}", l.needed_gap_m) : "-", closes ? fmt::format("{:.4f}", l.t_s) : "-",
               l.peak_towards_m[0], l.peak_towards_m[1], l.rules.abs_m, l.rules.srss_m, l.rules.ddc_m);
  }
}

void print_rules(const analysis::NeededGap& gap) {
  fmt::print("First modes along x: B1 mode {} T = {:.4f} s zeta = {:.4f}; B2 mode {} T = {:.4f} s zeta = {:.4f}; "
             "CQC rho = {:.4f}\n",
             gap.modes[0].mode, gap.modes[0].period_s, gap.modes[0].damping_ratio, gap.modes[1].mode,
             gap.modes[1].period_s, gap.modes[1].damping_ratio, gap.rho);
  fmt::print("Code rules (largest over the levels) against the needed gap {}:\n", metres(gap.needed_gap_m));
  for (const analysis::RuleVerdict& v : analysis::rule_verdicts(gap)) {
    fmt::print("  {:<5} {:.6f} m  {} by {:.6f} m ({:+.1f} %)\n", v.rule, v.value_m,
               v.unconservative() ? "UNCONSERVATIVE, short" : "conservative, over", std::abs(v.margin_m),
               100.0 * v.margin_m / gap.needed_gap_m);
  }
}

void print_curve(const std::vector<analysis::SeverityPoint>& curve) {
  fmt::print("{:>10} {:>8} {:>18} {:>20} {:>17} {:>9}\n", "gap [m]", "impacts", "max impulse [kNs]",
             "max approach [m/s]", "energy lost [kJ]", "status");
  for (const analysis::SeverityPoint& p : curve) {
    fmt::print("{:>10.4f} {:>8} {:>18.3f} {:>20.4f} {:>17.3f} {:>9}\n", p.gap_m, p.impacts, p.max_impulse_kNs,
               p.max_approach_mps, p.energy_lost_kJ, p.status);
  }
}

}  // namespace

int run_gap(const GapCommand& command, const std::string& command_line) {
  analysis::Scene scene = io::read_scene(command.scene, {.gap_m = command.gap_m});
  if (command.rtol) scene.solver.rtol = *command.rtol;
  if (command.atol) scene.solver.atol = *command.atol;
  try {
    scene.validate();
  } catch (const InputError& error) {
    throw InputError(error.key() == "solver.rtol" ? "--rtol" : error.key() == "solver.atol" ? "--atol" : error.key(),
                     error.value(), error.reason(), command.scene);
  }
  // A scene name is text, not a path; the folder must take files before the runs, not after them.
  const std::string folder = command.out_dir.empty() ? "out/" + io::folder_name(scene.name + "-gap") : command.out_dir;
  io::require_writable_folder(folder, "--out");
  const io::Provenance provenance = io::make_provenance(scene, command_line);
  const analysis::NeededGap gap = analysis::needed_gap(scene);
  fmt::print("Needed gap of '{}' (contact-free run, CVODE rtol {:g}; {} maxima located, {} steps, {:.3f} s):\n",
             scene.name, scene.solver.rtol, gap.extrema, gap.steps, gap.wall_time_s);
  if (gap.candidate < 0) {
    fmt::print("  no vertex-edge pair ever approaches: any gap prevents contact\n");
  } else {
    const contact::Candidate& pair = gap.candidates[static_cast<std::size_t>(gap.candidate)];
    fmt::print("  {} at level {} (floors {}/{}, z = {:.2f} m), t = {:.6f} s, pair {}\n", metres(gap.needed_gap_m),
               gap.level, pair.floors[0], pair.floors[1], pair.elevation_m, gap.t_s, contact::describe(pair));
  }
  print_levels(gap);
  print_rules(gap);

  std::vector<analysis::SeverityPoint> curve;
  if (command.curve > 0) {
    fmt::print("Severity below the needed gap: {} runs ({})\n", command.curve, scene.solver.method);
    int done = 0;
    curve = analysis::severity_curve(scene, gap.needed_gap_m, command.curve, command.threads,
                                     [&](const analysis::SeverityPoint& p) {
                                       fmt::print(stderr, "\r  {}/{} runs done (gap {:.4f} m)", ++done, command.curve,
                                                  p.gap_m);
                                     });
    fmt::print(stderr, "\n");
    print_curve(curve);
  }
  io::write_gap(scene.name, gap, curve, provenance, folder);
  fmt::print("Wrote {0}/gap.json, gap.csv, gap_history.csv{1}; draw them with tools/plot_gap.py {0}\n", folder,
             curve.empty() ? "" : ", gap_curve.csv");
  return 0;
}

}  // namespace pounding::cli
