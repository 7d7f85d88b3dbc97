#include "pounding/analysis/study.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <limits>
#include <map>

#include "pounding/analysis/run_scene.hpp"
#include "pounding/model/mode.hpp"
#include "pounding/solvers/run_budget.hpp"
#include "pounding/input_error.hpp"

namespace pounding::analysis {
namespace {

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

/// Index of each regular-grid sample of a history (event rows have off-grid times).
std::map<long, std::size_t> grid_rows(const solvers::History& history, double interval_s) {
  std::map<long, std::size_t> rows;
  if (history.time_s.empty()) return rows;
  const double t0 = history.time_s.front();
  for (std::size_t r = 0; r < history.time_s.size(); ++r) {
    const double k = (history.time_s[r] - t0) / interval_s;
    if (std::abs(k - std::round(k)) < 1e-9) rows.emplace(std::lround(k), r);
  }
  return rows;
}

void compare_histories(const solvers::History& a, const solvers::History& b, RunErrors& errors) {
  if (a.time_s.empty() || a.columns != b.columns || a.interval_s != b.interval_s) return;
  const auto rows_a = grid_rows(a, a.interval_s), rows_b = grid_rows(b, b.interval_s);
  for (std::size_t c = 1; c < a.columns.size(); ++c) {
    const std::string& name = a.columns[c];
    double* worst = name.ends_with("_u_m")       ? &errors.history_u_m
                    : name.ends_with("_v_m")     ? &errors.history_v_m
                    : name.ends_with("_phi_rad") ? &errors.history_phi_rad
                                                 : nullptr;
    if (!worst) continue;
    for (const auto& [k, ra] : rows_a) {
      const auto found = rows_b.find(k);
      if (found == rows_b.end()) continue;
      *worst = std::max(*worst, std::abs(a.rows[ra][c - 1] - b.rows[found->second][c - 1]));
    }
  }
}

void compare_peaks(const solvers::RunResult& a, const solvers::RunResult& b, RunErrors& errors) {
  for (std::size_t building = 0; building < std::min(a.peaks.size(), b.peaks.size()); ++building) {
    const auto& fa = a.peaks[building].floors;
    const auto& fb = b.peaks[building].floors;
    for (std::size_t f = 0; f < std::min(fa.size(), fb.size()); ++f) {
      errors.peak_u_m = std::max(errors.peak_u_m, std::abs(std::abs(fa[f].u_m.value) - std::abs(fb[f].u_m.value)));
      errors.peak_v_m = std::max(errors.peak_v_m, std::abs(std::abs(fa[f].v_m.value) - std::abs(fb[f].v_m.value)));
      errors.peak_phi_rad =
          std::max(errors.peak_phi_rad, std::abs(std::abs(fa[f].phi_rad.value) - std::abs(fb[f].phi_rad.value)));
    }
  }
}

}  // namespace

void StudyOptions::validate() const {
  if (repeat < 1) throw InputError("--repeat", std::to_string(repeat), "must be at least 1");
  if (!(match_window_s > 0.0)) throw InputError("match_window_s", format_value(match_window_s), "must be positive (s)");
  if (!(stiffness_run_limit_s > 0.0) || !std::isfinite(stiffness_run_limit_s)) {
    throw InputError("stiffness_run_limit_s", format_value(stiffness_run_limit_s), "must be positive (s)");
  }
}

RunErrors compare_runs(const solvers::RunResult& reference, const solvers::RunResult& run, double window_s) {
  constexpr double kFastImpact_mps = 0.01;  // slower impacts' times are ill-conditioned (gap/speed)
  RunErrors errors;
  std::vector<bool> used(run.impacts.size(), false);
  double first_hold_s = std::numeric_limits<double>::infinity();
  for (const auto& hold : reference.sustained_contacts) first_hold_s = std::min(first_hold_s, hold.start_s);
  for (const auto& a : reference.impacts) {
    std::size_t best = run.impacts.size();
    double best_dt = window_s;
    for (std::size_t j = 0; j < run.impacts.size(); ++j) {
      const double dt = std::abs(run.impacts[j].t_s - a.t_s);
      if (!used[j] && run.impacts[j].candidate == a.candidate && dt <= best_dt) {
        best = j;
        best_dt = dt;
      }
    }
    if (best == run.impacts.size()) {
      ++errors.missing;
      continue;
    }
    used[best] = true;
    ++errors.matched;
    errors.impact_time_all_s = std::max(errors.impact_time_all_s, best_dt);
    if (a.t_s < first_hold_s) errors.impact_time_before_hold_s = std::max(errors.impact_time_before_hold_s, best_dt);
    if (a.approach_velocity_mps >= kFastImpact_mps) {
      errors.impact_time_s = std::max(errors.impact_time_s, best_dt);
      errors.impulse_relative =
          std::max(errors.impulse_relative, std::abs(run.impacts[best].impulse_kNs - a.impulse_kNs) / a.impulse_kNs);
    }
  }
  errors.extra = static_cast<std::size_t>(std::count(used.begin(), used.end(), false));
  compare_histories(reference.history, run.history, errors);
  compare_peaks(reference, run, errors);
  return errors;
}

std::vector<double> stiffness_ladder(const ContactLawInfo& law, bool quick) {
  if (law.stiffness_key.empty() || (quick && law.law != contact::ContactLaw::kelvin)) return {};
  const std::vector<double> factors =
      quick ? std::vector<double>{1.0, 100.0} : std::vector<double>{0.1, 1, 10, 100, 1000};
  std::vector<double> ladder;
  for (double factor : factors) ladder.push_back(factor * law.default_stiffness);
  return ladder;
}

namespace {

/// The contact-stiffness ladder: each compliant law at each rung on each method that runs it,
/// every run within options.stiffness_run_limit_s of wall time.
template <class Timed>
void add_stiffness_ladder(const Scene& scene, const StudyOptions& options, StudyResult& study, Timed& timed,
                          const std::function<void(const StiffnessRow&)>& progress) {
  const RunLimits limits{.max_wall_time_s = options.stiffness_run_limit_s};
  for (const ContactLawInfo& law : contact_laws()) {
    for (double stiffness : stiffness_ladder(law, options.quick)) {
      for (std::string_view method : law.methods) {
        if (solvers::interrupt_requested()) {
          study.interrupted = true;
          return;
        }
        Scene variant = scene;
        variant.solver = with_method(scene.solver, method);
        variant.solver.not_used.clear();
        variant.contact.law = std::string(law.name);
        variant.contact.stiffness_kN_per_m.reset();
        variant.contact.stiffness_kN_per_m1_5.reset();
        variant.contact.set_stiffness(stiffness);
        StiffnessRow row;
        row.law = law.name;
        row.method = method;
        row.stiffness = stiffness;
        row.stiffness_unit = law.stiffness_unit;
        const solvers::RunResult result = timed(variant, row.run_time_s, limits);
        row.status = std::string(solvers::to_string(result.status));
        row.steps = result.statistics.steps;
        row.rhs_evaluations = result.statistics.rhs_evaluations;
        row.jacobian_evaluations = result.statistics.jacobian_evaluations;
        row.impacts = result.impacts.size();
        for (const solvers::ImpactRecord& i : result.impacts)
          row.peak_force_kN = std::max(row.peak_force_kN, i.peak_force_kN);
        if (progress) progress(row);
        study.stiffness_rows.push_back(std::move(row));
      }
    }
  }
}

/// The truncation ladder: the reference method at each cut-off, its error against the reference.
template <class Timed>
void add_truncation_ladder(const Scene& scene, StudyResult& study, Timed& timed, double match_window_s) {
  Scene exact = scene;
  exact.solver = with_method(scene.solver, reference_method().name);
  exact.solver.not_used.clear();
  const dynamics::CoupledSystem system = build_system(exact);
  for (double cutoff_hz : truncation_ladder()) {
    if (solvers::interrupt_requested()) {
      study.interrupted = true;
      return;
    }
    TruncationRow row;
    row.cutoff_hz = cutoff_hz;
    std::array<int, 2> kept{0, 0};
    for (int b = 0; b < 2; ++b) {
      for (const model::Mode& mode : system.building(b).modes) {
        const bool keep = cutoff_hz == 0.0 || mode.omega_rad_s / (2.0 * std::numbers::pi) < cutoff_hz;
        kept[b] += keep ? 1 : 0;
        ++row.modes_total;
      }
    }
    if (kept[0] == 0 || kept[1] == 0) continue;  // refused by run_scene: no mode of a building left
    row.modes_kept = kept[0] + kept[1];
    Scene variant = exact;
    if (cutoff_hz > 0.0) variant.solver.modes_cutoff_hz = cutoff_hz;
    const solvers::RunResult result = timed(variant, row.run_time_s);
    row.status = std::string(solvers::to_string(result.status));
    row.steps = result.statistics.steps;
    row.impacts = result.impacts.size();
    row.errors = compare_runs(study.reference, result, match_window_s);
    study.truncation_rows.push_back(std::move(row));
  }
}

}  // namespace

std::vector<double> truncation_ladder() { return {2.0, 5.0, 10.0, 15.0, 0.0}; }

bool yields(const Scene& scene) {
  return std::any_of(scene.buildings.begin(), scene.buildings.end(),
                     [](const model::BuildingDefinition& b) { return b.hysteresis.yields(); });
}

bool exact_runs(const Scene& scene) {
  return !yields(scene) && supports(contact_law_info(scene.contact.law), reference_method());
}

std::string study_reference(const Scene& scene) {
  return exact_runs(scene) ? std::string(reference_method().name)
                           : fmt::format("cvode-bdf rtol {:g}", kCvodeReferenceRtol);
}

/// Whether `method` runs the scene: its columns (yielding or not) and its contact law.
bool runs_scene(const MethodInfo& method, const Scene& scene) {
  return (!yields(scene) || method.yielding_columns) && supports(contact_law_info(scene.contact.law), method);
}

namespace {

/// The reference run: the exact path with the scene's settings for it, or, where it cannot run
/// the scene, cvode-bdf at `rtol` (atol rtol/100 m) in the physical form.
Scene reference_scene(const Scene& scene, double rtol = kCvodeReferenceRtol) {
  Scene reference = scene;
  if (exact_runs(scene)) {
    reference.solver = with_method(scene.solver, reference_method().name);
  } else {
    reference.solver = with_method(scene.solver, "cvode-bdf");
    reference.solver.rtol = rtol;
    reference.solver.atol = rtol / 100;
    reference.solver.form = "physical";
  }
  reference.solver.not_used.clear();
  return reference;
}

}  // namespace

void require_study_scene(const Scene& scene) {
  if (!scene.is_row()) return;
  throw InputError("building", fmt::format("{} buildings", scene.buildings.size()),
                   "form a row, and the study's report is written for one pair and one gap: choose one with "
                   "--pair NAME:NAME (Python: one of Scene.pair_scenes())",
                   scene.file.string());
}

StudyResult run_study(const Scene& given, const StudyOptions& options,
                      const std::function<void(const StudyRow&)>& progress,
                      const std::function<void(const StiffnessRow&)>& stiffness_progress) {
  options.validate();
  require_study_scene(given);
  // Runs are compared by their histories and every peak group, whatever the scene's [output] leaves out.
  Scene scene = given;
  scene.output.history = true;
  scene.output.peaks.assign(kPeakGroups.begin(), kPeakGroups.end());
  auto timed = [&](Scene variant, double& run_time_s, const RunLimits& limits = {}) {
    std::vector<double> times;
    solvers::RunResult result;
    for (int i = 0; i < options.repeat; ++i) {
      result = run_scene(variant, limits).result;
      times.push_back(result.statistics.wall_time_s);
    }
    run_time_s = median(times);
    return result;
  };

  StudyResult study;
  study.scene = scene.name;
  study.gap_m = scene.contact.gap_m;
  study.reference_method = study_reference(scene);
  const Scene reference = reference_scene(scene);
  run_scene(reference);  // warm the process up (caches, page faults) before anything is timed
  study.reference = timed(reference, study.reference_run_time_s);
  Scene looser = reference;
  if (!exact_runs(scene)) {
    looser = reference_scene(scene, 10 * kCvodeReferenceRtol);
  } else {
    looser.solver.hold_rtol = std::min(resolve(reference.solver).hold_rtol * 100, 1e-6);
  }
  study.reference_error = compare_runs(study.reference, run_scene(looser).result, options.match_window_s);
  // Errors within this much of the estimate are the reference's, not the run's.
  constexpr double kMargin = 2.0;

  auto add = [&](Scene variant, const std::string& label, const std::string& setting, double value) {
    if (solvers::interrupt_requested()) {
      study.interrupted = true;
      return;
    }
    StudyRow row;
    row.method = label;
    row.setting = setting;
    row.value = value;
    const solvers::RunResult result = timed(std::move(variant), row.run_time_s);
    row.status = std::string(solvers::to_string(result.status));
    row.steps = result.statistics.steps;
    row.rhs_evaluations = result.statistics.rhs_evaluations;
    row.restarts = result.statistics.restarts;
    row.impacts = result.impacts.size();
    row.errors = compare_runs(study.reference, result, options.match_window_s);
    row.impact_time_at_reference = row.errors.impact_time_all_s <= kMargin * study.reference_error.impact_time_all_s;
    row.history_u_at_reference = row.errors.history_u_m <= kMargin * study.reference_error.history_u_m;
    if (progress) progress(row);
    study.rows.push_back(std::move(row));
  };
  study.interrupted = study.reference.status == solvers::RunStatus::interrupted;

  for (const MethodInfo& method : methods()) {
    if (method.reference || !runs_scene(method, scene)) continue;
    for (const StudySeries& series : method.series) {
      for (double value : options.quick ? method.quick_ladder : method.ladder) {
        const bool is_reference = !exact_runs(scene) && method.name == "cvode-bdf" && series.event_location.empty() &&
                                  value == kCvodeReferenceRtol;
        if (is_reference) continue;  // the reference's own run: no error to measure
        Scene variant = scene;
        variant.solver = with_method(scene.solver, method.name);  // the scene's settings this method uses
        variant.solver.not_used.clear();
        if (method.ladder_setting == Setting::rtol) {
          variant.solver.rtol = value;
          variant.solver.atol = value * 1e-2;  // m: displacements are centimetres to decimetres
        } else {
          variant.solver.dt_s = value;
        }
        if (!series.event_location.empty()) variant.solver.event_location = std::string(series.event_location);
        add(variant, std::string(series.label), std::string(spec(method.ladder_setting).key), value);
      }
    }
  }
  if (yields(scene)) return study;  // both ladders are the exact path's or elastic ones (run_study's header)
  add_stiffness_ladder(scene, options, study, timed, stiffness_progress);
  if (exact_runs(scene)) add_truncation_ladder(scene, study, timed, options.match_window_s);
  return study;
}

}  // namespace pounding::analysis
