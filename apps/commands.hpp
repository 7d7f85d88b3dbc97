#pragma once
// The sub-commands of the `pounding` program. Each one reads its inputs through the library,
// prints, and returns the process exit code; errors propagate as exceptions to main(). Those that
// write results take the command line as typed, for the outputs' provenance.

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "pounding/key_spec.hpp"
#include "pounding/analysis/methods.hpp"
#include "pounding/excitation/record_choice.hpp"

namespace pounding::cli {

struct ModesCommand {
  std::string scene;
  std::string json_file;  // empty: no JSON
  int count = 6;          // modes printed per building
};

struct MethodsCommand {
  bool json = false;  // the registry as JSON on stdout (for scripts)
};

struct SettingsCommand {
  bool json = false;                    // the table as JSON on stdout (for scripts)
  std::optional<std::string> markdown;  // solver | contact | limits: that table of the docs
};

struct OutputsCommand {
  bool json = false;                    // every field as JSON on stdout (for scripts)
  std::optional<std::string> markdown;  // history | impacts | peaks | energy: a table of output-columns.md
};

struct LawsCommand {
  bool json = false;         // the contact-law registry as JSON on stdout (for scripts)
  double restitution = 0.5;  // e for each law's closed-form rebound
};

/// Options of a key table's rows as given (analysis::KeyValue), by option name.
using GivenKeys = std::map<std::string, analysis::KeyValue, std::less<>>;

struct CheckCommand {
  std::string scene;
  std::vector<std::string> gaps;    // --gap (io::SceneOverrides::gaps)
  GivenKeys contact;                // --restitution, --contact-law, ... (io::SceneOverrides::contact)
  excitation::RecordChoice record;  // --record, --scale, --pga-g, ...
};

struct RunCommand {
  std::string scene;
  std::vector<std::string> gaps;    // --gap (io::SceneOverrides::gaps)
  GivenKeys contact;                // --restitution, --contact-law, ... (io::SceneOverrides::contact)
  excitation::RecordChoice record;  // --record, --scale, --pga-g, ...
  std::optional<std::string> method;
  std::map<analysis::Setting, analysis::SettingValue> settings;  // the [solver] options given (--rtol, --dt, ...)
  std::optional<std::string> halving;                            // on | off
  std::optional<std::string> history;                            // on | off: replaces output.history
  std::optional<std::string> peaks;     // none, all or a comma-separated list of groups: replaces output.peaks
  std::string out_dir;                  // empty: out/<scene name, made safe as a folder name>
  GivenKeys limits;                     // --max-steps, ... (analysis::limit_specs()); unset: RunLimits' defaults
  bool no_progress = false;             // no progress line even on a terminal
  bool contact_free_reference = false;  // --contact-free-reference: sets output.contact_free_reference
  bool member_forces = false;           // --member-forces: sets output.member_forces
};

struct StudyCommand {
  std::string scene;
  std::vector<std::string> gaps;  // --gap (io::SceneOverrides::gaps)
  std::string pair;               // --pair NAME:NAME: a row's pair, studied alone (its own scene of two)
  int repeat = 3;
  bool quick = false;   // a short ladder (for smoke tests)
  std::string out_dir;  // empty: out/<scene name>-study
};

struct GapCommand {
  std::string scene;
  std::vector<std::string> gaps;                                 // --gap (io::SceneOverrides::gaps)
  std::map<analysis::Setting, analysis::SettingValue> settings;  // --rtol, --atol: the contact-free run's
  excitation::RecordChoice record;                               // --record, --scale, --pga-g, ...
  std::string records;                    // --records: a list file or a folder of .AT2 files; empty: the scene's record
  int curve = 0;                          // gaps of the severity curve; 0: none
  unsigned threads = 0;                   // runs at a time (curve, records); 0: every core
  std::optional<double> max_wall_time_s;  // each contact-free run's budget (s); default one hour
  std::optional<double> amplification;    // yielding scenes: also the code rules from elastic peaks × this
  bool all_angles = false;                // also the needed gap over every angle of incidence
  std::string out_dir;                    // empty: out/<scene name>-gap (out/<scene name>-records with --records)
};

struct SpectrumCommand {
  std::vector<std::string> records;   // one spectrum each; two with --rotd: also the pair's RotD
  std::optional<std::string> format;  // peer-at2, columns, single; default: peer-at2 for .AT2, else columns
  std::string units = "g";            // of the records' accelerations
  std::optional<double> dt_s;         // single: the sample spacing; others: re-spaces
  std::vector<int> accel_columns;     // one for every record, or one per record (a pair from one file)
  double damping_ratio = 0.05;
  std::vector<double> periods_s;  // empty: 0.01–10 s, 61 log-spaced
  bool rotd = false;
  double angle_step_deg = 1.0;
  std::string scene;  // empty: no building periods marked
  std::string out_dir = "out/spectrum";
  bool no_plot = false;  // skip spectrum.png (drawn by tools/plot_spectrum.py)
};

struct PlanCommand {
  std::string scene;
  std::vector<std::string> gaps;  // --gap: building 2 moved along x, or a row's pair NAME:NAME=m
  std::string out_dir;            // empty: out/<scene name>-plan
  bool no_plot = false;           // skip plan.png (drawn by tools/plot_plan.py)
};

/// `pounding animate RUN_DIR`: the slabs of one level in plan, moving (tools/animate_run.py).
struct AnimateCommand {
  std::string run_dir;
  std::string scene;              // empty: the scene file named in the run's summary.json
  std::optional<int> level;       // unset: the history level with the most impacts
  std::optional<double> scale;    // motion exaggeration; unset: the largest displacement drawn as 1/8 of the plan
  double fps = 20.0;              // frames per second of the film
  double speed = 1.0;             // simulated seconds per second of film
  std::optional<double> start_s;  // unset: the run's start
  std::optional<double> end_s;    // unset: the run's end
  std::string format = "auto";    // mp4 (needs ffmpeg), gif, or auto: mp4 when ffmpeg is there
  std::string out_file;           // empty: RUN_DIR/level<N>.mp4 or .gif
};

/// `pounding report RUN_DIR`: one self-contained HTML page of a run (tools/report_run.py).
struct ReportCommand {
  std::string run_dir;
  std::string scene;     // empty: the scene file named in the run's summary.json
  std::string out_file;  // empty: RUN_DIR/report.html
  std::string bracket;   // bracket.json of `pounding bracket` (or its folder); empty: none
};

/// `pounding verify MANIFEST` (python -m pounding.verify).
struct VerifyCommand {
  std::string manifest;
  bool bless = false;       // store this run's results as the expected ones first
  std::optional<int> jobs;  // cases at a time; unset: every core
  std::string out_dir;      // empty: out/verify-<manifest name>
  bool no_progress = false;
};

/// `pounding compare RUN_A RUN_B` (tools/compare_runs.py).
struct CompareCommand {
  std::string run_a, run_b;
  std::optional<double> window_s;  // largest time difference of a match
  std::string json_file;           // also the comparison as JSON
};

struct SweepCommand {
  std::string sweep_file;
  std::optional<int> workers;  // LocalCluster processes; unset: every core
  bool serial = false;         // no Dask: the runs one after another in the interpreter
  std::string scheduler;       // a running Dask scheduler's address; empty: a LocalCluster
  std::string out_dir;         // empty: the sweep file's `out`, else out/<sweep file name>
  bool no_progress = false;
};

/// `pounding bracket SCENE` (python -m pounding.bracket): the scene across contact laws,
/// restitutions and stiffnesses, with each demand's spread and each verdict's agreement.
struct BracketCommand {
  std::string scene;
  std::string laws;               // comma-separated; empty: every law
  std::string restitutions;       // comma-separated; empty: 0.5, 0.65, 0.8
  std::string stiffness_factors;  // comma-separated multiples of each law's base stiffness; empty: 0.25, 1, 4
  std::optional<std::string> method;
  std::string out_dir;  // empty: out/bracket-<scene name>
  bool no_progress = false;
};

int run_gap(const GapCommand& command, const std::string& command_line);  // in gap_command.cpp
/// Replaces the process by `python3 -m pounding.sweep` (its exit code is the command's).
/// @throws InputError when the interpreter or the module is missing.
int run_sweep(const SweepCommand& command);                                         // in sweep_command.cpp
int run_verify(const VerifyCommand& command);                                       // in sweep_command.cpp
int run_bracket(const BracketCommand& command);                                     // in sweep_command.cpp
int run_compare(const CompareCommand& command);                                     // in plan_command.cpp
int run_spectrum(const SpectrumCommand& command, const std::string& command_line);  // in spectrum_command.cpp
int run_plan(const PlanCommand& command, const std::string& command_line);          // in plan_command.cpp
int run_animate(const AnimateCommand& command, const std::string& command_line);    // in plan_command.cpp
int run_report(const ReportCommand& command, const std::string& command_line);      // in plan_command.cpp
int run_modes(const ModesCommand& command);
int run_study(const StudyCommand& command, const std::string& command_line);
int run_run(const RunCommand& command, const std::string& command_line);
int run_check(const CheckCommand& command);
int run_methods(const MethodsCommand& command);
/// `pounding settings`: every [solver] setting with its option, type, default, range and methods.
int run_settings(const SettingsCommand& command);
/// `pounding outputs`: every output field (history.csv columns, impacts, peaks, energy) with its
/// unit and meaning.
int run_outputs(const OutputsCommand& command);  // in outputs_command.cpp
/// The contact laws: name, description, keys, default stiffness and its source, methods, and the
/// rebound a lone contact achieves at the given restitution.
int run_laws(const LawsCommand& command);

}  // namespace pounding::cli
