#include "pounding/analysis/methods.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <string>

#include "pounding/dynamics/coupled_system.hpp"
#include "pounding/dynamics/modal_system.hpp"
#include "pounding/input_error.hpp"
#include "pounding/model/mode.hpp"
#include "pounding/solvers/arkode_integrator.hpp"
#include "pounding/solvers/cvode_integrator.hpp"
#include "pounding/solvers/deviation_integrator.hpp"
#include "pounding/solvers/modal_exact_integrator.hpp"
#include "pounding/solvers/modal_integrator.hpp"

namespace pounding::analysis {
namespace {

using IntegratorPtr = std::unique_ptr<solvers::Integrator>;

// Root bracketing of the exact path: a subdivision fine against the shortest period that moves a gap.
constexpr double kExactSubdivisionsPerPeriod = 16.0;

template <typename T>
constexpr SettingMember<T> member(std::optional<T> SolverSettings::*given, T UsedSettings::*used) {
  return {given, used};
}

// The settings. Ranges: below 1e-14 a relative tolerance is under round-off; hold_rtol looser than
// 1e-6 would make the ground truth less accurate than the paths it judges; above 1e4 Hz no
// building model has modes to drop; 0.05 s / 2⁶⁰ is below the round-off of t. Built on first use
// (a function's static), so that other files' static initialisers may read it.
const std::vector<SettingSpec>& specs() {
  static const std::vector<SettingSpec> kSpecs = {
      {.id = Setting::order,
       .key = "order",
       .option = "--order",
       .member = member(&SolverSettings::order, &UsedSettings::order),
       .default_value = 0,
       .description = "ARKODE table order",
       .details = "`arkode-erk` 5 (Dormand–Prince; the 8th-order Fehlberg table was dropped because its error "
                  "estimate is blind to the time-dependent forcing); `arkode-dirk` 4 (SDIRK 5-3-4, default) or 3 "
                  "(Kvaerno 4-2-3)"},
      {.id = Setting::rtol,
       .key = "rtol",
       .option = "--rtol",
       .member = member(&SolverSettings::rtol, &UsedSettings::rtol),
       .default_value = 1e-8,
       .range = Range{1e-14, 0.1},
       .description = "relative tolerance"},
      {.id = Setting::atol,
       .key = "atol",
       .option = "--atol",
       .member = member(&SolverSettings::atol, &UsedSettings::atol),
       .default_value = 1e-10,
       .range = Range{1e-16, 1e-3, "m"},
       .description = "absolute tolerance of the slab displacements (m); rotations and rates derive from it",
       .details = "the other components' tolerances derive from it (below)"},
      {.id = Setting::newton,
       .key = "newton",
       .option = "--newton",
       .member = member(&SolverSettings::newton, &UsedSettings::newton),
       .default_value = std::string("reduced"),
       .choices = {"reduced", "dense"},
       .description = "Newton linear solver: reduced (n x n) or dense (2n x 2n LU)",
       .details = "`reduced` solves the exact n×n structural system with the analytic Jacobian (by a sparse LU in "
                  "the physical form, O(n)); `dense` is SUNDIALS' dense LU of the 2n×2n matrix (slower; results "
                  "agree to the tolerance)"},
      {.id = Setting::form,
       .key = "form",
       .option = "--form",
       .member = member(&SolverSettings::form, &UsedSettings::form),
       .default_value = std::string("physical"),
       .choices = {"physical", "modal", "deviation"},
       .description = "state integrated: physical (q, q'), modal (each building's modal coordinates) or deviation "
                      "(from the exact contact-free response)",
       .details = "`modal` integrates each building's mass-normalised modal coordinates (η, η̇), q = Φη, in which "
                  "free flight is 3N decoupled oscillators with a diagonal Newton system (O(n) per solve instead of "
                  "an LU); while a contact force acts (a hold, a compliant contact) the physical equations are "
                  "mapped through the modes. Tolerances below. Results agree with `physical` to the tolerance "
                  "(tests/solvers/test_modal_form.cpp). `deviation` integrates z = y − y_p(t), y_p the contact-free "
                  "response from the run's start propagated exactly over the record's linear pieces: the record's "
                  "kink at every sample is in y_p, so BDF no longer shrinks its steps at each sample of a dense "
                  "record, and its steps cross the samples (Chi-Chi at 0.005 s: 7 300 steps instead of 204 000, 0.33 s "
                  "instead of 2.2 s with impacts and energy only); "
                  "tolerances as `physical`, applied to z"},
      {.id = Setting::hold_rtol,
       .key = "hold_rtol",
       .option = "--hold-rtol",
       .member = member(&SolverSettings::hold_rtol, &UsedSettings::hold_rtol),
       .default_value = 1e-12,
       .range = Range{1e-14, 1e-6},
       .description = "relative tolerance of held stretches (CVODE BDF)",
       .details = "held stretches are the one part of the exact path integrated numerically (CVODE BDF, atol = "
                  "hold_rtol/100 m, per component as below): a held contact rotates with the slabs, so it is not "
                  "linear. Free flight is exact whatever this is"},
      {.id = Setting::modes_cutoff_hz,
       .key = "modes_cutoff_hz",
       .option = "--modes-cutoff",
       .member = member(&SolverSettings::modes_cutoff_hz, &UsedSettings::modes_cutoff_hz),
       .default_value = 0.0,
       .range = Range{0.0, 1e4, "Hz"},
       .description =
           "keep each building's modes below this frequency (Hz), the rest as their static response; 0: every mode",
       .details = "modal truncation: the other modes are taken as their quasi-static response to the ground, "
                  "R a_g(t) (residual flexibility, added to every displacement the run forms: gaps, impacts, "
                  "outputs). An approximation, not the exact path: what it neglects is in docs/model.md (\"Modal "
                  "truncation\"), and `pounding study` measures its error on the scene (`truncation.csv`). A "
                  "cut-off that keeps no mode of a building is refused"},
      {.id = Setting::dt_s,
       .key = "dt_s",
       .option = "--dt",
       .member = member(&SolverSettings::dt_s, &UsedSettings::dt_s),
       .default_value = 0.05,  // the published value
       .range = Range{0.0, 0.1, "s", true},
       .description = "fixed time step (s)",
       .details = "when not given: 0.05 s, or the record's sample spacing if that is shorter. A step longer than "
                  "the spacing sees the record only at its ends, so the run answers for a record with the samples "
                  "between left out; such a run carries the warning `record_undersampled`"},
      {.id = Setting::alpha,
       .key = "alpha",
       .option = "--alpha",
       .member = member(&SolverSettings::alpha, &UsedSettings::alpha),
       .default_value = -0.05,
       .range = Range{-1.0 / 3.0, 0.0, {}, false, "[-1/3, 0]"},
       .description = "HHT alpha in [-1/3, 0]",
       .details = "β = (1 − α)²/4, γ = (1 − 2α)/2"},
      {.id = Setting::contact_tolerance_m,
       .key = "contact_tolerance_m",
       .option = "--contact-tol",
       .member = member(&SolverSettings::contact_tolerance_m, &UsedSettings::contact_tolerance_m),
       .default_value = 1e-4,
       .range = Range{0.0, 0.01, "m", true},
       .description = "gap that counts as contact (m)",
       .details = "an approaching pair in this band takes an impact once it touches (g ≤ 0) or would within a step, "
                  "and a pair deeper than it ends the run as `unresolved_overlap`"},
      {.id = Setting::max_halvings,
       .key = "max_halvings",
       .option = "--max-halvings",
       .member = member(&SolverSettings::max_halvings, &UsedSettings::max_halvings),
       .default_value = 30,
       .range = Range{0, 60},
       .description = "deepest step halving"},
      {.id = Setting::event_location,
       .key = "event_location",
       .option = "--event-location",
       .member = member(&SolverSettings::event_location, &UsedSettings::event_location),
       .default_value = std::string("halving"),
       .choices = {"halving", "end-of-step", "interpolate"},
       .description = "halving, end-of-step or interpolate",
       .details = "how the contact instant is found (`--halving off` is `end-of-step`)"},
      {.id = Setting::max_events_per_s,
       .key = "max_events_per_s",
       .option = "--max-events-per-s",
       .member = member(&SolverSettings::max_events_per_s, &UsedSettings::max_events_per_s),
       .default_value = 2000.0,
       .range = Range{1.0, 1e7, "1/s"},
       .description = "events (impacts, holds, releases, touches) allowed within one simulated second",
       .details = "more within any one second of the record stops the run with status `event_limit`: an "
                  "accumulation the contact rules did not resolve. Raise it for a scene that really has that many "
                  "(a long row of slabs chattering), lower it to stop a runaway run early"},
  };
  return kSpecs;
}

solvers::NewtonSolver newton_solver(const UsedSettings& used) {
  return used.newton == "dense" ? solvers::NewtonSolver::dense : solvers::NewtonSolver::second_order;
}

/// The per-component atol of `used` on `system` (resolve() sets it for every method with atol).
Eigen::VectorXd atol_vector(const UsedSettings& used, const dynamics::CoupledSystem& system) {
  return used.atol_components ? used.atol_components->vector(system) : Eigen::VectorXd();
}

/// `make(functions, settings, t0, y0)` on the physical state; for form "modal" on the modal
/// coordinates behind a ModalIntegrator, its atol vector mapped by ModalSystem::atol; for form
/// "deviation" on the deviation from the free response behind a DeviationIntegrator (atol as is:
/// the deviation is in the units of y).
template <typename Settings, typename Make>
solvers::IntegratorFactory in_form(const UsedSettings& used, const dynamics::CoupledSystem& system, Settings settings,
                                   Make make) {
  std::shared_ptr<const dynamics::ModalSystem> modes;
  if (used.form != "physical") modes = std::make_shared<const dynamics::ModalSystem>(system);
  if (used.form == "modal") {
    const Eigen::VectorXd physical_atol = settings.atol_vector.size()
                                              ? settings.atol_vector
                                              : Eigen::VectorXd::Constant(system.state_size(), settings.atol);
    settings.atol_vector = modes->atol(physical_atol);
  }
  solvers::IntegratorFactory inner = [settings, make](solvers::OdeFunctions& functions, double t0,
                                                      const Eigen::VectorXd& y0) -> IntegratorPtr {
    return make(functions, settings, t0, y0);
  };
  if (!modes) return inner;
  if (used.form == "deviation") {
    return [modes, inner](solvers::OdeFunctions& functions, double t0, const Eigen::VectorXd& y0) -> IntegratorPtr {
      return std::make_unique<solvers::DeviationIntegrator>(*modes, functions, inner, t0, y0);
    };
  }
  return [modes, inner](solvers::OdeFunctions& functions, double t0, const Eigen::VectorXd& y0) -> IntegratorPtr {
    return std::make_unique<solvers::ModalIntegrator>(*modes, functions, inner, t0, y0);
  };
}

template <solvers::CvodeMethod kMethod>
solvers::IntegratorFactory cvode_factory(const UsedSettings& used, const dynamics::CoupledSystem& system) {
  const solvers::CvodeSettings settings{.method = kMethod,
                                        .rtol = used.rtol,
                                        .atol = used.atol,
                                        .newton_solver = newton_solver(used),
                                        .atol_vector = atol_vector(used, system)};
  return in_form(used, system, settings,
                 [](solvers::OdeFunctions& functions, const solvers::CvodeSettings& s, double t0,
                    const Eigen::VectorXd& y0) -> IntegratorPtr {
                   return std::make_unique<solvers::CvodeIntegrator>(functions, s, t0, y0);
                 });
}

template <solvers::ArkodeMethod kMethod>
solvers::IntegratorFactory arkode_factory(const UsedSettings& used, const dynamics::CoupledSystem& system) {
  const solvers::ArkodeSettings settings{.method = kMethod,
                                         .rtol = used.rtol,
                                         .atol = used.atol,
                                         .order = used.order,
                                         .newton_solver = newton_solver(used),
                                         .atol_vector = atol_vector(used, system)};
  return in_form(used, system, settings,
                 [](solvers::OdeFunctions& functions, const solvers::ArkodeSettings& s, double t0,
                    const Eigen::VectorXd& y0) { return solvers::make_arkode_integrator(functions, s, t0, y0); });
}

solvers::IntegratorFactory exact_factory(const UsedSettings& used, const dynamics::CoupledSystem& system) {
  const solvers::ExactSettings settings{.hold_rtol = used.hold_rtol,
                                        .hold_atol = used.hold_rtol / 100,
                                        .hold_atol_vector = atol_vector(used, system),
                                        .modes_cutoff_hz = used.modes_cutoff_hz};
  // Rayleigh damping is classical, so free flight runs in modal form (ModalExactIntegrator).
  return [settings, &system](solvers::OdeFunctions& functions, double t0, const Eigen::VectorXd& y0) -> IntegratorPtr {
    return std::make_unique<solvers::ModalExactIntegrator>(functions, system, t0, y0, settings);
  };
}

const std::vector<double> kRtolLadder{1e-4, 1e-6, 1e-8, 1e-10, 1e-12}, kQuickRtolLadder{1e-6, 1e-8};
const std::vector<double> kDtLadder{0.05, 0.01, 0.002, 0.0005}, kQuickDtLadder{0.05, 0.01};
using enum Setting;

const std::vector<MethodInfo> kMethods = {
    {.name = "cvode-bdf",
     .description = "CVODE BDF (orders 1-5), event-driven: stiff-safe, the default",
     .settings = {rtol, atol, newton, form, max_events_per_s},
     .factory = cvode_factory<solvers::CvodeMethod::bdf>,
     .yielding_columns = true,
     .ladder = kRtolLadder,
     .quick_ladder = kQuickRtolLadder,
     .series = {{"cvode-bdf", "", {"tab:blue", "o"}}}},
    {.name = "cvode-adams",
     .description = "CVODE Adams-Moulton (orders 1-12) with Newton iterations, event-driven",
     .settings = {rtol, atol, newton, form, max_events_per_s},
     .factory = cvode_factory<solvers::CvodeMethod::adams>,
     .yielding_columns = true,
     .ladder = kRtolLadder,
     .quick_ladder = kQuickRtolLadder,
     .series = {{"cvode-adams", "", {"tab:cyan", "s"}}}},
    {.name = "arkode-erk",
     .description = "ARKODE explicit Runge-Kutta, Dormand-Prince 5(4), event-driven: no linear algebra",
     .settings = {order, rtol, atol, form, max_events_per_s},
     .orders = {5},
     .factory = arkode_factory<solvers::ArkodeMethod::erk>,
     .yielding_columns = true,
     .ladder = kRtolLadder,
     .quick_ladder = kQuickRtolLadder,
     .series = {{"arkode-erk", "", {"tab:green", "^"}}}},
    {.name = "arkode-dirk",
     .description = "ARKODE diagonally implicit Runge-Kutta, SDIRK 5-3-4 or Kvaerno 4-2-3, event-driven",
     .settings = {order, rtol, atol, newton, form, max_events_per_s},
     .orders = {4, 3},
     .factory = arkode_factory<solvers::ArkodeMethod::dirk>,
     .yielding_columns = true,
     .ladder = kRtolLadder,
     .quick_ladder = kQuickRtolLadder,
     .series = {{"arkode-dirk", "", {"tab:olive", "v"}}}},
    {.name = "hht",
     .description = "HHT-alpha with fixed steps and step halving at contact: the published scheme",
     .settings = {dt_s, alpha, contact_tolerance_m, max_halvings, event_location},
     .event_driven = false,
     .ladder_setting = dt_s,
     .ladder = kDtLadder,
     .quick_ladder = kQuickDtLadder,
     .series = {{"hht-halving", "halving", {"tab:red", "D"}},
                {"hht-end-of-step", "end-of-step", {"tab:orange", "x"}},
                {"hht-interpolate", "interpolate", {"tab:purple", "P"}}}},
    {.name = "exact",
     .description = "exact propagator of free flight in modal form, held contacts by CVODE BDF: the ground truth",
     .settings = {hold_rtol, modes_cutoff_hz, max_events_per_s},
     .factory = exact_factory,
     .steps_per_period = kExactSubdivisionsPerPeriod,
     .clearance_steps = true,
     .reference = true},
};

std::string quoted(const std::string& text) { return "\"" + text + "\""; }

std::string text_of(const SettingValue& value) {
  return std::visit([](const auto& v) { return fmt::format("{}", v); }, value);
}

/// The value of `setting` in `given`, if given.
std::optional<SettingValue> given_value(const SolverSettings& given, Setting setting) {
  return std::visit(
      [&](const auto& m) -> std::optional<SettingValue> {
        if (!(given.*m.given)) return std::nullopt;
        return SettingValue(*(given.*m.given));
      },
      spec(setting).member);
}

SettingValue used_value(const UsedSettings& used, Setting setting) {
  return std::visit([&](const auto& m) { return SettingValue(used.*m.used); }, spec(setting).member);
}

void clear(SolverSettings& given, Setting setting) {
  std::visit([&](const auto& m) { (given.*m.given).reset(); }, spec(setting).member);
}

std::string key_of(Setting setting) { return "solver." + std::string(spec(setting).key); }

std::string keys_of(const MethodInfo& info) {
  std::vector<std::string_view> keys;
  for (Setting s : info.settings) keys.push_back(spec(s).key);
  return keys.empty() ? "none" : fmt::format("{}", fmt::join(keys, ", "));
}

std::string or_list(const std::vector<std::string>& words) {
  if (words.size() < 2) return words.empty() ? "" : words.front();
  return fmt::format("{} or {}", fmt::join(words.begin(), words.end() - 1, ", "), words.back());
}

/// The range rule of each setting (applicability is checked before).
void validate_value(const MethodInfo& info, const SettingSpec& s, const SettingValue& value) {
  if (s.id == order) {
    const int given = std::get<int>(value);
    if (std::find(info.orders.begin(), info.orders.end(), given) == info.orders.end()) {
      std::vector<std::string> offered;
      for (int o : info.orders) offered.push_back(std::to_string(o));
      throw InputError(key_of(order), std::to_string(given),
                       fmt::format("{} offers order {}", info.name, or_list(offered)));
    }
  } else if (const auto* text = std::get_if<std::string>(&value)) {
    if (std::find(s.choices.begin(), s.choices.end(), *text) == s.choices.end()) {
      throw InputError(key_of(s.id), quoted(*text), "expected " + or_list(s.choices));
    }
  } else {
    require_range(key_of(s.id), std::holds_alternative<int>(value) ? std::get<int>(value) : std::get<double>(value),
                  *s.range);
  }
}

}  // namespace

std::span<const SettingSpec> setting_specs() { return specs(); }

const SettingSpec& spec(Setting setting) { return specs()[static_cast<std::size_t>(setting)]; }

std::span<const MethodInfo> methods() { return kMethods; }

const MethodInfo* find_method(std::string_view name) {
  for (const MethodInfo& info : kMethods) {
    if (info.name == name) return &info;
  }
  return nullptr;
}

const MethodInfo& reference_method() {
  return *std::find_if(kMethods.begin(), kMethods.end(), [](const MethodInfo& info) { return info.reference; });
}

std::string method_names() {
  std::vector<std::string> names;
  for (const MethodInfo& info : kMethods) names.emplace_back(info.name);
  return or_list(names);
}

const MethodInfo& method_info(std::string_view name, const std::string& key) {
  if (const MethodInfo* info = find_method(name)) return *info;
  throw InputError(key, quoted(std::string(name)), "expected " + method_names());
}

bool applies(const MethodInfo& method, Setting setting) {
  return std::find(method.settings.begin(), method.settings.end(), setting) != method.settings.end();
}

bool SolverSettings::given(Setting setting) const { return given_value(*this, setting).has_value(); }

void SolverSettings::validate() const {
  const MethodInfo& info = method_info(method);
  for (const SettingSpec& s : specs()) {
    const std::optional<SettingValue> value = given_value(*this, s.id);
    if (!value) continue;
    if (!applies(info, s.id)) {
      const std::string text = std::holds_alternative<std::string>(*value) ? quoted(text_of(*value)) : text_of(*value);
      throw InputError(key_of(s.id), text,
                       fmt::format("does not apply to method {} (it uses {})", info.name, keys_of(info)));
    }
    validate_value(info, s, *value);
  }
}

SolverSettings with_method(const SolverSettings& given, std::string_view method) {
  const MethodInfo& info = method_info(method);
  SolverSettings result = given;
  result.method = std::string(method);
  for (const SettingSpec& s : specs()) {
    const std::optional<SettingValue> value = given_value(given, s.id);
    if (!value) continue;
    const bool usable =
        applies(info, s.id) && (s.id != order || std::count(info.orders.begin(), info.orders.end(), *given.order));
    if (usable) continue;
    result.not_used[std::string(s.key)] = text_of(*value);
    clear(result, s.id);
  }
  return result;
}

/// hht's step when none is given: the published 0.05 s, or the record's sample spacing where that
/// is shorter. A longer step sees the record only at its ends and leaves out the samples between.
/// A spacing that is a short decimal up to round-off (0.019999999999999997) is taken as that decimal.
double default_dt_s(const dynamics::CoupledSystem& system, double published_s) {
  const double spacing_s = system.ground_motion().sample_spacing_s();
  if (!(spacing_s < published_s * (1.0 - 1e-9))) return published_s;
  const double decimal_s = std::stod(fmt::format("{:.6g}", spacing_s));
  return std::abs(decimal_s - spacing_s) <= 1e-9 * spacing_s ? decimal_s : spacing_s;
}

UsedSettings resolve(const SolverSettings& given, const dynamics::CoupledSystem* system) {
  UsedSettings used;
  used.method = &method_info(given.method);
  used.order = used.method->orders.empty() ? 0 : given.order.value_or(used.method->orders.front());
  for (const SettingSpec& s : specs()) {
    if (s.id == order) continue;
    std::visit(
        [&](const auto& m) {
          using T = std::decay_t<decltype(used.*m.used)>;
          used.*m.used = (given.*m.given).value_or(std::get<T>(s.default_value));
        },
        s.member);
  }
  if (system) {
    if (applies(*used.method, dt_s) && !given.dt_s) used.dt_s = default_dt_s(*system, used.dt_s);
    if (applies(*used.method, atol)) used.atol_components = component_atol(*system, used.atol);
    if (applies(*used.method, hold_rtol)) used.atol_components = component_atol(*system, used.hold_rtol / 100);
  }
  return used;
}

std::vector<SettingEntry> given_entries(const SolverSettings& given) {
  std::vector<SettingEntry> entries;
  for (const SettingSpec& s : specs()) {
    if (auto value = given_value(given, s.id)) entries.push_back({s.key, std::move(*value)});
  }
  return entries;
}

std::vector<SettingEntry> used_entries(const UsedSettings& used) {
  std::vector<SettingEntry> entries;
  for (Setting s : used.method->settings) entries.push_back({spec(s).key, used_value(used, s)});
  return entries;
}

std::string describe_used_settings(const UsedSettings& used) {
  std::vector<std::string> parts;
  for (const SettingEntry& entry : used_entries(used)) {
    std::string part = fmt::format("{} {}", entry.key, text_of(entry.value));
    if (entry.key == "atol" && used.atol_components) {
      const ComponentAtol& c = *used.atol_components;
      part += fmt::format(" m (phi {:.3g} rad, rates x {:.3g}/s)", fmt::join(c.rotation_rad, "/"), c.rate_per_s);
    }
    parts.push_back(std::move(part));
  }
  return fmt::format("{}", fmt::join(parts, ", "));
}

std::string option_help(Setting setting) {
  std::vector<std::string> users;
  for (const MethodInfo& info : kMethods) {
    if (applies(info, setting)) users.emplace_back(info.name);
  }
  return fmt::format("{}: {} (default {})", fmt::join(users, ", "), spec(setting).description,
                     setting == order ? "the method's first" : text_of(spec(setting).default_value));
}

std::string_view type_name(const SettingSpec& s) {
  constexpr std::string_view kNames[] = {"integer", "number", "string"};
  return kNames[s.member.index()];
}

std::string expected_text(const SettingSpec& s) {
  return fmt::format("{} {}", s.member.index() == 0 ? "an" : "a", type_name(s));
}

std::string accepted_text(const SettingSpec& s) {
  if (s.id == order) return "the method's table orders";
  if (!s.choices.empty()) return or_list(s.choices);
  if (s.member.index() == 0) return fmt::format("{}..{}", s.range->min, s.range->max);  // integers
  return range_text(*s.range);
}

std::string default_text(const SettingSpec& s) {
  if (s.id == order) return "the method's first";
  if (const auto* text = std::get_if<std::string>(&s.default_value)) return quoted(*text);
  return text_of(s.default_value);
}

void SolverSettings::set(Setting setting, const SettingValue& value) {
  const SettingSpec& s = spec(setting);
  std::visit(
      [&](const auto& m) {
        using T = typename std::decay_t<decltype(this->*m.given)>::value_type;
        if (const T* same = std::get_if<T>(&value)) {
          this->*m.given = *same;
          return;
        }
        if constexpr (std::is_same_v<T, double>) {  // a whole number is a number
          if (const int* whole = std::get_if<int>(&value)) {
            this->*m.given = *whole;
            return;
          }
        }
        const bool text = std::holds_alternative<std::string>(value);
        throw InputError(key_of(setting), text ? quoted(text_of(value)) : text_of(value),
                         "expected " + expected_text(s));
      },
      s.member);
}

std::string methods_help() {
  return fmt::format("Solution path: {} (default {}; `pounding methods` describes each)", method_names(),
                     kMethods.front().name);
}

ComponentAtol component_atol(const dynamics::CoupledSystem& system, double atol_m) {
  ComponentAtol result;
  result.displacement_m = atol_m;
  double lowest_omega = std::numeric_limits<double>::infinity();
  for (int b = 0; b < system.building_count(); ++b) {
    const model::BuildingDefinition& d = system.building(b).definition;
    double farthest_m = 0.0;
    for (const model::Point2& corner : d.slab.vertices())
      farthest_m = std::max(farthest_m, (corner - d.centre_of_mass).norm());
    result.rotation_rad.push_back(atol_m / farthest_m);
    lowest_omega = std::min(lowest_omega, system.building(b).modes.front().omega_rad_s);
  }
  result.rate_per_s = lowest_omega;
  return result;
}

Eigen::VectorXd ComponentAtol::vector(const dynamics::CoupledSystem& system) const {
  const int n = system.dof();
  Eigen::VectorXd atol(system.state_size());
  for (int b = 0; b < system.building_count(); ++b) {
    for (int floor = 1; floor <= system.building(b).storeys(); ++floor) {
      const int i = system.floor_index(b, floor);
      atol.segment<3>(i) << displacement_m, displacement_m, rotation_rad[static_cast<std::size_t>(b)];
      atol.segment<3>(n + i) = rate_per_s * atol.segment<3>(i);
    }
  }
  // A Bouc–Wen z moves the column's force as a drift d_y z would.
  for (const dynamics::YieldingSpring& spring : system.springs().all()) {
    if (spring.bouc_wen) atol[spring.z_index] = displacement_m / spring.yield_drift_m;
  }
  return atol;
}

}  // namespace pounding::analysis
