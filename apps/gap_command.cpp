// `pounding gap`: prints what analysis::needed_gap, analysis::severity_curve and
// analysis::record_set_gaps find.

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <thread>
#include <utility>

#include "commands.hpp"
#include "interrupts.hpp"
#include "pounding/analysis/needed_gap.hpp"
#include "pounding/analysis/record_set.hpp"
#include "pounding/analysis/run_scene.hpp"
#include "pounding/contact/candidates.hpp"
#include "pounding/input_error.hpp"
#include "pounding/io/gap_writer.hpp"
#include "pounding/io/json_report.hpp"
#include "pounding/io/output_files.hpp"
#include "pounding/io/provenance.hpp"
#include "pounding/io/record_list.hpp"
#include "pounding/io/scene_reader.hpp"

namespace pounding::cli {
namespace {

std::string metres(double value) { return std::isfinite(value) ? fmt::format("{:.6f} m", value) : "never closes"; }

/// How the tables name the pair's buildings: B1 and B2 for a scene of two, the scene's own names
/// for a pair of a row.
struct PairNames {
  std::array<std::string, 2> buildings{"B1", "B2"};
  std::array<std::string, 2> peaks{"d1", "d2"};  // the columns of their peaks towards each other
};

PairNames row_pair_names(const analysis::Scene& two) {
  return {{two.buildings[0].name, two.buildings[1].name}, {"d " + two.buildings[0].name, "d " + two.buildings[1].name}};
}

void print_levels(const analysis::NeededGap& gap, const PairNames& names = {}) {
  fmt::print("{:>5} {:>9} {:>8} {:>15} {:>9} {:>10} {:>10} {:>10} {:>10} {:>10}\n", "level", "floors", "z [m]",
             "needed gap [m]", "t [s]", names.peaks[0] + " [m]", names.peaks[1] + " [m]", "ABS [m]", "SRSS [m]",
             "DDC [m]");
  bool columns = false;
  for (const analysis::LevelGap& l : gap.levels) {
    const bool closes = l.candidate >= 0;
    columns = columns || l.column;
    fmt::print("{:>5} {:>9} {:>8.2f} {:>15} {:>9} {:>10.6f} {:>10.6f} {:>10.6f} {:>10.6f} {:>10.6f}\n",
               l.column ? fmt::format("c{}", l.slab_building + 1) : fmt::format("{}", l.level.index),
               fmt::format("{}/{}", l.level.floors[0], l.level.floors[1]), l.level.elevation_m,
               closes ? fmt::format("{:.6f}", l.needed_gap_m) : "-", closes ? fmt::format("{:.4f}", l.t_s) : "-",
               l.peak_towards_m[0], l.peak_towards_m[1], l.rules.abs_m, l.rules.srss_m, l.rules.ddc_m);
  }
  if (columns) {
    fmt::print(
        "  c1, c2: a slab of {}, {} facing the other building's columns (floors: the slab's floor and the "
        "struck storey; d: the slab's facing vertices and the column points at its height)\n",
        names.buildings[0], names.buildings[1]);
  }
}

void print_rules(const analysis::NeededGap& gap, const PairNames& names = {}) {
  fmt::print(
      "First modes along x: {} mode {} T = {:.4f} s zeta = {:.4f}; {} mode {} T = {:.4f} s zeta = {:.4f}; "
      "CQC rho = {:.4f}\n",
      names.buildings[0], gap.modes[0].mode, gap.modes[0].period_s, gap.modes[0].damping_ratio, names.buildings[1],
      gap.modes[1].mode, gap.modes[1].period_s, gap.modes[1].damping_ratio, gap.rho);
  if (gap.yielding) {
    fmt::print(
        "Columns yield: the contact-free run is nonlinear ({} branch changes), and the code rules below "
        "combine its inelastic peaks d1, d2\n",
        gap.yield_events);
  }
  fmt::print("Code rules (largest over the levels) against the needed gap {}:\n", metres(gap.needed_gap_m));
  for (const analysis::RuleVerdict& v : analysis::rule_verdicts(gap)) {
    fmt::print("  {:<5} {:.6f} m  {} by {:.6f} m ({:+.1f} %)\n", v.rule, v.value_m,
               v.unconservative() ? "UNCONSERVATIVE, short" : "conservative, over", std::abs(v.margin_m),
               100.0 * v.margin_m / gap.needed_gap_m);
  }
}

void print_amplified(const analysis::NeededGap& gap) {
  if (!gap.amplified_elastic) return;
  const analysis::AmplifiedElastic& a = *gap.amplified_elastic;
  fmt::print("Elastic analysis (every column elastic, needed gap {}), peaks times {:g}, against the needed gap {}{}:\n",
             metres(a.elastic_needed_gap_m), a.factor, metres(gap.needed_gap_m),
             a.status == solvers::RunStatus::completed
                 ? ""
                 : fmt::format(" (the elastic run stopped: {}; its peaks cover part of the record)",
                               solvers::to_string(a.status)));
  for (const analysis::RuleVerdict& v : analysis::rule_verdicts(a.rules, gap.needed_gap_m)) {
    fmt::print("  {:<5} {:.6f} m  {} by {:.6f} m ({:+.1f} %)\n", v.rule, v.value_m,
               v.unconservative() ? "UNCONSERVATIVE, short" : "conservative, over", std::abs(v.margin_m),
               100.0 * v.margin_m / gap.needed_gap_m);
  }
}

void print_all_angles(const analysis::NeededGap& gap) {
  if (!gap.all_angles) return;
  const analysis::AllAngles& all = *gap.all_angles;
  fmt::print("Every angle of incidence ({}, {} contact-free runs{}):\n",
             all.method == "superposition"
                 ? fmt::format("two runs superposed, the touch gaps sampled every {:g} s", all.sample_interval_s)
                 : fmt::format("one run every {:g} degrees: yielding buildings do not superpose", all.step_deg),
             all.runs,
             all.status == solvers::RunStatus::completed ? "" : fmt::format("; {}: lower bounds", all.status_detail));
  // Level 0 with a governing pair: a slab facing columns (its pair names the column and the slab).
  const std::string where = all.worst_level > 0 || all.worst_candidate < 0
                                ? fmt::format("level {}", all.worst_level)
                                : contact::describe(gap.candidates[static_cast<std::size_t>(all.worst_candidate)]);
  fmt::print("  largest: {} with the record along {:.2f} deg ({}, t = {:.6f} s), refined by full runs to {:g} deg\n",
             metres(all.worst.needed_gap_m), all.worst.angle_deg, where, all.worst_t_s, all.refine_tolerance_deg);
  fmt::print("  the envelope's largest: {} at {:g} deg; at the record's own {:g} deg: {}\n",
             metres(all.estimate.needed_gap_m), all.estimate.angle_deg, all.record_angle_deg, metres(gap.needed_gap_m));
}

void print_curve(const std::vector<analysis::SeverityPoint>& curve) {
  fmt::print("{:>10} {:>8} {:>18} {:>20} {:>17} {:>9}\n", "gap [m]", "impacts", "max impulse [kNs]",
             "max approach [m/s]", "energy lost [kJ]", "status");
  for (const analysis::SeverityPoint& p : curve) {
    fmt::print("{:>10.4f} {:>8} {:>18.3f} {:>20.4f} {:>17.3f} {:>9}\n", p.gap_m, p.impacts, p.max_impulse_kNs,
               p.max_approach_mps, p.energy_lost_kJ, p.status);
  }
}

/// "0.364275" for a number that exists, "-" otherwise (a failed record, a statistic of one value).
std::string cell(double value, int decimals = 6) {
  return std::isfinite(value) ? fmt::format("{:.{}f}", value, decimals) : "-";
}

void print_record_rows(const analysis::RecordSetResult& set) {
  fmt::print("{:<46} {:>7} {:>10} {:>15} {:>7} {:>8} {:>10} {:>10} {:>10}\n", "record", "PGA [g]", "length [s]",
             "needed gap [m]", "floors", "t [s]", "ABS [m]", "SRSS [m]", "DDC [m]");
  for (const analysis::RecordGap& r : set.records) {
    if (!r.completed()) {
      fmt::print("{:<46} FAILED: {}\n", r.record, r.message);
      continue;
    }
    const bool closes = r.closes;
    fmt::print("{:<46} {:>7} {:>10} {:>15} {:>7} {:>8} {:>10} {:>10} {:>10}\n", r.record, cell(r.pga_g, 3),
               cell(r.duration_s, 2), closes ? cell(r.needed_gap_m) : "never",
               closes ? fmt::format("{}/{}", r.floors[0], r.floors[1]) : "-", closes ? cell(r.t_s, 3) : "-",
               cell(r.rules.abs_m), cell(r.rules.srss_m), cell(r.rules.ddc_m));
  }
}

void print_set_statistics(const analysis::RecordSetResult& set) {
  const std::array<const analysis::SetStatistic*, 4> columns{&set.needed_gap_m, &set.abs_m, &set.srss_m, &set.ddc_m};
  fmt::print("Over the {} completed records{}:\n", set.records.size() - static_cast<std::size_t>(set.failed),
             set.failed ? fmt::format(" ({} failed)", set.failed) : "");
  fmt::print("{:<22} {:>15} {:>10} {:>10} {:>10}\n", "", "needed gap [m]", "ABS [m]", "SRSS [m]", "DDC [m]");
  auto row = [&](const char* name, double analysis::SetStatistic::*field) {
    fmt::print("{:<22} {:>15} {:>10} {:>10} {:>10}\n", name, cell(columns[0]->*field), cell(columns[1]->*field),
               cell(columns[2]->*field), cell(columns[3]->*field));
  };
  row("mean", &analysis::SetStatistic::mean);
  row("median", &analysis::SetStatistic::median);
  row("84th pct (lognormal)", &analysis::SetStatistic::p84_lognormal);
  fmt::print(
      "  84th percentile = exp(m + s), m and s the mean and the sample standard deviation (divisor n - 1) "
      "of ln x over the records\n");
  if (set.worst >= 0) {
    const analysis::RecordGap& worst = set.records[static_cast<std::size_t>(set.worst)];
    fmt::print("Worst record: {}, needed gap {} at floors {}/{}, t = {:.3f} s\n", worst.record,
               metres(worst.needed_gap_m), worst.floors[0], worst.floors[1], worst.t_s);
  }
  // Per rule, under how many records it asks for less than the needed gap.
  const std::array<std::pair<const char*, double analysis::GapRules::*>, 3> rules{
      {{"ABS", &analysis::GapRules::abs_m},
       {"SRSS", &analysis::GapRules::srss_m},
       {"DDC", &analysis::GapRules::ddc_m}}};
  for (const auto& [name, field] : rules) {
    int short_of = 0, compared = 0;
    for (const analysis::RecordGap& r : set.records) {
      if (!r.completed() || !std::isfinite(r.needed_gap_m)) continue;
      ++compared;
      if (r.rules.*field < r.needed_gap_m) ++short_of;
    }
    fmt::print("  {:<5} unconservative under {} of {} records\n", name, short_of, compared);
  }
}

/// Each contact-free run's budget (--max-wall-time). @throws InputError naming the option.
solvers::RunBudget run_budget(const GapCommand& command) {
  solvers::RunBudget budget;
  if (command.max_wall_time_s) budget.max_wall_time_s = *command.max_wall_time_s;
  try {
    budget.validate();
  } catch (const InputError& error) {
    throw InputError("--max-wall-time", error.value(), error.reason());
  }
  return budget;
}

/// The needed gap of `scene` under every record of `records`, `threads` at a time, with a
/// progress line; then its rows and statistics printed.
analysis::RecordSetResult run_set(const GapCommand& command, const analysis::Scene& scene,
                                  const std::vector<analysis::RecordEntry>& records, unsigned threads) {
  const auto start = std::chrono::steady_clock::now();
  int done = 0, failed = 0;
  const analysis::RecordSetResult set = analysis::record_set_gaps(
      scene, records, threads,
      [&](const analysis::RecordGap& r) {
        failed += r.completed() ? 0 : 1;
        const double elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        fmt::print(stderr, "\r  {}/{} records done, {} failed, {:.1f} s", ++done, records.size(), failed, elapsed_s);
      },
      run_budget(command));
  fmt::print(stderr, "\n");
  print_record_rows(set);
  print_set_statistics(set);
  return set;
}

/// What `gap --records` shares for a scene of two and a row: the list read against the scene's
/// excitation, the folder, the provenance (the scene's own record is not run: the rows name theirs)
/// and the thread count.
struct RecordSetJob {
  std::vector<analysis::RecordEntry> records;
  std::string folder;
  io::Provenance provenance;
  unsigned threads = 1;
};

RecordSetJob record_set_job(const GapCommand& command, const analysis::Scene& scene, const std::string& command_line) {
  RecordSetJob job{io::read_record_list(command.records, scene.excitation),
                   command.out_dir.empty() ? "out/" + io::folder_name(scene.name + "-records") : command.out_dir,
                   {},
                   command.threads ? command.threads : std::max(1u, std::thread::hardware_concurrency())};
  io::require_writable_folder(job.folder, "--out");
  analysis::Scene without_record = scene;
  without_record.excitation.file.clear();
  without_record.excitation.second.reset();
  job.provenance = io::make_provenance(without_record, command_line);
  fmt::print("Needed gap of '{}' under {} records ({}; contact-free runs, CVODE rtol {:g}, {} at a time):\n",
             scene.name, job.records.size(), command.records, analysis::resolve(scene.solver).rtol,
             std::min<std::size_t>(job.threads, job.records.size()));
  return job;
}

/// `gap --records`: the needed gap under every record of the set, then the set's statistics.
/// Returns 3 when a record failed (its row says why; the others are still written).
int run_record_set(const GapCommand& command, const analysis::Scene& scene, const std::string& command_line) {
  const RecordSetJob job = record_set_job(command, scene, command_line);
  const InterruptRequests interrupts;
  const analysis::RecordSetResult set = run_set(command, scene, job.records, job.threads);
  io::write_record_set(scene.name, set, job.provenance, job.folder);
  fmt::print("Wrote {0}/records.csv and records.json ({1:.1f} s for the set)\n", job.folder, set.wall_time_s);
  return set.failed == 0 ? 0 : 3;
}

/// A statistic of a record set in rows.json: null where it does not exist.
nlohmann::ordered_json statistic_json(const analysis::SetStatistic& s) {
  auto value = [](double x) { return std::isfinite(x) ? nlohmann::ordered_json(x) : nlohmann::ordered_json(nullptr); };
  return {{"count", s.count},
          {"mean", value(s.mean)},
          {"median", value(s.median)},
          {"p84_lognormal", value(s.p84_lognormal)}};
}

/// A row's neighbouring pair, as the gap runs take it: its own scene of two, facing along x.
struct RowPair {
  analysis::BuildingPair pair;
  double turned_deg = 0.0;  // how far its plan was turned to face along x
  analysis::Scene scene;
  std::string name;    // "B1:B2", in the scene's names
  std::string folder;  // its files: FOLDER/<first>-<second>/
};

/// Every pair of the row turned first, so that a pair the analysis cannot take stops the command
/// before any file is written; a spectral scaling at a building's period is the row's (its slots
/// are the row's).
std::vector<RowPair> row_pairs(const analysis::Scene& scene, const std::string& folder) {
  const std::optional<excitation::SaScaling> row_scaling = analysis::resolved_excitation(scene).scale_to_sa;
  std::vector<RowPair> pairs;
  for (const analysis::BuildingPair& pair : scene.pairs()) {
    RowPair& p = pairs.emplace_back(RowPair{pair});
    p.scene = scene.pair_scene_facing_x(pair, p.turned_deg);
    if (row_scaling && row_scaling->building != 0) {
      p.scene.excitation.scale_to_sa = row_scaling;
      p.scene.excitation.scale_to_sa->building = 0;  // at the period resolved for the row
    }
    p.name = fmt::format("{}:{}", p.scene.buildings[0].name, p.scene.buildings[1].name);
    p.folder = fmt::format("{}/{}-{}", folder, io::folder_name(p.scene.buildings[0].name),
                           io::folder_name(p.scene.buildings[1].name));
  }
  return pairs;
}

std::string turn_note(double turned_deg) {
  return turned_deg == 0.0 ? std::string()
                           : fmt::format("; the plan turned by {:g} deg so that they face along x", turned_deg);
}

/// `gap --records` on a row: each pair's needed gap under every record (its own contact-free
/// runs, as for the scene's record), its rows and statistics, each pair's records.csv and
/// records.json in FOLDER/<first>-<second>/, and rows.json with each pair's statistics. Returns 3
/// when a record failed for some pair.
int run_row_record_set(const GapCommand& command, const analysis::Scene& scene, const std::string& command_line) {
  const RecordSetJob job = record_set_job(command, scene, command_line);
  const std::vector<RowPair> pairs = row_pairs(scene, job.folder);
  const InterruptRequests interrupts;
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  int failed = 0;
  for (const RowPair& p : pairs) {
    fmt::print("Pair {} (gap {:.6g} m{}):\n", p.name, p.pair.gap_m, turn_note(p.turned_deg));
    const analysis::RecordSetResult set =
        run_set(command, p.scene, analysis::pair_records(scene, job.records, p.turned_deg), job.threads);
    io::write_record_set(p.scene.name, set, job.provenance, p.folder);
    failed += set.failed;
    list.push_back({{"pair", p.name},
                    {"buildings", {p.pair.first + 1, p.pair.second + 1}},
                    {"gap_m", p.pair.gap_m},
                    {"plan_turned_deg", p.turned_deg},
                    {"records", set.records.size()},
                    {"failed", set.failed},
                    {"needed_gap_m", statistic_json(set.needed_gap_m)},
                    {"abs_m", statistic_json(set.abs_m)},
                    {"srss_m", statistic_json(set.srss_m)},
                    {"ddc_m", statistic_json(set.ddc_m)},
                    {"worst_record", set.worst < 0 ? nlohmann::ordered_json(nullptr)
                                                   : nlohmann::ordered_json(set.records[set.worst].record)},
                    {"folder", p.folder}});
  }
  io::write_json(nlohmann::ordered_json{{"scene", scene.name},
                                        {"records", command.records},
                                        {"pairs", list},
                                        {"provenance", io::provenance_json(job.provenance)}},
                 job.folder + "/rows.json");
  fmt::print("Wrote {0}/rows.json and each pair's records.csv and records.json in {0}/<first>-<second>/\n", job.folder);
  return failed == 0 ? 0 : 3;
}

}  // namespace

/// A row: each neighbouring pair's needed gap from its own contact-free run (without contact the
/// buildings move independently, so a pair's clearance history is that of its two-building scene),
/// each pair's files in FOLDER/<first>-<second>/, and rows.json summing them up.
int run_row_gap(const GapCommand& command, const analysis::Scene& scene, const std::string& command_line) {
  if (command.curve > 0 || command.all_angles || command.amplification) {
    throw InputError("SCENE", command.scene,
                     "is a row: its gaps are found pair by pair; --curve, --all-angles and --amplification take "
                     "scenes of two buildings (run them on one pair's scene)");
  }
  if (!command.records.empty()) return run_row_record_set(command, scene, command_line);
  const std::string folder = command.out_dir.empty() ? "out/" + io::folder_name(scene.name + "-gap") : command.out_dir;
  io::require_writable_folder(folder, "--out");
  const io::Provenance provenance = io::make_provenance(scene, command_line);
  const InterruptRequests interrupts;
  const std::vector<RowPair> row = row_pairs(scene, folder);
  nlohmann::ordered_json pairs = nlohmann::ordered_json::array();
  bool completed = true;
  for (const RowPair& p : row) {
    const analysis::NeededGap gap = analysis::needed_gap(p.scene, run_budget(command));
    fmt::print("Pair {} (gap {:.6g} m{}): needed gap {}", p.name, p.pair.gap_m, turn_note(p.turned_deg),
               metres(gap.needed_gap_m));
    if (gap.candidate >= 0) {  // named by the row's building numbers
      std::vector<contact::Candidate> governing{gap.candidates[static_cast<std::size_t>(gap.candidate)]};
      contact::place_in_pair(governing, {p.pair.first, p.pair.second}, 0);
      fmt::print(" at t = {:.6f} s, {}{}", gap.t_s, contact::describe(governing.front()),
                 p.turned_deg == 0.0 ? "" : " (in the turned plan's coordinates)");
    }
    fmt::print("\n");
    print_levels(gap, row_pair_names(p.scene));
    print_rules(gap, row_pair_names(p.scene));
    const bool done = gap.status == solvers::RunStatus::completed;
    completed = completed && done;
    if (!done) fmt::print("Stopped at t = {:.3f} s ({}): a lower bound\n", gap.end_s, solvers::to_string(gap.status));
    io::write_gap(p.scene.name, gap, {}, provenance, p.folder);
    pairs.push_back({{"pair", p.name},
                     {"buildings", {p.pair.first + 1, p.pair.second + 1}},
                     {"gap_m", p.pair.gap_m},
                     {"plan_turned_deg", p.turned_deg},
                     {"needed_gap_m", std::isfinite(gap.needed_gap_m) ? nlohmann::json(gap.needed_gap_m) : nullptr},
                     {"t_s", gap.candidate < 0 ? nlohmann::json(nullptr) : nlohmann::json(gap.t_s)},
                     {"status", solvers::to_string(gap.status)},
                     {"folder", p.folder}});
  }
  io::write_json(
      nlohmann::ordered_json{{"scene", scene.name}, {"pairs", pairs}, {"provenance", io::provenance_json(provenance)}},
      folder + "/rows.json");
  fmt::print("Wrote {0}/rows.json and each pair's gap.json, gap.csv, gap_history.csv in {0}/<first>-<second>/\n",
             folder);
  return completed ? 0 : 3;
}

int run_gap(const GapCommand& command, const std::string& command_line) {
  analysis::Scene scene = io::read_scene(command.scene, {.gaps = command.gaps, .record = command.record});
  std::map<std::string, std::string> names;  // an option's value is blamed on the option
  try {
    for (const auto& [setting, value] : command.settings) {
      scene.solver.set(setting, value);
      names["solver." + std::string(analysis::spec(setting).key)] = analysis::spec(setting).option;
    }
    scene.validate();
  } catch (const InputError& error) {
    throw error.renamed(names).in_context(command.scene);
  }
  if (scene.is_row()) return run_row_gap(command, scene, command_line);
  if (!command.records.empty()) return run_record_set(command, scene, command_line);
  // A scene name is text, not a path; the folder must take files before the runs, not after them.
  const std::string folder = command.out_dir.empty() ? "out/" + io::folder_name(scene.name + "-gap") : command.out_dir;
  io::require_writable_folder(folder, "--out");
  const io::Provenance provenance = io::make_provenance(scene, command_line);
  const InterruptRequests interrupts;
  analysis::NeededGap gap = analysis::needed_gap(scene, run_budget(command));
  if (command.amplification) {
    try {
      analysis::add_amplified_elastic(scene, *command.amplification, gap, run_budget(command));
    } catch (const InputError& error) {
      if (error.key() != "amplification") throw;
      throw InputError("--amplification", error.value(), error.reason());
    }
  }
  fmt::print("Needed gap of '{}' (contact-free run, CVODE rtol {:g}; {} maxima located, {} steps, {:.3f} s):\n",
             scene.name, analysis::resolve(scene.solver).rtol, gap.extrema, gap.steps, gap.wall_time_s);
  if (gap.candidate < 0) {
    fmt::print("  no vertex-edge pair ever approaches: any gap prevents contact\n");
  } else {
    const contact::Candidate& pair = gap.candidates[static_cast<std::size_t>(gap.candidate)];
    const std::string where =
        pair.column ? fmt::format("B{} floor {} facing B{}'s storey-{} columns (z = {:.2f} m)",
                                  pair.struck_building + 1, pair.floor_of(pair.struck_building),
                                  pair.striking_building + 1, pair.floor_of(pair.striking_building), pair.elevation_m)
                    : fmt::format("level {} (floors {}/{}, z = {:.2f} m)", gap.level, pair.floors[0], pair.floors[1],
                                  pair.elevation_m);
    fmt::print("  {} at {}, t = {:.6f} s, pair {}\n", metres(gap.needed_gap_m), where, gap.t_s,
               contact::describe(pair));
  }
  print_levels(gap);
  print_rules(gap);
  print_amplified(gap);
  if (command.all_angles) {
    analysis::add_all_angles(scene, gap, run_budget(command));
    print_all_angles(gap);
  }
  const bool completed = gap.status == solvers::RunStatus::completed &&
                         (!gap.all_angles || gap.all_angles->status == solvers::RunStatus::completed);
  if (!completed) {
    fmt::print(
        "Stopped at t = {:.3f} s ({}: {}): the figures above cover the record up to there only; the needed "
        "gap is a lower bound\n",
        gap.end_s, solvers::to_string(gap.status), gap.status_detail);
  }

  std::vector<analysis::SeverityPoint> curve;
  if (command.curve > 0 && completed) {
    fmt::print("Severity below the needed gap: {} runs ({})\n", command.curve, scene.solver.method);
    int done = 0;
    try {
      curve = analysis::severity_curve(
          scene, gap.needed_gap_m, command.curve, command.threads, [&](const analysis::SeverityPoint& p) {
            fmt::print(stderr, "\r  {}/{} runs done (gap {:.4f} m)", ++done, command.curve, p.gap_m);
          });
    } catch (const InputError& error) {
      if (error.key() != "count") throw;
      throw InputError("--curve", error.value(), error.reason());
    }
    fmt::print(stderr, "\n");
    print_curve(curve);
  }
  io::write_gap(scene.name, gap, curve, provenance, folder);
  fmt::print("Wrote {0}/gap.json, gap.csv, gap_history.csv{1}{2}; draw them with tools/plot_gap.py {0}\n", folder,
             curve.empty() ? "" : ", gap_curve.csv", gap.all_angles ? ", gap_angles.csv" : "");
  return completed ? 0 : 3;
}

}  // namespace pounding::cli
