#pragma once
// The one table of solution paths (methods): per method its name, a one-line description, its
// factory, the [solver] settings that apply to it, its study ladder and its plot style. Validation,
// `--help`, `check`, the study, summary.json's `settings` and the plot styles all read it, so a new
// method is one entry here plus its own solver files (the way Drake derives integrator names and
// factories from one list).
//
// Settings are kept as the user gave them (SolverSettings: unset = the method's default) and
// resolved to what a run uses (UsedSettings), like Ceres' `*_given` / `*_used`. A given setting the
// method does not use is refused by SolverSettings::validate(), naming the setting and the method.

#include <Eigen/Core>
#include <array>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "pounding/input_error.hpp"
#include "pounding/solvers/event_options.hpp"
#include "pounding/solvers/integrator.hpp"

namespace pounding::dynamics {
class CoupledSystem;
}

namespace pounding::analysis {

/// The keys of [solver] (docs/scene-format.md), in the order they are listed and written.
enum class Setting {
  order,
  rtol,
  atol,
  newton,
  form,
  hold_rtol,
  modes_cutoff_hz,
  dt_s,
  alpha,
  contact_tolerance_m,
  max_halvings,
  event_location,
  max_events_per_s
};

struct SolverSettings;
struct UsedSettings;
using SettingValue = std::variant<int, double, std::string>;

/// Where a setting of type T lives: its given value (unset: the default) and the value a run uses.
template <typename T>
struct SettingMember {
  std::optional<T> SolverSettings::*given;
  T UsedSettings::*used;
};

/// One [solver] setting, declared once: every reader (scene file, `pounding run` options, Python
/// keywords), the validator, resolve(), summary.json's settings, `--help`, `pounding settings` and
/// the table in docs/scene-format.md come from its row (the way Drake visits DRAKE_NVP fields).
struct SettingSpec {
  Setting id;
  std::string_view key;     // [solver] key, the key in summary.json and the Python keyword
  std::string_view option;  // `pounding run` option that sets it
  std::variant<SettingMember<int>, SettingMember<double>, SettingMember<std::string>> member;  // its type
  SettingValue default_value;                 // what a run uses when it is not given (order: the method's first)
  std::optional<Range> range = std::nullopt;  // numbers: the values accepted (integers are whole numbers in it)
  std::vector<std::string> choices{};         // text: the values accepted
  std::string_view description;               // one line, with units: `--help`
  std::string_view details{};                 // the docs' meaning column (docs/scene-format.md), after the description
};

/// Every setting, in enum order.
std::span<const SettingSpec> setting_specs();
const SettingSpec& spec(Setting setting);
/// "integer", "number" or "string": the type a reader expects.
std::string_view type_name(const SettingSpec& spec);
/// "an integer", "a number" or "a string": what a value of another type is told.
std::string expected_text(const SettingSpec& spec);
/// The accepted values as the docs and errors state them: "[1e-14, 0.1]", "0..60", "reduced or dense".
std::string accepted_text(const SettingSpec& spec);
/// The default as the docs print it ("1e-08", "\"reduced\"", "the method's first").
std::string default_text(const SettingSpec& spec);

/// Time integration of `pounding run` as given (scene file, then command line). Unset: the
/// method's default (UsedSettings lists the defaults).
struct SolverSettings {
  std::string method = "cvode-bdf";  // a name of the registry (methods())
  std::optional<int> order;          // ARKODE table order (MethodInfo::orders)
  std::optional<double> rtol;
  std::optional<double> atol;         // m: the slab displacements; rotations and rates derive from it (ComponentAtol)
  std::optional<std::string> newton;  // reduced | dense
  std::optional<std::string> form;    // physical | modal: the state the SUNDIALS methods integrate
  std::optional<double> hold_rtol;    // exact: held stretches
  std::optional<double> modes_cutoff_hz;  // exact: keep modes below this (Hz), the rest quasi-static
  std::optional<double> dt_s;             // hht
  std::optional<double> alpha;
  std::optional<double> contact_tolerance_m;
  std::optional<int> max_halvings;
  std::optional<std::string> event_location;  // halving | end-of-step | interpolate
  std::optional<double> max_events_per_s;     // event-driven: more in one simulated second stops the run
  /// Given settings this method does not use, with their values as text: what a scene file set
  /// for its own method when the command line runs another (with_method()). Never used.
  std::map<std::string, std::string> not_used;

  bool given(Setting setting) const;
  /// Gives `setting` the value `value` (an integer for a number is taken as that number).
  /// @throws InputError(`solver.<key>`, value, "expected an integer|a number|a string") for a
  ///   value of another type; the range is validate()'s.
  void set(Setting setting, const SettingValue& value);
  /// The method is a name of the registry, every given setting applies to it (else "does not
  /// apply to method M"), and every value lies in its range.
  /// @throws InputError naming `solver.<key>` and the value.
  void validate() const;
};

/// Absolute tolerances per state component (CVodeSVtolerances / ARKStepSVtolerances): metres,
/// radians and their rates differ by orders of magnitude (docs/scene-format.md, "atol").
///   u, v:      atol (m)
///   φ:         atol / r_b, r_b the largest distance of a slab corner of building b from its CM,
///              so a rotation error moves no corner by more than atol
///   rates:     the component's atol × ω₁, ω₁ the lowest circular frequency of both buildings:
///              a rate error δ displaces the state by about δ/ω within the time the response
///              takes to turn (1/ω), longest for the slowest mode, so δ = atol ω₁ keeps that drift
///              within atol for every mode.
struct ComponentAtol {
  double displacement_m = 0.0;
  std::vector<double> rotation_rad;  // per building
  double rate_per_s = 0.0;           // ω₁ (rad/s)
  /// The vector over the state (q, q̇) of `system`.
  Eigen::VectorXd vector(const dynamics::CoupledSystem& system) const;
};

/// @pre atol_m > 0.
ComponentAtol component_atol(const dynamics::CoupledSystem& system, double atol_m);

struct MethodInfo;

/// What a run uses: the given settings, the rest at their defaults (SettingSpec::default_value;
/// `order` is the method's first order). resolve() makes it.
struct UsedSettings {
  const MethodInfo* method = nullptr;
  int order = 0;  // the real table order; 0 for methods without one
  double rtol = 0.0;
  double atol = 0.0;             // m (ComponentAtol derives the rest)
  std::string newton;            // reduced | dense
  std::string form;              // physical (q, q̇) | modal (η, η̇) per building's modes (ModalSystem)
  double hold_rtol = 0.0;        // exact; the held stretches' atol is hold_rtol / 100 (m)
  double modes_cutoff_hz = 0.0;  // exact; 0: every mode (no truncation)
  double dt_s = 0.0;             // s
  double alpha = 0.0;
  double contact_tolerance_m = 0.0;
  int max_halvings = 0;
  std::string event_location;
  double max_events_per_s = 0.0;  // 1/s
  /// Per component, of atol (or of hold_rtol / 100 for exact); set by resolve() given a system.
  std::optional<ComponentAtol> atol_components;
};

struct SettingEntry {
  std::string_view key;
  SettingValue value;
};

struct PlotStyle {
  std::string_view colour;  // a matplotlib colour
  std::string_view marker;  // a matplotlib marker
};

/// One line of the work–precision study: the method, with `event_location` fixed if not empty.
struct StudySeries {
  std::string_view label;           // as study.csv's `method`
  std::string_view event_location;  // empty: the method's default
  PlotStyle style;
};

struct MethodInfo {
  std::string_view name;
  std::string_view description;     // one line
  std::vector<Setting> settings{};  // those that apply, in enum order
  std::vector<int> orders{};        // table orders offered, the default first; empty: no `order`
  bool event_driven = true;         // false: fixed steps (run_hht)
  /// Event-driven: the integrator with `used`'s settings on `system`'s state. Null for hht.
  solvers::IntegratorFactory (*factory)(const UsedSettings& used, const dynamics::CoupledSystem& system) = nullptr;
  double steps_per_period = 0.0;  // root bracketing of event-driven runs; 0: EventOptions' default
  bool clearance_steps = false;   // EventOptions::clearance_steps: longer steps far from contact
  bool reference = false;         // the study's reference (no ladder of its own)
  /// Runs scenes whose columns yield (in the physical form): their branch changes are root
  /// functions like the contacts. The exact path's modal propagator and HHT's constant effective
  /// matrix assume elastic buildings.
  bool yielding_columns = false;
  Setting ladder_setting = Setting::rtol;
  std::vector<double> ladder{}, quick_ladder{};  // the study's settings (quick: `study --quick`)
  std::vector<StudySeries> series{};             // one per line of the study plot
};

/// Every method, the default first.
std::span<const MethodInfo> methods();
/// @returns null for a name not in the registry.
const MethodInfo* find_method(std::string_view name);
/// @throws InputError(key, "\"name\"", "expected cvode-bdf, ...") for a name not in the registry.
const MethodInfo& method_info(std::string_view name, const std::string& key = "solver.method");
/// The study's reference (the one entry with `reference` set).
const MethodInfo& reference_method();
/// "cvode-bdf, cvode-adams, ... or exact".
std::string method_names();
bool applies(const MethodInfo& method, Setting setting);

/// `given` run with `method`: its settings that `method` does not use move to `not_used`.
/// @throws InputError (key `solver.method`) for an unknown method.
SolverSettings with_method(const SolverSettings& given, std::string_view method);

/// The settings a run of `given` uses; with `system`, also the absolute tolerances per component.
/// @pre given.validate() passed.
UsedSettings resolve(const SolverSettings& given, const dynamics::CoupledSystem* system = nullptr);

/// The given settings (not_used excluded), in registry order.
std::vector<SettingEntry> given_entries(const SolverSettings& given);
/// The settings the run's method uses, with their values, in registry order.
std::vector<SettingEntry> used_entries(const UsedSettings& used);
/// "rtol 1e-08, atol 1e-10 m (φ 5e-12 rad …), newton reduced": the printed settings line.
std::string describe_used_settings(const UsedSettings& used);
/// Text for `--help`: the option's meaning, its default and the methods it applies to.
std::string option_help(Setting setting);
/// Text for `--help` of --method: the names and the default.
std::string methods_help();

}  // namespace pounding::analysis
