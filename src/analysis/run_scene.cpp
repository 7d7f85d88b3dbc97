#include "pounding/analysis/run_scene.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <fmt/format.h>

#include "pounding/analysis/contact_laws.hpp"
#include "pounding/input_error.hpp"
#include "pounding/model/mode.hpp"
#include "pounding/solvers/event_driven.hpp"
#include "pounding/solvers/gap_mode_bound.hpp"
#include "pounding/solvers/hht.hpp"
#include "pounding/solvers/recorder.hpp"

namespace pounding::analysis {

namespace {

/// The facing candidates first, in their order, then the corner ones: a scene's facing candidates
/// keep their numbers whether or not it has corner candidates (docs/model.md §4).
std::vector<contact::Candidate> corners_last(std::vector<contact::Candidate> candidates) {
  std::stable_partition(candidates.begin(), candidates.end(), [](const contact::Candidate& c) { return !c.corner; });
  return candidates;
}

}  // namespace

std::vector<contact::Candidate> scene_candidates(const Scene& scene) {
  if (scene.is_row()) {
    // Pair by pair, each pair's slab-to-slab candidates and then its slab-to-column ones, the
    // levels numbered on as Scene::levels() numbers them.
    std::vector<contact::Candidate> candidates;
    int level_offset = 0;
    for (const BuildingPair& pair : scene.pairs()) {
      const Scene two = scene.pair_scene(pair);
      std::vector<contact::Candidate> found = scene_candidates(two);
      contact::place_in_pair(found, {pair.first, pair.second}, level_offset);
      candidates.insert(candidates.end(), found.begin(), found.end());
      level_offset += static_cast<int>(two.levels().size());
    }
    return corners_last(std::move(candidates));
  }
  contact::PairGeometry geometry{{scene.buildings[0].slab, scene.buildings[1].slab},
                                 {scene.buildings[0].centre_of_mass, scene.buildings[1].centre_of_mass}};
  std::vector<contact::Candidate> candidates = contact::find_candidates(
      geometry, scene.levels(), {.margin_m = scene.contact.candidate_margin_m, .gap_m = scene.contact.gap_m});
  // Slab to column after slab to slab, so that a scene without them keeps its candidates' numbers.
  const std::vector<contact::Candidate> columns = scene.column_candidates();
  candidates.insert(candidates.end(), columns.begin(), columns.end());
  return corners_last(std::move(candidates));
}

namespace {

/// The scene's keys that chose how its record is read, as typed ("excitation.format = single,
/// excitation.accel_column = 99"), for an error the record file itself raised.
std::string reading_keys(const std::string& prefix, const excitation::RecordReadOptions& read) {
  constexpr const char* kFormats[] = {"peer-at2", "columns", "single"};
  std::string keys = fmt::format("{}format = {}", prefix, kFormats[static_cast<int>(read.format)]);
  if (read.format == excitation::RecordFormat::columns)
    keys += fmt::format(", {}time_column = {}", prefix, read.time_column);
  if (read.accel_column) keys += fmt::format(", {}accel_column = {}", prefix, *read.accel_column);
  if (read.dt_s) keys += fmt::format(", {}dt_s = {}", prefix, *read.dt_s);
  return keys;
}

/// `error` (raised reading `file`) with what the scene asked of that file: its file and keys.
InputError with_reading_keys(const InputError& error, const Scene& scene, const std::filesystem::path& file,
                             const std::string& keys) {
  // The record's own errors name "file" or "file:line"; anything else came from elsewhere.
  const std::string& where = error.file();
  const std::string path = file.string();
  if (scene.file.empty() || !(where == path || where.rfind(path + ":", 0) == 0)) return error;
  return InputError(error.key(), error.value(),
                    fmt::format("{} (read as {} asks: {})", error.reason(), scene.file.string(), keys), error.file());
}

}  // namespace

namespace {

/// `spec` with a spectral scaling at a building's first period (…@B1, …@B2, …@T1: the longer)
/// given that period from `first_periods_s` (each building's longest).
excitation::ExcitationSpec with_sa_period(excitation::ExcitationSpec spec, const std::vector<double>& first_periods_s) {
  if (!spec.scale_to_sa || spec.scale_to_sa->building == 0) return spec;
  const int building = spec.scale_to_sa->building;
  spec.scale_to_sa->period_s = building == 3 ? *std::max_element(first_periods_s.begin(), first_periods_s.end())
                                             : first_periods_s[static_cast<std::size_t>(building - 1)];
  return spec;
}

std::vector<model::Building> scene_buildings(const Scene& scene) {
  std::vector<model::Building> buildings(scene.buildings.size());
  for (std::size_t b = 0; b < buildings.size(); ++b) {
    try {
      buildings[b] = model::make_building(scene.buildings[b]);
    } catch (const InputError& error) {
      throw error.in_context(scene.file.string(), fmt::format("building[{}]", b + 1));
    }
  }
  return buildings;
}

std::vector<double> first_periods_s(const std::vector<model::Building>& buildings) {
  std::vector<double> periods;
  for (const model::Building& building : buildings) periods.push_back(building.modes.front().period_s);
  return periods;
}

/// The record (or pair) `spec` describes, its errors with the scene's file and the keys that chose
/// how it is read.
excitation::GroundMotion load_scene_record(const Scene& scene, const excitation::ExcitationSpec& spec) {
  try {
    return excitation::load_ground_motion(spec);
  } catch (const excitation::SecondComponentError& error) {
    const excitation::SecondComponentSpec& second = *scene.excitation.second;
    throw with_reading_keys(error, scene, second.file, reading_keys("excitation.second.", second.read));
  } catch (const InputError& error) {
    // The record file's line and field say what was found; the scene's file and keys say what
    // was asked of it (a column 99 the file does not have was the scene's choice).
    throw with_reading_keys(error, scene, scene.excitation.file, reading_keys("excitation.", scene.excitation.read));
  }
}

}  // namespace

excitation::ExcitationSpec resolved_excitation(const Scene& scene) {
  if (!scene.excitation.scale_to_sa || scene.excitation.scale_to_sa->building == 0) return scene.excitation;
  return with_sa_period(scene.excitation, first_periods_s(scene_buildings(scene)));
}

excitation::GroundMotion scene_ground_motion(const Scene& scene) {
  return load_scene_record(scene, resolved_excitation(scene));
}

dynamics::CoupledSystem build_system(const Scene& scene, bool contact) {
  std::vector<model::Building> buildings = scene_buildings(scene);
  // A spectral scaling at a building's period takes it from the buildings just assembled.
  excitation::GroundMotion motion =
      load_scene_record(scene, with_sa_period(scene.excitation, first_periods_s(buildings)));
  return dynamics::CoupledSystem(std::move(buildings), std::move(motion), scene.levels(),
                                 contact ? scene_candidates(scene) : std::vector<contact::Candidate>{});
}

solvers::HhtOptions hht_options(const Scene& scene, const UsedSettings& used) {
  solvers::HhtOptions options;
  options.dt_s = used.dt_s;
  options.alpha = used.alpha;
  options.contact_tolerance_m = used.contact_tolerance_m;
  options.max_halvings = used.max_halvings;
  options.location = used.event_location == "end-of-step"   ? solvers::HhtEventLocation::end_of_step
                     : used.event_location == "interpolate" ? solvers::HhtEventLocation::interpolate
                                                            : solvers::HhtEventLocation::halving;
  options.restitution = scene.contact.restitution;
  options.outputs = scene.output.selection();
  options.history_floors = scene.output.history_floors;
  options.history_other_floors = scene.history_other_floors();
  options.history_interval_s = scene.output.history_interval_s;
  return options;
}

namespace {

solvers::EventOptions event_options(const Scene& scene, const UsedSettings& used) {
  const MethodInfo& method = *used.method;
  solvers::EventOptions options;
  options.restitution = scene.contact.restitution;
  options.hold_velocity_mps = scene.contact.hold_velocity_mps;
  options.hold_height_m = scene.contact.hold_height_m;
  options.law = contact_law_info(scene.contact.law).law;
  options.contact_stiffness = scene.contact.used_stiffness();
  options.outputs = scene.output.selection();
  options.history_floors = scene.output.history_floors;
  options.history_other_floors = scene.history_other_floors();
  options.history_interval_s = scene.output.history_interval_s;
  if (method.steps_per_period > 0.0) options.steps_per_period = method.steps_per_period;
  options.modes_cutoff_hz = used.modes_cutoff_hz;
  options.clearance_steps = method.clearance_steps;
  options.max_events_per_s = used.max_events_per_s;
  return options;
}

/// A truncation must keep some mode of each building: below the first, nothing would move but
/// the static response. @throws InputError naming solver.modes_cutoff_hz.
void check_modes_kept(const Scene& scene, const UsedSettings& used, const dynamics::CoupledSystem& system) {
  if (used.modes_cutoff_hz == 0.0) return;
  for (int b = 0; b < system.building_count(); ++b) {
    const double first_hz = system.building(b).modes.front().omega_rad_s / (2.0 * std::numbers::pi);
    if (first_hz < used.modes_cutoff_hz) continue;
    throw InputError("solver.modes_cutoff_hz", format_value(used.modes_cutoff_hz),
                     fmt::format("keeps no mode of {} (its first mode is at {:.4g} Hz)",
                                 system.building(b).definition.name, first_hz),
                     scene.file.string());
  }
}

/// Yielding columns run only on methods that locate their branch changes, in the physical form.
/// @throws InputError naming the first yielding building's hysteresis.law.
void require_yielding_supported(const Scene& scene, const UsedSettings& used) {
  for (std::size_t b = 0; b < scene.buildings.size(); ++b) {
    if (!scene.buildings[b].hysteresis.yields()) continue;
    std::vector<std::string_view> able;
    for (const MethodInfo& method : methods()) {
      if (method.yielding_columns) able.push_back(method.name);
    }
    const std::string key = fmt::format("building[{}].hysteresis.law", b + 1);
    const std::string law = fmt::format("\"{}\"", model::to_string(scene.buildings[b].hysteresis.kind));
    if (!used.method->yielding_columns) {
      throw InputError(key, law,
                       fmt::format("yielding columns do not run on method {} (it assumes elastic buildings); they run "
                                   "on {}",
                                   used.method->name, fmt::join(able, ", ")),
                       scene.file.string());
    }
    if (used.form != "physical") {
      throw InputError(key, law,
                       fmt::format("yielding columns need solver.form = \"physical\" (the {} form assumes elastic "
                                   "buildings)",
                                   used.form),
                       scene.file.string());
    }
  }
}

}  // namespace

std::vector<RunWarning> scene_warnings(const Scene& scene) {
  constexpr double kLightest_t_per_m2 = 0.1, kHeaviest_t_per_m2 = 10.0;
  std::vector<RunWarning> warnings;
  for (std::size_t b = 0; b < scene.buildings.size(); ++b) {
    const model::BuildingDefinition& building = scene.buildings[b];
    const double area_m2 = std::abs(building.slab.signed_area());
    for (std::size_t f = 0; f < building.mass_t.size(); ++f) {
      const double per_area = building.mass_t[f] / area_m2;
      if (per_area >= kLightest_t_per_m2 && per_area <= kHeaviest_t_per_m2) continue;
      warnings.push_back({
          "implausible_floor_mass",
          fmt::format("building[{}] '{}' floor {}: mass_t = {:.6g} t on {:.6g} m² of slab is {:.3g} t/m² (floors weigh "
                      "about 0.5-2 t/m²{}); fine if the slab stands in for a rigid wall or a massless one on purpose",
                      b + 1, building.name, f + 1, building.mass_t[f], area_m2, per_area,
                      per_area >= 500.0 ? ": a thousand times that is kilograms given as tonnes?" : ""),
      });
      break;  // once per building
    }
  }
  if (scene.is_row()) {  // each pair's slabs that miss the other's columns, as for two buildings
    const std::vector<BuildingPair> pairs = scene.pairs();
    for (std::size_t b = 0; b < scene.buildings.size(); ++b) {
      const int index = static_cast<int>(b);
      if (std::any_of(pairs.begin(), pairs.end(),
                      [&](const BuildingPair& p) { return p.first == index || p.second == index; })) {
        continue;
      }
      warnings.push_back(
          {"building_alone", fmt::format("building[{}] '{}' stands farther than contact.candidate_margin_m = {} m from "
                                         "every other building: it is shaken but touches nothing",
                                         b + 1, scene.buildings[b].name, scene.contact.candidate_margin_m)});
    }
    for (const BuildingPair& pair : pairs) {
      for (RunWarning& warning : scene_warnings(scene.pair_scene(pair))) {
        if (warning.code == "slab_misses_columns") warnings.push_back(std::move(warning));
      }
    }
    return warnings;
  }
  const std::vector<contact::Candidate> columns = scene.column_candidates();
  for (const contact::ColumnLevel& level : scene.column_levels()) {
    const auto strikes = [&](const contact::Candidate& c) {
      return c.struck_building == level.slab_building && c.floors[level.slab_building] == level.slab_floor;
    };
    if (std::any_of(columns.begin(), columns.end(), strikes)) continue;
    const std::string& slab = scene.buildings[static_cast<std::size_t>(level.slab_building)].name;
    const std::string& other = scene.buildings[static_cast<std::size_t>(1 - level.slab_building)].name;
    warnings.push_back({"slab_misses_columns",
                        fmt::format("{} floor {} ({:.6g} m) stands between floors of {} but no facade column of {}'s "
                                    "storey {} is within reach: that slab meets nothing there (beams and infill walls "
                                    "are not modelled)",
                                    slab, level.slab_floor, level.elevation_m, other, other, level.storey)});
  }
  return warnings;
}

namespace {

/// A fixed step longer than the record's sample spacing leaves samples out of the forcing.
std::vector<RunWarning> settings_warnings(const UsedSettings& used, const dynamics::CoupledSystem& system) {
  std::vector<RunWarning> warnings;
  const double spacing_s = system.ground_motion().sample_spacing_s();
  if (applies(*used.method, Setting::dt_s) && system.ground_motion().skips_samples(used.dt_s)) {
    warnings.push_back(
        {"record_undersampled",
         fmt::format("dt_s = {} s is longer than the record's sample spacing {:.6g} s: the scheme sees a_g only at its "
                     "step ends (about 1 sample in {:.3g}), so the response and the energy audit are those of a record "
                     "with the samples between left out; give dt_s <= {:.6g} s (the default when dt_s is not given)",
                     used.dt_s, spacing_s, used.dt_s / spacing_s, spacing_s)});
  }
  return warnings;
}

}  // namespace

// The limits' ranges: at least one step and one history value, at most 1e12 of either (a
// month of CPU at the fastest step rate, terabytes of history); any positive wall time.
std::span<const LimitSpec> limit_specs() {
  static const std::vector<LimitSpec> kSpecs = {
      {.key = "max_steps",
       .option = "--max-steps",
       .member = &RunLimits::max_steps,
       .range = Range{1.0, 1e12, {}, false, "[1, 1e12]"},
       .description = "integrator steps over the whole run (hht: trial steps, halvings included)",
       .details = "a run estimated to need more (hht: record length / Δt; event-driven: record length / "
                  "(T_min/4), exact: T_min/16) is refused before it starts (exit 2); one that takes more ends with "
                  "status `step_limit` (exit 3)"},
      {.key = "max_wall_time_s",
       .option = "--max-wall-time",
       .member = &RunLimits::max_wall_time_s,
       .range = Range{0.0, 1e12, "s", true, "(0, 1e12]"},
       .description = "wall-clock time of the run (s)",
       .details = "a run that takes longer ends with status `time_limit` (exit 3), everything computed up to "
                  "`end_s` written"},
      {.key = "max_history_values",
       .option = "--max-history-values",
       .member = &RunLimits::max_history_values,
       .range = Range{1.0, 1e12, {}, false, "[1, 1e12]"},
       .description = "values of history.csv (rows × columns)",
       .details = "a run whose history would hold more (record length / `history_interval_s` × columns) is "
                  "refused before it starts (exit 2). 2e7 is about 450 MB of history.csv, 160 MB in memory when a "
                  "library caller keeps the history"},
  };
  return kSpecs;
}

void RunLimits::validate() const { validate_keys(*this, limit_specs(), "limits"); }

WorkEstimate estimate_work(const Scene& scene, const dynamics::CoupledSystem& system) {
  WorkEstimate estimate;
  estimate.dof = system.dof();
  estimate.duration_s = system.ground_motion().end_s() - system.ground_motion().start_s();
  if (scene.output.history) {
    estimate.history_rows = std::floor(estimate.duration_s / scene.output.history_interval_s) + 1.0;
    estimate.history_columns = static_cast<double>(
        solvers::history_columns(system, {scene.output.history_floors, scene.history_other_floors()},
                                 scene.output.member_forces)
            .size());
  }
  const UsedSettings used = resolve(scene.solver, &system);
  if (!used.method->event_driven) {
    estimate.min_steps = std::ceil(estimate.duration_s / used.dt_s);
  } else {
    // The automatic step bound is longest at rest (motion only adds modal amplitude); steps that
    // far from contact span whole record intervals are bounded only by the record's samples.
    const solvers::EventOptions options = event_options(scene, used);
    if (options.clearance_steps) {
      estimate.min_steps = static_cast<double>(system.ground_motion().time_s().size() - 1);
    } else {
      const solvers::GapModeBound bound(system, options.overlap_allowance_m, options.steps_per_period,
                                        options.modes_cutoff_hz);
      estimate.min_steps =
          std::ceil(estimate.duration_s / bound.max_step_s(Eigen::VectorXd::Zero(system.state_size())));
    }
  }
  return estimate;
}

void check_work(const WorkEstimate& estimate, const RunLimits& limits) {
  if (estimate.min_steps > static_cast<double>(limits.max_steps)) {
    throw InputError("limits.max_steps", std::to_string(limits.max_steps),
                     fmt::format("the run needs at least {:.3g} steps ({} s of record, {} DOF), above this limit",
                                 estimate.min_steps, estimate.duration_s, estimate.dof));
  }
  if (estimate.history_values() > limits.max_history_values) {
    throw InputError("limits.max_history_values", format_value(limits.max_history_values),
                     fmt::format("history.csv would hold {:.3g} values ({:.3g} rows of {} columns), above this "
                                 "limit; raise output.history_interval_s, list fewer output.history_floors or "
                                 "(with output.member_forces, a column group per column) keep the member forces to "
                                 "summary.json's peaks with output.history = false",
                                 estimate.history_values(), estimate.history_rows, estimate.history_columns));
  }
}

namespace {

void add_shear_demand(const dynamics::YieldingSpring& spring, const solvers::SpringResult& r, StoreyYielding& storey) {
  ++storey.springs_with_capacity;
  if (std::isfinite(r.shear_failure_t_s)) {
    ++storey.shear_failures;
    if (!(storey.first_shear_failure_t_s <= r.shear_failure_t_s)) storey.first_shear_failure_t_s = r.shear_failure_t_s;
  }
  const double ratio = r.peak_force_kN / spring.shear_capacity_kN;
  if (storey.springs_with_capacity == 1 || ratio > storey.largest_demand_capacity_ratio) {
    storey.largest_demand_capacity_ratio = ratio;
    storey.critical_column = spring.column;
    storey.critical_direction = spring.direction == 0 ? 'x' : 'y';
    storey.critical_peak_force_kN = r.peak_force_kN;
    storey.critical_capacity_kN = spring.shear_capacity_kN;
  }
}

}  // namespace

std::vector<StoreyYielding> storey_yielding(const std::vector<dynamics::YieldingSpring>& springs,
                                            const std::vector<solvers::SpringResult>& results) {
  std::vector<StoreyYielding> storeys;
  for (std::size_t j = 0; j < springs.size(); ++j) {
    const dynamics::YieldingSpring& spring = springs[j];
    if (storeys.empty() || storeys.back().building != spring.building || storeys.back().storey != spring.storey) {
      storeys.push_back({.building = spring.building,
                         .storey = spring.storey,
                         .first_yield_t_s = std::numeric_limits<double>::quiet_NaN(),
                         .first_shear_failure_t_s = std::numeric_limits<double>::quiet_NaN(),
                         .first_degrading_failure_t_s = std::numeric_limits<double>::quiet_NaN()});
    }
    StoreyYielding& storey = storeys.back();
    const solvers::SpringResult& r = results[j];
    const auto direction = static_cast<std::size_t>(spring.direction);
    storey.peak_ductility[direction] =
        std::max(storey.peak_ductility[direction], r.peak_drift_m / spring.yield_drift_m);
    storey.peak_column_force_kN[direction] = std::max(storey.peak_column_force_kN[direction], r.peak_force_kN);
    if (r.yield_count > 0) {
      ++storey.springs_yielded;
      if (!(storey.first_yield_t_s <= r.first_yield_t_s)) storey.first_yield_t_s = r.first_yield_t_s;
    }
    ++storey.springs;
    storey.hysteretic_kJ += r.hysteretic_kJ;
    if (spring.shear_capacity_kN > 0.0) add_shear_demand(spring, r, storey);
    if (!spring.imk) continue;
    ++storey.degrading_springs;
    if (std::isnan(r.degrading_failure_t_s)) continue;
    ++storey.degrading_failures;
    if (!(storey.first_degrading_failure_t_s <= r.degrading_failure_t_s))
      storey.first_degrading_failure_t_s = r.degrading_failure_t_s;
  }
  return storeys;
}

namespace {

solvers::RunResult run_system(const Scene& scene, const UsedSettings& used, const dynamics::CoupledSystem& system,
                              const RunLimits& limits, const solvers::RunBudget& budget, solvers::RunSink* sink) {
  const std::string method(used.method->name);
  if (used.method->factory) {
    solvers::EventOptions options = event_options(scene, used);
    options.max_steps = limits.max_steps;
    options.budget = budget;
    options.sink = sink;
    return solvers::run_event_driven(system, options, used.method->factory(used, system), method);
  }
  solvers::HhtOptions options = hht_options(scene, used);
  options.max_steps = limits.max_steps;
  options.budget = budget;
  options.sink = sink;
  return solvers::run_hht(system, options, method);
}

}  // namespace

RunReport run_scene(const Scene& scene, const RunLimits& limits, solvers::RunSink* sink) {
  scene.solver.validate();
  const ContactLawInfo& law = contact_law_info(scene.contact.law);
  try {
    require_supported(law, method_info(scene.solver.method));
  } catch (const InputError& error) {
    throw error.in_context(scene.file.string());
  }
  require_compliant_law_where_needed(scene);
  limits.validate();
  const dynamics::CoupledSystem system = build_system(scene);
  check_work(estimate_work(scene, system), limits);
  const UsedSettings used = resolve(scene.solver, &system);
  check_modes_kept(scene, used, system);
  require_yielding_supported(scene, used);
  RunReport report{scene.name,
                   scene.contact.gap_m,
                   scene.contact.restitution,
                   scene.solver,
                   used,
                   scene.contact.hold_velocity_mps,
                   system.levels(),
                   system.candidates(),
                   {}};
  report.contact_law = law.name;
  if (scene.is_row()) {
    report.pairs = scene.pairs();
    for (const model::BuildingDefinition& b : scene.buildings) report.building_names.push_back(b.name);
  }
  report.g_mps2 = scene.excitation.g_mps2;
  report.contact_stiffness = scene.contact.used_stiffness();
  report.contact_damping = contact_damping(law, scene.contact.restitution);
  report.warnings = scene_warnings(scene);
  report.springs = system.springs().all();
  if (scene.excitation.scale_to_sa) {
    std::vector<double> periods;
    for (int b = 0; b < system.building_count(); ++b) periods.push_back(system.building(b).modes.front().period_s);
    const excitation::SaScaling sa = *with_sa_period(scene.excitation, periods).scale_to_sa;
    report.spectral_scaling = SpectralScaling{.asked = sa.text,
                                              .target_g = sa.target_g,
                                              .period_s = *sa.period_s,
                                              .design = sa.design,
                                              .from_s = sa.from * *sa.period_s,
                                              .to_s = sa.to * *sa.period_s,
                                              .damping_ratio = excitation::kSaScalingDamping,
                                              .rotd100 = system.ground_motion().is_pair(),
                                              .record_factor = system.ground_motion().record_scale()};
  }
  for (RunWarning& warning : settings_warnings(used, system)) report.warnings.push_back(std::move(warning));
  const solvers::RunBudget budget{.max_wall_time_s = limits.max_wall_time_s};
  report.result = run_system(scene, used, system, limits, budget, sink);
  if (scene.output.contact_free_reference) {
    // The same buildings, record and method without any contact candidate: what the storeys
    // would have done had the buildings never met. Peaks only.
    Scene reference = scene;
    reference.output.history = false;
    const dynamics::CoupledSystem free = build_system(reference, false);
    report.contact_free = run_system(reference, resolve(reference.solver, &free), free, limits, budget, nullptr);
  }
  report.limit_states = drift_limit_states(scene.buildings, report.result, report.contact_free);
  report.free_vibration_s = scene.excitation.free_vibration_s;
  // A run that ended early (a collapse, a limit) has no residual drift: its end is not rest.
  if (report.result.status == solvers::RunStatus::completed && report.result.outputs.drift_peaks &&
      (!report.springs.empty() || !report.limit_states.empty() || report.free_vibration_s > 0.0)) {
    for (int b = 0; b < system.building_count(); ++b) {
      report.residual_drifts.push_back(residual_drift(report.result.peaks.at(static_cast<std::size_t>(b)),
                                                      system.building(b).modes.front().period_s));
    }
  }
  return report;
}

}  // namespace pounding::analysis
