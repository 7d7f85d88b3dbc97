#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <set>
#include <string>

#include "pounding/analysis/methods.hpp"
#include "pounding/analysis/run_scene.hpp"
#include "pounding/excitation/ground_motion.hpp"
#include "pounding/input_error.hpp"
#include "pounding/io/scene_reader.hpp"

using namespace pounding;
using analysis::Setting;
namespace tt = boost::test_tools;

namespace {

/// A value inside the documented range of `setting` that `method` would accept.
void give(analysis::SolverSettings& s, const analysis::MethodInfo& method, Setting setting) {
  switch (setting) {
    case Setting::order: s.order = method.orders.empty() ? 4 : method.orders.back(); break;
    case Setting::rtol: s.rtol = 1e-6; break;
    case Setting::atol: s.atol = 1e-9; break;
    case Setting::newton: s.newton = "dense"; break;
    case Setting::form: s.form = "modal"; break;
    case Setting::hold_rtol: s.hold_rtol = 1e-10; break;
    case Setting::modes_cutoff_hz: s.modes_cutoff_hz = 20.0; break;
    case Setting::dt_s: s.dt_s = 0.01; break;
    case Setting::alpha: s.alpha = -0.1; break;
    case Setting::contact_tolerance_m: s.contact_tolerance_m = 1e-3; break;
    case Setting::max_halvings: s.max_halvings = 10; break;
    case Setting::event_location: s.event_location = "interpolate"; break;
    case Setting::max_events_per_s: s.max_events_per_s = 500.0; break;
  }
}

std::string reason_of(const analysis::SolverSettings& s, std::string* key = nullptr) {
  try {
    s.validate();
  } catch (const InputError& error) {
    if (key) *key = error.key();
    return error.reason();
  }
  return "";
}

analysis::Scene paper() { return io::read_scene(POUNDING_EXAMPLES_DIR "/paper/paper.toml"); }

}  // namespace

BOOST_AUTO_TEST_CASE(EveryMethodHasAFactoryADescriptionSettingsAndALadder) {
  const dynamics::CoupledSystem system = analysis::build_system(paper());
  std::set<std::string_view> labels;
  int references = 0;
  for (const analysis::MethodInfo& method : analysis::methods()) {
    BOOST_TEST_CONTEXT(method.name) {
      BOOST_TEST(analysis::find_method(method.name) == &method);
      BOOST_TEST(!method.description.empty());
      BOOST_TEST(!method.settings.empty());
      BOOST_TEST(method.event_driven == (method.factory != nullptr));  // the rest run by run_hht
      if (method.factory) {
        analysis::SolverSettings given;
        given.method = std::string(method.name);
        BOOST_TEST(static_cast<bool>(method.factory(analysis::resolve(given, &system), system)));
      }
      BOOST_TEST(method.orders.empty() == !analysis::applies(method, Setting::order));
      for (std::size_t i = 1; i < method.settings.size(); ++i)
        BOOST_TEST((method.settings[i - 1] < method.settings[i]));
      if (method.reference) {
        ++references;
        BOOST_TEST(method.ladder.empty());  // the study measures the others against it
        continue;
      }
      BOOST_TEST(analysis::applies(method, method.ladder_setting));
      BOOST_TEST(!method.ladder.empty());
      BOOST_TEST(!method.quick_ladder.empty());
      BOOST_TEST(!method.series.empty());
      for (const analysis::StudySeries& series : method.series) {
        BOOST_TEST(labels.insert(series.label).second);  // one style per study line
        BOOST_TEST(!series.style.colour.empty());
        BOOST_TEST(!series.style.marker.empty());
      }
    }
  }
  BOOST_TEST(references == 1);
  BOOST_TEST(&analysis::reference_method() == analysis::find_method("exact"));
  for (const analysis::SettingSpec& spec : analysis::setting_specs()) {
    BOOST_TEST(&analysis::spec(spec.id) == &spec);
    BOOST_TEST(spec.option.starts_with("--"));
  }
}

BOOST_AUTO_TEST_CASE(ASettingTheMethodDoesNotUseIsRefusedNamingTheSettingAndTheMethod) {
  for (const analysis::MethodInfo& method : analysis::methods()) {
    for (const analysis::SettingSpec& spec : analysis::setting_specs()) {
      analysis::SolverSettings s;
      s.method = std::string(method.name);
      give(s, method, spec.id);
      std::string key;
      const std::string reason = reason_of(s, &key);
      BOOST_TEST_CONTEXT(method.name << " with " << spec.key) {
        if (analysis::applies(method, spec.id)) {
          BOOST_TEST(reason == "");
        } else {
          BOOST_TEST(key == "solver." + std::string(spec.key));
          BOOST_TEST(reason.find("does not apply to method " + std::string(method.name)) == 0);
        }
      }
    }
  }
  // The library refuses it too, before any work.
  analysis::Scene scene = paper();
  scene.solver.method = "hht";
  scene.solver.rtol = 1e-12;
  BOOST_CHECK_EXCEPTION(analysis::run_scene(scene), InputError, [](const InputError& e) {
    return e.key() == "solver.rtol" && e.reason().find("method hht") != std::string::npos;
  });
}

BOOST_AUTO_TEST_CASE(UnknownMethodsAndOrdersNameTheChoices) {
  analysis::SolverSettings s;
  s.method = "euler";
  BOOST_TEST(reason_of(s) == "expected cvode-bdf, cvode-adams, arkode-erk, arkode-dirk, hht or exact");
  s.method = "arkode-dirk";
  s.order = 5;
  BOOST_TEST(reason_of(s) == "arkode-dirk offers order 4 or 3");
  s.method = "arkode-erk";
  BOOST_TEST(reason_of(s) == "");
  s.order = 8;  // Fehlberg 13-7-8 was dropped (arkode_integrator.cpp says why)
  BOOST_TEST(reason_of(s) == "arkode-erk offers order 5");
}

BOOST_AUTO_TEST_CASE(UsedSettingsAreTheRealOnes) {
  analysis::SolverSettings s;
  s.method = "arkode-dirk";
  BOOST_TEST(analysis::resolve(s).order == 4);  // SDIRK 5-3-4, not "0 = default"
  s.order = 3;
  BOOST_TEST(analysis::resolve(s).order == 3);
  s = {};
  s.method = "arkode-erk";
  const analysis::UsedSettings erk = analysis::resolve(s);
  BOOST_TEST(erk.order == 5);
  std::set<std::string_view> keys;
  for (const auto& entry : analysis::used_entries(erk)) keys.insert(entry.key);
  BOOST_TEST((keys == std::set<std::string_view>{"order", "rtol", "atol", "form",
                                                 "max_events_per_s"}));  // no Newton iterations
  s = {};
  s.newton = "dense";
  const analysis::UsedSettings bdf = analysis::resolve(s);
  BOOST_TEST(bdf.newton == "dense");
  BOOST_TEST(bdf.order == 0);
  BOOST_TEST(analysis::describe_used_settings(bdf) ==
             "rtol 1e-08, atol 1e-10, newton dense, form physical, max_events_per_s 2000");
  BOOST_TEST(analysis::given_entries(s).size() == 1u);
  s.form = "modal";
  BOOST_TEST(analysis::resolve(s).form == "modal");
  s.form = "eigen";
  std::string key;
  BOOST_TEST(reason_of(s, &key) == "expected physical, modal or deviation");
  BOOST_TEST(key == "solver.form");
}

BOOST_AUTO_TEST_CASE(AnotherMethodKeepsTheSettingsItUsesAndListsTheRestAsNotUsed) {
  analysis::SolverSettings file;
  file.method = "hht";
  file.dt_s = 0.01;
  file.alpha = -0.1;
  const analysis::SolverSettings run = analysis::with_method(file, "exact");
  BOOST_TEST(run.method == "exact");
  BOOST_TEST(!run.dt_s.has_value());
  BOOST_TEST(!run.alpha.has_value());
  BOOST_TEST(run.not_used.size() == 2u);
  BOOST_TEST(run.not_used.at("dt_s") == "0.01");
  BOOST_TEST(reason_of(run) == "");
  analysis::SolverSettings dirk;
  dirk.method = "arkode-dirk";
  dirk.order = 3;
  dirk.rtol = 1e-6;
  const analysis::SolverSettings erk = analysis::with_method(dirk, "arkode-erk");
  BOOST_TEST(!erk.order.has_value());  // order 3 is no ERK table
  BOOST_TEST(erk.rtol.value_or(0.0) == 1e-6);
  BOOST_CHECK_THROW(analysis::with_method(dirk, "euler"), InputError);
}

BOOST_AUTO_TEST_CASE(AbsoluteTolerancesPerComponentAreWhatTheDocumentationSays) {
  const analysis::Scene scene = paper();
  const dynamics::CoupledSystem system = analysis::build_system(scene);
  const double atol_m = 1e-10;
  const analysis::ComponentAtol c = analysis::component_atol(system, atol_m);
  // Farthest corners from the CM, by hand from examples/paper/paper.toml: B1's (−24, 0) from
  // (−10.8, 11), B2's (28.2, 33) from (12.8, 19.25).
  const std::array<double, 2> farthest_m{std::hypot(13.2, 11.0), std::hypot(15.4, 13.75)};
  // ω₁: the lowest ω of K φ = ω² M φ over both buildings, solved here independently.
  double omega1 = INFINITY;
  for (int b = 0; b < 2; ++b) {
    const model::Building& building = system.building(b);
    const Eigen::MatrixXd mass = building.mass_diagonal.asDiagonal();
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(building.stiffness, mass);
    omega1 = std::min(omega1, std::sqrt(modes.eigenvalues().minCoeff()));
  }
  BOOST_TEST(c.displacement_m == atol_m);
  BOOST_TEST(c.rate_per_s == omega1, tt::tolerance(1e-9));
  for (std::size_t b = 0; b < 2; ++b) {
    BOOST_TEST(c.rotation_rad[b] == atol_m / farthest_m[b], tt::tolerance(1e-12));
    // Rotating the farthest corner by that angle moves it by atol.
    const Eigen::Vector2d arm = Eigen::Vector2d(farthest_m[b], 0.0);
    BOOST_TEST((Eigen::Rotation2Dd(c.rotation_rad[b]) * arm - arm).norm() == atol_m, tt::tolerance(1e-6));
  }
  const Eigen::VectorXd vector = c.vector(system);
  BOOST_TEST_REQUIRE(vector.size() == system.state_size());
  const int n = system.dof();
  for (int b = 0; b < 2; ++b) {
    for (int floor = 1; floor <= system.building(b).storeys(); ++floor) {
      const int i = system.floor_index(b, floor);
      const double phi = atol_m / farthest_m[static_cast<std::size_t>(b)];
      BOOST_TEST(vector[i] == atol_m);
      BOOST_TEST(vector[i + 1] == atol_m);
      BOOST_TEST(vector[i + 2] == phi, tt::tolerance(1e-12));
      BOOST_TEST(vector[n + i] == atol_m * omega1, tt::tolerance(1e-9));
      BOOST_TEST(vector[n + i + 1] == atol_m * omega1, tt::tolerance(1e-9));
      BOOST_TEST(vector[n + i + 2] == phi * omega1, tt::tolerance(1e-9));
    }
  }
  // A run records them as used; the exact path's held stretches use hold_rtol / 100.
  analysis::SolverSettings exact;
  exact.method = "exact";
  BOOST_TEST(analysis::resolve(exact, &system).atol_components->displacement_m == 1e-14);
  BOOST_TEST(!analysis::resolve(analysis::with_method({}, "hht"), &system).atol_components.has_value());
}

BOOST_AUTO_TEST_CASE(EverySettingRowIsConsistent) {
  // The table is the one declaration of each setting: its default must pass its own rule on every
  // method using it, values beyond its range or choices are refused naming solver.<key>, a value
  // of another type is refused by set(), and resolve() uses the default when it is not given.
  const auto specs = analysis::setting_specs();
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const analysis::SettingSpec& spec = specs[i];
    BOOST_TEST_CONTEXT(spec.key) {
      BOOST_TEST(static_cast<std::size_t>(spec.id) == i);  // enum order: spec(id) is a lookup
      BOOST_TEST(spec.option.substr(0, 2) == "--");
      BOOST_TEST(!spec.description.empty());
      const std::string key = "solver." + std::string(spec.key);
      for (const analysis::MethodInfo& method : analysis::methods()) {
        if (!analysis::applies(method, spec.id) || spec.id == Setting::order) continue;
        analysis::SolverSettings s;
        s.method = std::string(method.name);
        s.set(spec.id, spec.default_value);
        BOOST_TEST(reason_of(s) == "");
        analysis::SolverSettings method_only;
        method_only.method = s.method;
        const analysis::UsedSettings defaulted = analysis::resolve(method_only);
        const analysis::UsedSettings given = analysis::resolve(s);
        BOOST_TEST(analysis::describe_used_settings(defaulted) == analysis::describe_used_settings(given));
        if (spec.range) {
          for (double outside : {spec.range->min - 1.0, spec.range->max * 2.0 + 1.0}) {
            if (spec.member.index() == 0)
              s.set(spec.id, static_cast<int>(outside));
            else
              s.set(spec.id, outside);
            std::string where;
            BOOST_TEST(reason_of(s, &where).rfind("must lie in", 0) == 0u);
            BOOST_TEST(where == key);
          }
        } else {
          s.set(spec.id, std::string("no-such-choice"));
          std::string where;
          BOOST_TEST(reason_of(s, &where).rfind("expected ", 0) == 0u);
          BOOST_TEST(where == key);
        }
      }
      analysis::SolverSettings s;
      const analysis::SettingValue wrong =
          spec.member.index() == 2 ? analysis::SettingValue(1.5) : analysis::SettingValue(std::string("1e-8"));
      try {
        s.set(spec.id, wrong);
        BOOST_TEST(false, "a value of another type was taken");
      } catch (const InputError& error) {
        BOOST_TEST(error.key() == key);
        BOOST_TEST(error.reason() == "expected " + analysis::expected_text(spec));
      }
      BOOST_TEST(!s.given(spec.id));
    }
  }
  analysis::SolverSettings s;
  s.set(Setting::rtol, 1);  // a whole number is a number
  BOOST_TEST(*s.rtol == 1.0);
  BOOST_CHECK_THROW(s.set(Setting::max_halvings, 2.0), InputError);  // a number is not a whole number
}

BOOST_AUTO_TEST_CASE(EveryContactRowIsCheckedByItsOwnRange) {
  // Each [contact] number with a range: its default (ContactSettings' initialiser) passes, and a
  // value beyond either bound is refused naming contact.<key> (the stiffness keys once their law
  // is in force). The paper scene's levels are 3.5 m apart, so level_tolerance_m's 0.5 m is the
  // table's bound, not the half-storey rule.
  const analysis::ContactSettings defaults;
  for (const analysis::ContactSettingSpec& spec : analysis::contact_setting_specs()) {
    if (!spec.range) continue;
    BOOST_TEST_CONTEXT(spec.key) {
      for (double outside : {spec.range->min - 1.0, spec.range->max * 2.0 + 1.0}) {
        analysis::Scene scene = paper();
        std::visit(
            [&](auto analysis::ContactSettings::*member) {
              using T = std::decay_t<decltype(scene.contact.*member)>;
              if constexpr (std::is_same_v<T, double> || std::is_same_v<T, std::optional<double>> ||
                            std::is_same_v<T, long>) {
                scene.contact.*member = outside;
                if constexpr (std::is_same_v<std::decay_t<decltype(defaults.*member)>, double>) {
                  const double default_value = defaults.*member;
                  if (!spec.required)
                    BOOST_TEST(default_value == std::clamp(default_value, spec.range->min, spec.range->max));
                }
              }
            },
            spec.member);
        if (spec.key == "stiffness_kN_per_m") scene.contact.law = "kelvin";
        if (spec.key == "stiffness_kN_per_m1_5") scene.contact.law = "hertzdamp";
        try {
          scene.validate();
          BOOST_TEST(false, "accepted " << outside);
        } catch (const InputError& error) {
          BOOST_TEST(error.key() == "contact." + std::string(spec.key));
          BOOST_TEST(error.reason() == "must lie in " + range_text(*spec.range));
        }
      }
    }
  }
}

/// Sets every number of `owner`'s row `spec` (a list: each storey's) to `value`; false for a row
/// that holds no number.
template <typename Owner>
bool set_number(Owner& owner, const KeySpec<Owner>& spec, double value) {
  return std::visit(
      [&](auto Owner::*member) {
        auto& target = owner.*member;
        using T = std::decay_t<decltype(target)>;
        if constexpr (std::is_same_v<T, double> || std::is_same_v<T, std::optional<double>>) {
          target = value;
          return true;
        } else if constexpr (std::is_same_v<T, std::vector<double>>) {
          target.assign(target.empty() ? 1 : target.size(), value);
          return !target.empty();
        } else {
          return false;
        }
      },
      spec.member);
}

/// Each ranged number of `specs` (rows of `section`, reached in the scene by `owner`): a value
/// beyond either bound is refused by Scene::validate() naming `<section>.<key>` (a list's first
/// entry, `[1]`) with the row's range.
template <typename Owner>
void check_row_ranges(const analysis::Scene& base, std::span<const KeySpec<Owner>> specs, std::string_view section,
                      Owner& (*owner)(analysis::Scene&)) {
  for (const KeySpec<Owner>& spec : specs) {
    if (!spec.range) continue;
    BOOST_TEST_CONTEXT(section << "." << spec.key) {
      for (double outside : {spec.range->min - 1.0, spec.range->max * 2.0 + 1.0}) {
        analysis::Scene scene = base;
        Owner& target = owner(scene);
        const auto is_strength = [](const KeySpec<Owner>& row) { return row.key.starts_with("yield_"); };
        if (is_strength(spec)) {  // the law's one strength: this row's
          for (const KeySpec<Owner>& other : specs)
            if (is_strength(other)) (target.*std::get<std::vector<double> Owner::*>(other.member)).clear();
        }
        if (is_per_storey(spec))
          (target.*std::get<std::vector<double> Owner::*>(spec.member)).assign(scene.buildings[0].storeys, 1.0);
        BOOST_REQUIRE(set_number(target, spec, outside));
        try {
          scene.validate();
          BOOST_TEST(false, "accepted " << outside);
        } catch (const InputError& error) {
          const std::string key = fmt::format("{}.{}{}", section, spec.key, is_per_storey(spec) ? "[1]" : "");
          BOOST_TEST(error.key().ends_with(key));
          BOOST_TEST(error.reason() == "must lie in " + range_text(*spec.range));
        }
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(TheExcitationOutputAndHysteresisRowsCheckTheirOwnRanges) {
  // The rows of [excitation], [output] and [building.hysteresis] (the yielding paper scene, whose
  // Bouc-Wen keys are checked whatever the law) are the one place their ranges are checked.
  check_row_ranges<excitation::ExcitationSpec>(
      paper(), excitation::excitation_specs(), "excitation", [](analysis::Scene & s) -> auto& { return s.excitation; });
  check_row_ranges<analysis::OutputSettings>(
      paper(), analysis::output_specs(), "output", [](analysis::Scene & s) -> auto& { return s.output; });
  const analysis::Scene yielding = io::read_scene(POUNDING_EXAMPLES_DIR "/paper/paper-yielding.toml");
  check_row_ranges<model::HystereticLaw>(
      yielding, model::hysteresis_specs(), "hysteresis",
      [](analysis::Scene & s) -> auto& { return s.buildings[0].hysteresis; });
}

BOOST_AUTO_TEST_CASE(EveryRunLimitIsCheckedByItsOwnRange) {
  // Each run limit's default (RunLimits' initialiser) lies in its row's range, and a value beyond
  // either bound is refused naming limits.<key> with that range; set_key refuses a value of
  // another type by the key.
  const analysis::RunLimits defaults;
  BOOST_CHECK_NO_THROW(defaults.validate());
  for (const analysis::LimitSpec& spec : analysis::limit_specs()) {
    BOOST_TEST_CONTEXT(spec.key) {
      BOOST_TEST(spec.option.starts_with("--"));
      for (double outside : {spec.range->min - 1.0, spec.range->max * 2.0}) {
        analysis::RunLimits limits;
        const bool whole = analysis::type_name(spec) == "integer";
        analysis::set_key(limits, spec, "limits",
                          whole ? analysis::KeyValue(static_cast<long>(outside)) : analysis::KeyValue(outside));
        try {
          limits.validate();
          BOOST_TEST(false, "accepted " << outside);
        } catch (const InputError& error) {
          BOOST_TEST(error.key() == "limits." + std::string(spec.key));
          BOOST_TEST(error.reason() == "must lie in " + range_text(*spec.range));
        }
      }
      analysis::RunLimits limits;
      BOOST_CHECK_THROW(analysis::set_key(limits, spec, "limits", analysis::KeyValue(std::string("ten"))), InputError);
    }
  }
}
