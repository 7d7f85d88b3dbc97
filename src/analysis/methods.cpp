#include "pounding/analysis/methods.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "pounding/dynamics/coupled_system.hpp"
#include "pounding/dynamics/modal_system.hpp"
#include "pounding/input_error.hpp"
#include "pounding/model/mode.hpp"
#include "pounding/solvers/arkode_integrator.hpp"
#include "pounding/solvers/cvode_integrator.hpp"
#include "pounding/solvers/exact_integrator.hpp"
#include "pounding/solvers/modal_exact_integrator.hpp"
#include "pounding/solvers/modal_integrator.hpp"

namespace pounding::analysis {
namespace {

using IntegratorPtr = std::unique_ptr<solvers::Integrator>;

// Ranges of the settings (docs/scene-format.md lists each next to its key).
constexpr Range kRtol{1e-14, 0.1};                         // below 1e-14 is under round-off
constexpr Range kAtol{1e-16, 1e-3, "m"};
// Held stretches of the exact path: tighter than 1e-14 is under round-off; looser than 1e-6
// would make the ground truth less accurate than the paths it judges.
constexpr Range kHoldRtol{1e-14, 1e-6};
// Modal truncation of the exact path: 0 is off; above 1e4 Hz no building model has modes to drop.
constexpr Range kModesCutoff{0.0, 1e4, "Hz"};
constexpr Range kHhtStep{0.0, 0.1, "s", true};             // published 0.05 s
constexpr Range kHhtContactTolerance{0.0, 0.01, "m", true};
constexpr int kMaxHalvings = 60;                           // 0.05 s / 2⁶⁰ is below round-off of t
const std::vector<std::string> kNewtonSolvers{"reduced", "dense"};
const std::vector<std::string> kForms{"physical", "modal"};
const std::vector<std::string> kEventLocations{"halving", "end-of-step", "interpolate"};
// Root bracketing of the exact path: a subdivision fine against the shortest period that moves a gap.
constexpr double kExactSubdivisionsPerPeriod = 16.0;

constexpr SettingSpec kSpecs[] = {
    {Setting::order, "order", "--order", "ARKODE table order"},
    {Setting::rtol, "rtol", "--rtol", "relative tolerance"},
    {Setting::atol, "atol", "--atol",
     "absolute tolerance of the slab displacements (m); rotations and rates derive from it"},
    {Setting::newton, "newton", "--newton", "Newton linear solver: reduced (n x n) or dense (2n x 2n LU)"},
    {Setting::form, "form", "--form",
     "state integrated: physical (q, q') or modal (each building's modal coordinates)"},
    {Setting::hold_rtol, "hold_rtol", "--hold-rtol", "relative tolerance of held stretches (CVODE BDF)"},
    {Setting::modes_cutoff_hz, "modes_cutoff_hz", "--modes-cutoff",
     "keep each building's modes below this frequency (Hz), the rest as their static response; 0: every mode"},
    {Setting::dt_s, "dt_s", "--dt", "fixed time step (s)"},
    {Setting::alpha, "alpha", "--alpha", "HHT alpha in [-1/3, 0]"},
    {Setting::contact_tolerance_m, "contact_tolerance_m", "--contact-tol", "gap that counts as contact (m)"},
    {Setting::max_halvings, "max_halvings", "--max-halvings", "deepest step halving"},
    {Setting::event_location, "event_location", "--event-location", "halving, end-of-step or interpolate"},
};

solvers::NewtonSolver newton_solver(const UsedSettings& used) {
  return used.newton == "dense" ? solvers::NewtonSolver::dense : solvers::NewtonSolver::second_order;
}

/// The per-component atol of `used` on `system` (resolve() sets it for every method with atol).
Eigen::VectorXd atol_vector(const UsedSettings& used, const dynamics::CoupledSystem& system) {
  return used.atol_components ? used.atol_components->vector(system) : Eigen::VectorXd();
}

/// `make(functions, settings, t0, y0)` on the physical state, or for form "modal" on the modal
/// coordinates behind a ModalIntegrator, its atol vector mapped by ModalSystem::atol.
template <typename Settings, typename Make>
solvers::IntegratorFactory in_form(const UsedSettings& used, const dynamics::CoupledSystem& system, Settings settings,
                                   Make make) {
  std::shared_ptr<const dynamics::ModalSystem> modes;
  if (used.form == "modal") {
    modes = std::make_shared<const dynamics::ModalSystem>(system);
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
  return [modes, inner](solvers::OdeFunctions& functions, double t0, const Eigen::VectorXd& y0) -> IntegratorPtr {
    return std::make_unique<solvers::ModalIntegrator>(*modes, functions, inner, t0, y0);
  };
}

template <solvers::CvodeMethod kMethod>
solvers::IntegratorFactory cvode_factory(const UsedSettings& used, const dynamics::CoupledSystem& system) {
  const solvers::CvodeSettings settings{.method = kMethod, .rtol = used.rtol, .atol = used.atol,
                                        .newton_solver = newton_solver(used), .atol_vector = atol_vector(used, system)};
  return in_form(used, system, settings,
                 [](solvers::OdeFunctions& functions, const solvers::CvodeSettings& s, double t0,
                    const Eigen::VectorXd& y0) -> IntegratorPtr {
                   return std::make_unique<solvers::CvodeIntegrator>(functions, s, t0, y0);
                 });
}

template <solvers::ArkodeMethod kMethod>
solvers::IntegratorFactory arkode_factory(const UsedSettings& used, const dynamics::CoupledSystem& system) {
  const solvers::ArkodeSettings settings{.method = kMethod, .rtol = used.rtol, .atol = used.atol,
                                         .order = used.order, .newton_solver = newton_solver(used),
                                         .atol_vector = atol_vector(used, system)};
  return in_form(used, system, settings,
                 [](solvers::OdeFunctions& functions, const solvers::ArkodeSettings& s, double t0,
                    const Eigen::VectorXd& y0) { return solvers::make_arkode_integrator(functions, s, t0, y0); });
}

solvers::IntegratorFactory exact_factory(const UsedSettings& used, const dynamics::CoupledSystem& system) {
  const solvers::ExactSettings settings{.hold_rtol = used.hold_rtol, .hold_atol = used.hold_rtol / 100,
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
     .settings = {rtol, atol, newton, form},
     .factory = cvode_factory<solvers::CvodeMethod::bdf>,
     .ladder = kRtolLadder, .quick_ladder = kQuickRtolLadder,
     .series = {{"cvode-bdf", "", {"tab:blue", "o"}}}},
    {.name = "cvode-adams",
     .description = "CVODE Adams-Moulton (orders 1-12) with Newton iterations, event-driven",
     .settings = {rtol, atol, newton, form},
     .factory = cvode_factory<solvers::CvodeMethod::adams>,
     .ladder = kRtolLadder, .quick_ladder = kQuickRtolLadder,
     .series = {{"cvode-adams", "", {"tab:cyan", "s"}}}},
    {.name = "arkode-erk",
     .description = "ARKODE explicit Runge-Kutta, Dormand-Prince 5(4), event-driven: no linear algebra",
     .settings = {order, rtol, atol, form},
     .orders = {5},
     .factory = arkode_factory<solvers::ArkodeMethod::erk>,
     .ladder = kRtolLadder, .quick_ladder = kQuickRtolLadder,
     .series = {{"arkode-erk", "", {"tab:green", "^"}}}},
    {.name = "arkode-dirk",
     .description = "ARKODE diagonally implicit Runge-Kutta, SDIRK 5-3-4 or Kvaerno 4-2-3, event-driven",
     .settings = {order, rtol, atol, newton, form},
     .orders = {4, 3},
     .factory = arkode_factory<solvers::ArkodeMethod::dirk>,
     .ladder = kRtolLadder, .quick_ladder = kQuickRtolLadder,
     .series = {{"arkode-dirk", "", {"tab:olive", "v"}}}},
    {.name = "hht",
     .description = "HHT-alpha with fixed steps and step halving at contact: the published scheme",
     .settings = {dt_s, alpha, contact_tolerance_m, max_halvings, event_location},
     .event_driven = false,
     .ladder_setting = dt_s, .ladder = kDtLadder, .quick_ladder = kQuickDtLadder,
     .series = {{"hht-halving", "halving", {"tab:red", "D"}},
                {"hht-end-of-step", "end-of-step", {"tab:orange", "x"}},
                {"hht-interpolate", "interpolate", {"tab:purple", "P"}}}},
    {.name = "exact",
     .description = "exact propagator of free flight in modal form, held contacts by CVODE BDF: the ground truth",
     .settings = {hold_rtol, modes_cutoff_hz},
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
  auto value = [](const auto& optional) -> std::optional<SettingValue> {
    if (!optional) return std::nullopt;
    return SettingValue(*optional);
  };
  switch (setting) {
    case order: return value(given.order);
    case rtol: return value(given.rtol);
    case atol: return value(given.atol);
    case newton: return value(given.newton);
    case form: return value(given.form);
    case hold_rtol: return value(given.hold_rtol);
    case modes_cutoff_hz: return value(given.modes_cutoff_hz);
    case dt_s: return value(given.dt_s);
    case alpha: return value(given.alpha);
    case contact_tolerance_m: return value(given.contact_tolerance_m);
    case max_halvings: return value(given.max_halvings);
    case event_location: return value(given.event_location);
  }
  return std::nullopt;
}

SettingValue used_value(const UsedSettings& used, Setting setting) {
  switch (setting) {
    case order: return used.order;
    case rtol: return used.rtol;
    case atol: return used.atol;
    case newton: return used.newton;
    case form: return used.form;
    case hold_rtol: return used.hold_rtol;
    case modes_cutoff_hz: return used.modes_cutoff_hz;
    case dt_s: return used.dt_s;
    case alpha: return used.alpha;
    case contact_tolerance_m: return used.contact_tolerance_m;
    case max_halvings: return used.max_halvings;
    case event_location: return used.event_location;
  }
  return 0;
}

void clear(SolverSettings& given, Setting setting) {
  switch (setting) {
    case order: given.order.reset(); break;
    case rtol: given.rtol.reset(); break;
    case atol: given.atol.reset(); break;
    case newton: given.newton.reset(); break;
    case form: given.form.reset(); break;
    case hold_rtol: given.hold_rtol.reset(); break;
    case modes_cutoff_hz: given.modes_cutoff_hz.reset(); break;
    case dt_s: given.dt_s.reset(); break;
    case alpha: given.alpha.reset(); break;
    case contact_tolerance_m: given.contact_tolerance_m.reset(); break;
    case max_halvings: given.max_halvings.reset(); break;
    case event_location: given.event_location.reset(); break;
  }
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

void require_one_of(Setting setting, const std::string& value, const std::vector<std::string>& choices) {
  if (std::find(choices.begin(), choices.end(), value) == choices.end()) {
    throw InputError(key_of(setting), quoted(value), "expected " + or_list(choices));
  }
}

/// The range rule of each setting (applicability is checked before).
void validate_value(const MethodInfo& info, const SolverSettings& given, Setting setting) {
  switch (setting) {
    case order:
      if (std::find(info.orders.begin(), info.orders.end(), *given.order) == info.orders.end()) {
        std::vector<std::string> offered;
        for (int o : info.orders) offered.push_back(std::to_string(o));
        throw InputError(key_of(order), std::to_string(*given.order),
                         fmt::format("{} offers order {}", info.name, or_list(offered)));
      }
      return;
    case rtol: return require_range(key_of(rtol), *given.rtol, kRtol);
    case atol: return require_range(key_of(atol), *given.atol, kAtol);
    case newton: return require_one_of(newton, *given.newton, kNewtonSolvers);
    case form: return require_one_of(form, *given.form, kForms);
    case hold_rtol: return require_range(key_of(hold_rtol), *given.hold_rtol, kHoldRtol);
    case modes_cutoff_hz: return require_range(key_of(modes_cutoff_hz), *given.modes_cutoff_hz, kModesCutoff);
    case dt_s: return require_range(key_of(dt_s), *given.dt_s, kHhtStep);
    case alpha:
      if (!(*given.alpha >= -1.0 / 3.0 && *given.alpha <= 0.0)) {
        throw InputError(key_of(alpha), format_value(*given.alpha), "must lie in [-1/3, 0]");
      }
      return;
    case contact_tolerance_m:
      return require_range(key_of(contact_tolerance_m), *given.contact_tolerance_m, kHhtContactTolerance);
    case max_halvings:
      if (*given.max_halvings < 0 || *given.max_halvings > kMaxHalvings) {
        throw InputError(key_of(max_halvings), std::to_string(*given.max_halvings),
                         fmt::format("must lie in 0..{}", kMaxHalvings));
      }
      return;
    case event_location: return require_one_of(event_location, *given.event_location, kEventLocations);
  }
}

}  // namespace

std::span<const SettingSpec> setting_specs() { return kSpecs; }

const SettingSpec& spec(Setting setting) { return kSpecs[static_cast<std::size_t>(setting)]; }

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
  for (const SettingSpec& s : kSpecs) {
    const std::optional<SettingValue> value = given_value(*this, s.id);
    if (!value) continue;
    if (!applies(info, s.id)) {
      const std::string text = std::holds_alternative<std::string>(*value) ? quoted(text_of(*value)) : text_of(*value);
      throw InputError(key_of(s.id), text,
                       fmt::format("does not apply to method {} (it uses {})", info.name, keys_of(info)));
    }
    validate_value(info, *this, s.id);
  }
}

SolverSettings with_method(const SolverSettings& given, std::string_view method) {
  const MethodInfo& info = method_info(method);
  SolverSettings result = given;
  result.method = std::string(method);
  for (const SettingSpec& s : kSpecs) {
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

UsedSettings resolve(const SolverSettings& given, const dynamics::CoupledSystem* system) {
  UsedSettings used;
  used.method = &method_info(given.method);
  used.order = used.method->orders.empty() ? 0 : given.order.value_or(used.method->orders.front());
  used.rtol = given.rtol.value_or(used.rtol);
  used.atol = given.atol.value_or(used.atol);
  used.newton = given.newton.value_or(used.newton);
  used.form = given.form.value_or(used.form);
  used.hold_rtol = given.hold_rtol.value_or(used.hold_rtol);
  used.modes_cutoff_hz = given.modes_cutoff_hz.value_or(used.modes_cutoff_hz);
  used.dt_s = given.dt_s.value_or(used.dt_s);
  used.alpha = given.alpha.value_or(used.alpha);
  used.contact_tolerance_m = given.contact_tolerance_m.value_or(used.contact_tolerance_m);
  used.max_halvings = given.max_halvings.value_or(used.max_halvings);
  used.event_location = given.event_location.value_or(used.event_location);
  if (system) {
    if (applies(*used.method, atol)) used.atol_components = component_atol(*system, used.atol);
    if (applies(*used.method, hold_rtol)) used.atol_components = component_atol(*system, used.hold_rtol / 100);
  }
  return used;
}

std::vector<SettingEntry> given_entries(const SolverSettings& given) {
  std::vector<SettingEntry> entries;
  for (const SettingSpec& s : kSpecs) {
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
      part += fmt::format(" m (phi {:.3g}/{:.3g} rad, rates x {:.3g}/s)", c.rotation_rad[0], c.rotation_rad[1],
                          c.rate_per_s);
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
  const std::string default_text =
      setting == order ? "the method's first" : text_of(used_value(UsedSettings{}, setting));
  return fmt::format("{}: {} (default {})", fmt::join(users, ", "), spec(setting).description, default_text);
}

std::string methods_help() {
  return fmt::format("Solution path: {} (default {}; `pounding methods` describes each)", method_names(),
                     kMethods.front().name);
}

ComponentAtol component_atol(const dynamics::CoupledSystem& system, double atol_m) {
  ComponentAtol result;
  result.displacement_m = atol_m;
  double lowest_omega = std::numeric_limits<double>::infinity();
  for (int b = 0; b < 2; ++b) {
    const model::BuildingDefinition& d = system.building(b).definition;
    double farthest_m = 0.0;
    for (const model::Point2& corner : d.slab.vertices()) farthest_m = std::max(farthest_m, (corner - d.centre_of_mass).norm());
    result.rotation_rad[static_cast<std::size_t>(b)] = atol_m / farthest_m;
    lowest_omega = std::min(lowest_omega, system.building(b).modes.front().omega_rad_s);
  }
  result.rate_per_s = lowest_omega;
  return result;
}

Eigen::VectorXd ComponentAtol::vector(const dynamics::CoupledSystem& system) const {
  const int n = system.dof();
  Eigen::VectorXd atol(system.state_size());
  for (int b = 0; b < 2; ++b) {
    for (int floor = 1; floor <= system.building(b).storeys(); ++floor) {
      const int i = system.floor_index(b, floor);
      atol.segment<3>(i) << displacement_m, displacement_m, rotation_rad[static_cast<std::size_t>(b)];
      atol.segment<3>(n + i) = rate_per_s * atol.segment<3>(i);
    }
  }
  return atol;
}

}  // namespace pounding::analysis
