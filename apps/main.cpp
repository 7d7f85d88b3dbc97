// The `pounding` command-line program: parses arguments, calls a command, maps errors to exit
// codes (2 for bad input, 3 for a run that did not complete, 1 for anything else).

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <initializer_list>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "commands.hpp"
#include "pounding/analysis/contact_laws.hpp"
#include "pounding/analysis/methods.hpp"
#include "pounding/analysis/run_scene.hpp"
#include "pounding/analysis/scene.hpp"
#include "pounding/input_error.hpp"
#include "pounding/io/provenance.hpp"
#include "pounding/version.hpp"

namespace {

void add_scene_argument(CLI::App& command, std::string& scene) {
  command.add_option("scene", scene, "Scene file (TOML)")->required();
}

/// `--gap`, once per pair: a gap in m (two buildings: building 2 moves along x), or NAME:NAME=m
/// for a neighbouring pair of a row (io::SceneOverrides::gaps).
void add_gap_option(CLI::App& command, std::vector<std::string>& gaps) {
  command
      .add_option("--gap", gaps,
                  "Clear gap (m): moves building 2 along x. A row: NAME:NAME=m, one --gap per pair (the pair's "
                  "second building moves, with its neighbours beyond)")
      ->allow_extra_args(false);
}

/// A run's folder and, for a scene built in code or changed since, its scene file (animate, report).
void add_run_folder_arguments(CLI::App& command, std::string& run_dir, std::string& scene) {
  command.add_option("run_dir", run_dir, "Folder of a run (pounding run --out)")->required();
  command.add_option("--scene", scene, "Scene file of the run (default: the one its summary.json names, if unchanged)");
}

/// The options that replace the scene's record or its scaling (io::SceneOverrides::record).
void add_record_options(CLI::App& command, pounding::excitation::RecordChoice& record) {
  command.add_option_function<std::string>(
      "--record", [&record](const std::string& file) { record.file = file; },
      "Record file replacing the scene's (path from the current folder); the scene's format, units, scaling and "
      "direction still apply, its dt_s, columns and cut do not");
  command.add_option("--record-format", record.format, "Format of the record: peer-at2, columns or single");
  command.add_option("--units", record.units,
                     "Units of the record's accelerations: " + std::string(pounding::excitation::kAccelUnitChoices));
  command.add_option("--record-dt", record.dt_s,
                     "single: the record's sample spacing (s); other formats: re-spaces it");
  command.add_option("--record-column", record.accel_column, "Column of the acceleration in the record (from 1)");
  command.add_option("--scale,--scale-factor", record.scale_factor,
                     "Multiply the record by this (the scene's scale_factor; replaces the scene's scaling)");
  command.add_option("--pga-g,--scale-to-pga-g", record.pga_g,
                     "Scale the record to this peak |a_g| in g (the scene's scale_to_pga_g; replaces the scene's "
                     "scaling)");
  command.add_option("--scale-to-sa", record.sa,
                     "Scale the record so its 5%-damped PSA (of a pair: RotD100) at a period is this: 0.5g@T1 (the "
                     "longer first period of the two buildings), 0.5g@B1, 0.5g@B2 or 0.5g@1.2s; or so it best fits "
                     "the ASCE 7 design spectrum over a range: 'asce7(SDS=1.0,SD1=0.6,TL=8)@0.2-2T1' or @0.1-1.5s "
                     "(replaces the scene's scaling)");
  command.add_option(
      "--direction-deg", record.direction_deg,
      "Direction of the shaking in plan (degrees from +x); a pair's second component acts 90 degrees on");
  command.add_option_function<std::string>(
      "--record2", [&record](const std::string& file) { record.second_file = file; },
      "Second horizontal component of a pair (path from the current folder), read with the record's format and "
      "units, acting along --direction-deg + 90 degrees; replaces the scene's [excitation.second]");
  command.add_option("--record2-column", record.second_accel_column,
                     "Column of the second component's acceleration (from 1); a pair from one file: --record F "
                     "--record-column 2 --record2 F --record2-column 3");
}

/// A study's timed repetitions: each repeats the whole ladder (about a minute on the paper scene).
constexpr int kMaxStudyRepeats = 100;

/// Whole-number options: the range each may take, checked on the text (so an overflowing
/// 99999999999999999999 is refused by name, not wrapped or clamped by the conversion); the
/// [solver] settings' ranges come from their table (methods.hpp).
std::map<std::string, std::pair<long long, long long>> integer_ranges_of_options() {
  std::map<std::string, std::pair<long long, long long>> ranges = {
      {"--order", {1, 12}},  // any ARKODE table; the method's own orders are checked after
      {"--record-column", {1, 1000}},
      {"--record2-column", {1, 1000}},
      {"--threads", {0, 4096}}};
  auto add = [&ranges](std::string_view option, const pounding::Range& range) {
    ranges[std::string(option)] = {static_cast<long long>(range.min), static_cast<long long>(range.max)};
  };
  for (const pounding::analysis::SettingSpec& spec : pounding::analysis::setting_specs()) {
    if (spec.member.index() == 0 && spec.range) add(spec.option, *spec.range);
  }
  for (const pounding::analysis::LimitSpec& spec : pounding::analysis::limit_specs()) {
    if (pounding::analysis::type_name(spec) == "integer" && spec.range) add(spec.option, *spec.range);
  }
  return ranges;
}

/// The options of a key table's rows (key_spec.hpp), each value kept by option name in `given`
/// for the library to apply and check. An option the command already has (`--gap`, with its own
/// forms) or that an earlier row shares (`--contact-stiffness`) is not added again.
template <typename Owner>
void add_key_options(CLI::App& command, std::span<const pounding::analysis::KeySpec<Owner>> specs,
                     pounding::cli::GivenKeys& given) {
  for (const pounding::analysis::KeySpec<Owner>& spec : specs) {
    const std::string option(spec.option);
    if (option.empty() || command.get_option_no_throw(option) != nullptr) continue;
    std::visit(
        [&](auto Owner::*member) {
          using T = std::decay_t<decltype(Owner{}.*member)>;
          using Parsed = std::conditional_t<
              std::is_same_v<T, long>, long,
              std::conditional_t<std::is_same_v<T, std::string> || std::is_same_v<T, bool>, std::string, double>>;
          command.add_option_function<Parsed>(
              option, [&given, option](const Parsed& value) { given[option] = value; },
              pounding::analysis::option_help(spec));
        },
        spec.member);
  }
}

/// The [solver] settings' options (setting_specs()), each value kept by setting in `given` for
/// SolverSettings::set(); `only`: just these settings (empty: every one).
void add_setting_options(CLI::App& command,
                         std::map<pounding::analysis::Setting, pounding::analysis::SettingValue>& given,
                         std::initializer_list<pounding::analysis::Setting> only = {}) {
  for (const pounding::analysis::SettingSpec& spec : pounding::analysis::setting_specs()) {
    if (only.size() != 0 && std::find(only.begin(), only.end(), spec.id) == only.end()) continue;
    std::visit(
        [&](const auto& member) {
          using T = typename std::decay_t<decltype(pounding::analysis::SolverSettings{}.*member.given)>::value_type;
          command.add_option_function<T>(
              std::string(spec.option), [&given, id = spec.id](const T& value) { given[id] = value; },
              pounding::analysis::option_help(spec.id));
        },
        spec.member);
  }
}

/// Every option that takes a value refuses an empty one (`--gap ''` is a slip, not "unset"), and
/// the whole-number options their range.
void harden_options(CLI::App& app) {
  const CLI::Validator non_empty(
      [](std::string& value) { return value.empty() ? std::string("an empty value is not allowed") : std::string(); },
      "", "NON_EMPTY");
  const auto integer_ranges = integer_ranges_of_options();
  for (CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) {
    for (CLI::Option* option : command->get_options([](CLI::Option* o) { return o->get_type_size() > 0; })) {
      option->check(non_empty);
      const auto range = integer_ranges.find(option->get_name());
      if (range != integer_ranges.end()) option->check(CLI::Range(range->second.first, range->second.second));
    }
  }
}

/// A first argument that names no command: said with the word and the commands there are (CLI11
/// would say only "A subcommand is required").
std::optional<std::string> unknown_command(CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return std::nullopt;
  std::string names;
  for (const CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) {
    if (command->get_name() == argv[1]) return std::nullopt;
    names += (names.empty() ? "" : ", ") + command->get_name();
  }
  return fmt::format("unknown command '{}'; the commands are {}", argv[1], names);
}

/// "pounding 0.1.0 (git 0123abc...)", or without the commit when the build did not know it.
std::string version_text() {
  const std::string_view commit = pounding::git_commit();
  return fmt::format("pounding {}{}", pounding::program_version(),
                     commit.empty() ? std::string() : fmt::format(" (git {})", commit));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"pounding: seismic pounding of adjacent multistorey buildings, two or a row of any number"};
  app.require_subcommand(1);
  app.set_version_flag("--version", version_text(), "Print the program version and the git commit it was built from");

  pounding::cli::ModesCommand modes;
  CLI::App* modes_app = app.add_subcommand("modes", "Modal analysis of both buildings");
  add_scene_argument(*modes_app, modes.scene);
  modes_app->add_option("--json", modes.json_file, "Also write the modes as JSON to this file");
  modes_app->add_option("--count", modes.count, "Modes printed per building")
      ->capture_default_str()
      ->check(CLI::Range(1, 10000));

  pounding::cli::MethodsCommand methods;
  CLI::App* methods_app = app.add_subcommand("methods", "The solution paths and the settings each uses");
  methods_app->add_flag("--json", methods.json, "As JSON (name, description, settings, study ladder and plot styles)");

  pounding::cli::SettingsCommand settings;
  CLI::App* settings_app =
      app.add_subcommand("settings",
                         "The [solver] and [contact] settings, the run limits and the [excitation], [output], "
                         "[building.hysteresis], [building.limit_states], [building.shear_capacity] and "
                         "[building.flexural_strength] keys: key, "
                         "option, type, "
                         "default, range (and the methods using each solver setting)");
  settings_app->add_flag("--json", settings.json,
                         "As JSON (key, toml, option, python, type, default, range or choices, unit, methods)");
  settings_app->add_option("--markdown", settings.markdown,
                           "solver, contact, limits, excitation, output, hysteresis, limit_states, shear_capacity or "
                           "flexural_strength: "
                           "that section's tables in "
                           "docs/scene-format.md (limits: docs/guide/limits.md)");

  pounding::cli::OutputsCommand outputs;
  CLI::App* outputs_app = app.add_subcommand(
      "outputs",
      "Every output field: history.csv's columns, impacts, per-floor peaks and the energy audit, with units");
  outputs_app->add_flag("--json", outputs.json, "As JSON (history, impacts, peaks, energy: name, unit, description)");
  outputs_app->add_option("--markdown", outputs.markdown,
                          "history, impacts, peaks or energy: that table of docs/guide/output-columns.md");

  pounding::cli::LawsCommand laws;
  CLI::App* laws_app =
      app.add_subcommand("laws", "The contact laws, their default stiffness and the rebound each achieves");
  laws_app->add_flag("--json", laws.json, "As JSON (name, description, keys, default stiffness, methods, rebound)");
  laws_app->add_option("--restitution", laws.restitution, "Restitution e at which to give each law's rebound")
      ->capture_default_str();

  pounding::cli::CheckCommand check;
  CLI::App* check_app = app.add_subcommand("check", "Validate a scene and print what it describes");
  add_scene_argument(*check_app, check.scene);
  add_gap_option(*check_app, check.gaps);
  add_key_options(*check_app, pounding::analysis::contact_setting_specs(), check.contact);
  add_record_options(*check_app, check.record);

  pounding::cli::RunCommand run;
  CLI::App* run_app = app.add_subcommand("run", "Time-history analysis with event-driven contact");
  add_scene_argument(*run_app, run.scene);
  add_gap_option(*run_app, run.gaps);
  add_key_options(*run_app, pounding::analysis::contact_setting_specs(), run.contact);
  add_record_options(*run_app, run.record);
  run_app->add_option("--method", run.method, pounding::analysis::methods_help());
  add_setting_options(*run_app, run.settings);
  run_app->add_option("--halving", run.halving,
                      "hht: on (default) or off (impacts at the end of the overlapping step)");
  run_app->add_flag("--contact-free-reference", run.contact_free_reference,
                    "Also run without contact and report the pounding-induced change of each storey's peak drift "
                    "(and ductility) (sets output.contact_free_reference)");
  run_app->add_flag("--member-forces", run.member_forces,
                    "Record the storeys' shears and torques and the columns' shears and end moments: peaks in "
                    "summary.json, histories in history.csv (sets output.member_forces)");
  run_app->add_option("--history", run.history,
                      "on or off: write history.csv and contacts_history.csv (replaces output.history; off computes "
                      "neither)");
  run_app->add_option(
      "--peaks", run.peaks,
      "Peak groups in summary.json: none, all or a comma-separated list of displacements, accelerations, "
      "drifts (replaces output.peaks)");
  run_app->add_option("--out", run.out_dir, "Output folder (default out/<scene name>)");
  add_key_options(*run_app, pounding::analysis::limit_specs(), run.limits);
  run_app->add_flag("--no-progress,--quiet", run.no_progress,
                    "No progress line (simulated time, impacts) on the terminal while the run goes; it is never "
                    "shown when stderr is not a terminal");

  pounding::cli::StudyCommand study;
  CLI::App* study_app =
      app.add_subcommand("study", "Error against run time of every solution path, measured against the exact path");
  add_scene_argument(*study_app, study.scene);
  add_gap_option(*study_app, study.gaps);
  study_app->add_option("--pair", study.pair,
                        "A row: the neighbouring pair NAME:NAME to study, alone (its own scene of two buildings)");
  study_app->add_option("--repeat", study.repeat, "Timed runs per setting; the median is reported")
      ->capture_default_str()
      ->check(CLI::Range(1, kMaxStudyRepeats));
  study_app->add_flag("--quick", study.quick, "A short ladder: rtol 1e-6 and 1e-8, dt 0.05 and 0.01 s");
  study_app->add_option("--out", study.out_dir, "Output folder (default out/<scene name>-study)");

  pounding::cli::GapCommand gap;
  CLI::App* gap_app =
      app.add_subcommand("gap", "The clear gap that prevents pounding, from one contact-free run, and the code rules");
  add_scene_argument(*gap_app, gap.scene);
  add_gap_option(*gap_app, gap.gaps);
  add_setting_options(*gap_app, gap.settings, {pounding::analysis::Setting::rtol, pounding::analysis::Setting::atol});
  add_record_options(*gap_app, gap.record);
  CLI::Option* curve =
      gap_app->add_option("--curve", gap.curve, "Also run N gaps from 0 towards the needed gap: the severity table")
          ->check(CLI::Range(2, 1000));
  gap_app
      ->add_option("--records", gap.records,
                   "The needed gap under every record of a list file (a path and options a line) or of a "
                   "folder's .AT2 files, with the set's statistics")
      ->excludes(curve)
      ->excludes("--record");
  gap_app->add_option("--threads", gap.threads, "Runs of --curve or --records at a time (default: every core)");
  gap_app->add_option(
      "--max-wall-time", gap.max_wall_time_s,
      "Stop each contact-free run after this many seconds (default 3600); SIGINT/SIGTERM stop them too");
  gap_app
      ->add_option("--amplification", gap.amplification,
                   "Yielding columns: also the code rules from the elastic contact-free run's peaks times this "
                   "factor (ASCE 7 Cd/Ie, EC8 q), against the yielding buildings' needed gap")
      ->excludes("--records");
  gap_app
      ->add_flag("--all-angles", gap.all_angles,
                 "Also the needed gap over every angle of incidence of the record (or pair): elastic buildings from "
                 "two contact-free runs (superposition), yielding ones from a run every 10 degrees; the worst angle "
                 "refined with full runs (gap_angles.csv, gap.json all_angles)")
      ->excludes("--records");
  gap_app->add_option("--out", gap.out_dir,
                      "Output folder (default out/<scene name>-gap, or out/<scene name>-records with --records)");

  pounding::cli::SpectrumCommand spectrum;
  CLI::App* spectrum_app = app.add_subcommand(
      "spectrum",
      "Elastic response spectra (Sd, PSV, PSA) of records, exact for piecewise-linear records; RotD50 and "
      "RotD100 of a pair; a scene's building periods marked");
  spectrum_app->add_option("records", spectrum.records, "Record files (one spectrum each)")->required();
  spectrum_app->add_option("--format", spectrum.format,
                           "Format of the records: peer-at2, columns or single (default: peer-at2 for .AT2 files, "
                           "else columns)");
  spectrum_app
      ->add_option("--units", spectrum.units,
                   "Units of the records' accelerations: " + std::string(pounding::excitation::kAccelUnitChoices))
      ->capture_default_str();
  spectrum_app->add_option("--record-dt", spectrum.dt_s,
                           "single: the records' sample spacing (s); other formats: re-spaces them");
  spectrum_app
      ->add_option("--record-column", spectrum.accel_columns,
                   "Column of the acceleration (from 1): one for every record, or one per record, "
                   "comma-separated (a pair from one file: 1,2)")
      ->delimiter(',');
  spectrum_app->add_option("--damping", spectrum.damping_ratio, "Critical damping ratio of the oscillators, in [0, 1)")
      ->capture_default_str();
  spectrum_app
      ->add_option("--periods", spectrum.periods_s, "Periods (s), comma-separated (default 0.01-10 s, 61 log-spaced)")
      ->delimiter(',');
  spectrum_app->add_flag("--rotd", spectrum.rotd,
                         "With two records (a pair of horizontal components): RotD50 and RotD100");
  spectrum_app->add_option("--angle-step", spectrum.angle_step_deg, "Angle step of RotD (degrees)")
      ->capture_default_str();
  spectrum_app->add_option("--scene", spectrum.scene, "Scene whose buildings' first three periods are marked");
  spectrum_app->add_option("--out", spectrum.out_dir, "Output folder")->capture_default_str();
  spectrum_app->add_flag("--no-plot", spectrum.no_plot, "Do not draw spectrum.png (tools/plot_spectrum.py)");

  pounding::cli::PlanCommand plan;
  CLI::App* plan_app = app.add_subcommand(
      "plan",
      "The scene's plan and elevation before any run: slabs, columns, centres of mass and of stiffness, the "
      "levels where floors meet and the contact candidates (plan.json; plan.png by tools/plot_plan.py)");
  plan_app->add_option("scene", plan.scene, "Scene file (TOML)")->required();
  add_gap_option(*plan_app, plan.gaps);
  plan_app->add_option("--out", plan.out_dir, "Output folder (default out/<scene name>-plan)");
  plan_app->add_flag("--no-plot", plan.no_plot, "Do not draw plan.png");

  pounding::cli::AnimateCommand animate;
  CLI::App* animate_app = app.add_subcommand(
      "animate",
      "A film of a run: the slabs of one level in plan, their motion exaggerated, impacts marked (MP4 "
      "with ffmpeg, else GIF; tools/animate_run.py). Writes the plan of the run's scene to RUN_DIR/plan.json");
  add_run_folder_arguments(*animate_app, animate.run_dir, animate.scene);
  animate_app->add_option("--level", animate.level, "Level to show (default: the history level with most impacts)")
      ->check(CLI::Range(1, 100000));
  animate_app
      ->add_option("--scale", animate.scale,
                   "Motion drawn this many times larger (default: the largest displacement as 1/8 of the plan)")
      ->check(CLI::PositiveNumber);
  animate_app->add_option("--fps", animate.fps, "Frames per second of the film")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 60.0));
  animate_app->add_option("--speed", animate.speed, "Simulated seconds per second of film")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  animate_app->add_option("--start", animate.start_s, "First simulated time shown (s; default the run's start)");
  animate_app->add_option("--end", animate.end_s, "Last simulated time shown (s; default the run's end)");
  animate_app->add_option("--format", animate.format, "mp4 (needs ffmpeg), gif, or auto")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "mp4", "gif"}));
  animate_app->add_option("--out", animate.out_file, "Film file (default RUN_DIR/level<N>.mp4 or .gif)");

  pounding::cli::ReportCommand report;
  CLI::App* report_app = app.add_subcommand(
      "report",
      "One self-contained HTML page of a run: plan, histories, impacts, energy, settings and provenance "
      "(tools/report_run.py). Writes the plan of the run's scene to RUN_DIR/plan.json");
  add_run_folder_arguments(*report_app, report.run_dir, report.scene);
  report_app->add_option("--out", report.out_file, "HTML file (default RUN_DIR/report.html)");
  report_app->add_option("--bracket", report.bracket,
                         "bracket.json of `pounding bracket` on the run's scene, or its folder: the page shows its "
                         "spread");

  pounding::cli::VerifyCommand verify;
  CLI::App* verify_app = app.add_subcommand(
      "verify",
      "Runs a manifest's cases and checks them against stored (--bless) or written expected results: impact "
      "counts and times, impulses, peaks, needed gaps, energy, overlap. A table, OUT/junit.xml, verify.md and "
      "verify.json; exit 1 when a check fails (python3 -m pounding.verify)");
  verify_app->add_option("manifest", verify.manifest, "Manifest file (TOML)")->required();
  verify_app->add_flag("--bless", verify.bless, "Store this run's results as the expected ones first");
  verify_app->add_option("--jobs", verify.jobs, "Cases at a time (default: every core)")->check(CLI::Range(1, 4096));
  verify_app->add_option("--out", verify.out_dir, "Output folder (default out/verify-<manifest name>)");
  verify_app->add_flag("--no-progress,--quiet", verify.no_progress, "No progress line");

  pounding::cli::CompareCommand compare;
  CLI::App* compare_app = app.add_subcommand(
      "compare",
      "Two runs of any methods compared: impacts matched by contact and time, the peaks and histories "
      "(tools/compare_runs.py)");
  compare_app->add_option("run_a", compare.run_a, "Folder of run A (pounding run --out)")->required();
  compare_app->add_option("run_b", compare.run_b, "Folder of run B")->required();
  compare_app->add_option("--window", compare.window_s, "Largest time difference of a match (s; default 0.05)")
      ->check(CLI::PositiveNumber);
  compare_app->add_option("--json", compare.json_file, "Also write the comparison as JSON");

  pounding::cli::SweepCommand sweep;
  CLI::App* sweep_app = app.add_subcommand(
      "sweep",
      "Runs of every scene x record x gap x restitution x method x contact law of a sweep file, on Dask "
      "(python3 -m pounding.sweep), into one table; a sweep started again skips the runs done");
  sweep_app->add_option("sweep_file", sweep.sweep_file, "Sweep file (TOML)")->required();
  CLI::Option* workers =
      sweep_app->add_option("--workers", sweep.workers, "Worker processes of a LocalCluster (default: every core)")
          ->check(CLI::Range(1, 4096));
  CLI::Option* serial =
      sweep_app->add_flag("--serial", sweep.serial, "No Dask: the runs one after another in one process")
          ->excludes(workers);
  sweep_app->add_option("--scheduler", sweep.scheduler, "Address of a running Dask scheduler (tcp://HOST:8786)")
      ->excludes(workers)
      ->excludes(serial);
  sweep_app->add_option("--out", sweep.out_dir, "Output folder (default: the file's out, else out/<sweep file name>)");
  sweep_app->add_flag("--no-progress,--quiet", sweep.no_progress, "No progress bar");

  pounding::cli::BracketCommand bracket;
  CLI::App* bracket_app = app.add_subcommand(
      "bracket",
      "One scene run across contact laws, restitutions and contact stiffnesses: every demand's spread "
      "(min, max, max/min) and whether each verdict is the same on all runs; OUT/bracket.csv and "
      "bracket.json (python3 -m pounding.bracket)");
  bracket_app->add_option("scene", bracket.scene, "Scene file (TOML)")->required();
  bracket_app->add_option("--laws", bracket.laws, "Contact laws, comma-separated (default: every law)");
  bracket_app->add_option("--restitutions", bracket.restitutions,
                          "Restitutions in [0, 1], comma-separated (default 0.5,0.65,0.8)");
  bracket_app->add_option("--stiffness-factors", bracket.stiffness_factors,
                          "Multiples of each law's base stiffness (the scene's for its own law, else the "
                          "law's default), comma-separated (default 0.25,1,4)");
  bracket_app->add_option("--method", bracket.method, pounding::analysis::methods_help());
  bracket_app->add_option("--out", bracket.out_dir, "Output folder (default out/bracket-<scene name>)");
  bracket_app->add_flag("--no-progress,--quiet", bracket.no_progress, "No progress line");

  harden_options(app);
  if (const auto unknown = unknown_command(app, argc, argv)) {
    fmt::print(stderr, "error: {}\n", *unknown);
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error) == 0 ? 0 : 2;  // --help exits 0; every usage error is bad input
  }

  const std::string command_line = pounding::io::command_line_text(std::vector<std::string>(argv, argv + argc));
  try {
    if (*modes_app) return pounding::cli::run_modes(modes);
    if (*check_app) return pounding::cli::run_check(check);
    if (*methods_app) return pounding::cli::run_methods(methods);
    if (*laws_app) return pounding::cli::run_laws(laws);
    if (*settings_app) return pounding::cli::run_settings(settings);
    if (*outputs_app) return pounding::cli::run_outputs(outputs);
    if (*run_app) return pounding::cli::run_run(run, command_line);
    if (*study_app) return pounding::cli::run_study(study, command_line);
    if (*gap_app) return pounding::cli::run_gap(gap, command_line);
    if (*sweep_app) return pounding::cli::run_sweep(sweep);
    if (*verify_app) return pounding::cli::run_verify(verify);
    if (*bracket_app) return pounding::cli::run_bracket(bracket);
    if (*compare_app) return pounding::cli::run_compare(compare);
    if (*spectrum_app) return pounding::cli::run_spectrum(spectrum, command_line);
    if (*plan_app) return pounding::cli::run_plan(plan, command_line);
    if (*animate_app) return pounding::cli::run_animate(animate, command_line);
    if (*report_app) return pounding::cli::run_report(report, command_line);
  } catch (const pounding::InputError& error) {
    fmt::print(stderr, "error: {}\n", error.what());
    return 2;
  } catch (const std::exception& error) {
    fmt::print(stderr, "error: {}\n", error.what());
    return 1;
  }
  return 1;
}
