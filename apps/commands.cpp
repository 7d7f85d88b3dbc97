#include "commands.hpp"
#include "interrupts.hpp"
#include "progress_line.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <optional>

#include "pounding/analysis/contact_laws.hpp"
#include "pounding/analysis/modal_summary.hpp"
#include "pounding/analysis/run_scene.hpp"
#include "pounding/analysis/study.hpp"
#include "pounding/contact/candidates.hpp"
#include "pounding/contact/column_contact.hpp"
#include "pounding/excitation/ground_motion.hpp"
#include "pounding/input_error.hpp"
#include "pounding/io/json_report.hpp"
#include "pounding/io/output_files.hpp"
#include "pounding/io/provenance.hpp"
#include "pounding/io/run_report.hpp"
#include "pounding/io/run_stream.hpp"
#include "pounding/io/run_writer.hpp"
#include "pounding/io/scene_reader.hpp"
#include "pounding/io/study_writer.hpp"
#include "pounding/solvers/run_budget.hpp"

namespace pounding::cli {
namespace {

void print_modes_table(const analysis::BuildingSummary& building, int count) {
  fmt::print("{} ({} storeys, {} DOF, frame factor {:.8f}{})\n", building.name, building.storeys, building.dof,
             building.frame_factor, building.frame_factor_solved ? ", solved" : "");
  fmt::print("  {:>4}  {:>10}  {:>10}  {:>8}  {:>8}  {:>8}  {:>8}\n", "mode", "T [s]", "f [Hz]", "dominant", "Meff,x",
             "Meff,y", "Meff,rz");
  const int shown = std::min<int>(count, static_cast<int>(building.modes.size()));
  for (int k = 0; k < shown; ++k) {
    const model::Mode& mode = building.modes[k];
    fmt::print("  {:>4}  {:>10.5f}  {:>10.5f}  {:>8}  {:>7.1f}%  {:>7.1f}%  {:>7.1f}%\n", k + 1, mode.period_s,
               1.0 / mode.period_s, model::to_string(mode.dominant), 100 * mode.effective_mass_ratio_x,
               100 * mode.effective_mass_ratio_y, 100 * mode.effective_mass_ratio_rz);
  }
}

/// The slabs between two floors of the other building and the facade columns each can strike.
void print_column_levels(const analysis::Scene& scene, const std::vector<contact::ColumnLevel>& column_levels,
                         const std::array<std::vector<double>, 2>& z,
                         const std::array<std::string, 2>& names = {"B1", "B2"}) {
  if (scene.contact.slab_to_column == "off") {
    const auto all = contact::column_levels(z, scene.contact.level_tolerance_m);
    if (!all.empty())
      fmt::print("Slab to column: off (contact.slab_to_column); {} slab(s) between floors left out\n", all.size());
    return;
  }
  if (column_levels.empty()) return;
  const std::vector<contact::Candidate> candidates = analysis::scene_candidates(scene);
  fmt::print("Slab to column (a slab between two floors of the other building strikes its facade columns): {}\n",
             column_levels.size());
  for (const contact::ColumnLevel& l : column_levels) {
    const int columns = 1 - l.slab_building;
    std::vector<std::string> struck, round_corner;  // facing the slab's edges; reachable round a corner
    for (const contact::Candidate& c : candidates) {
      if (!c.column || c.struck_building != l.slab_building || c.floors[l.slab_building] != l.slab_floor) continue;
      const std::string label =
          fmt::format("{} ({:.3g} mm/MN)", c.column_index + 1, c.flexibility_m_per_kN * 1e6);  // m/kN -> mm/MN
      std::vector<std::string>& list = c.corner ? round_corner : struck;
      if (std::find(list.begin(), list.end(), label) == list.end()) list.push_back(label);
    }
    const double below = l.storey > 1 ? z[columns][l.storey - 2] : 0.0;
    fmt::print("  {} floor {} ({:.6g} m) -> {} storey {} ({:.6g} to {:.6g} m) at height ratio {:.4g}: {}{}\n",
               names[l.slab_building], l.slab_floor, l.elevation_m, names[columns], l.storey, below,
               z[columns][l.storey - 1], l.height_ratio,
               struck.empty() ? std::string("no facade column within reach")
                              : fmt::format("columns {} (number, local flexibility)", fmt::join(struck, ", ")),
               round_corner.empty()
                   ? std::string()
                   : fmt::format("; round a corner, against a side edge: {}", fmt::join(round_corner, ", ")));
  }
}

/// A row: each neighbouring pair with its gap, levels and candidates.
void print_row(const analysis::Scene& scene) {
  const std::vector<analysis::BuildingPair> pairs = scene.pairs();
  const std::vector<contact::Candidate> candidates = analysis::scene_candidates(scene);
  fmt::print("Row of {} buildings: {} neighbouring pair(s) (slabs at most contact.candidate_margin_m = {} m apart)\n",
             scene.buildings.size(), pairs.size(), scene.contact.candidate_margin_m);
  const std::vector<contact::Level> levels = scene.levels();
  for (const analysis::BuildingPair& pair : pairs) {
    const std::string& first = scene.buildings[static_cast<std::size_t>(pair.first)].name;
    const std::string& second = scene.buildings[static_cast<std::size_t>(pair.second)].name;
    std::vector<std::string> at;
    for (const contact::Level& l : levels) {
      if (l.pair == std::array{pair.first, pair.second})
        at.push_back(fmt::format("{} ({}/{}, {:.6g} m)", l.index, l.floors[0], l.floors[1], l.elevation_m));
    }
    const auto in_pair = [&](const contact::Candidate& c) { return c.pair == std::array{pair.first, pair.second}; };
    const auto count = std::count_if(candidates.begin(), candidates.end(), in_pair);
    const auto columns = std::count_if(candidates.begin(), candidates.end(),
                                       [&](const contact::Candidate& c) { return in_pair(c) && c.column; });
    fmt::print("  {}:{}: gap {:.6g} m ({} moves away along ({:.6g}, {:.6g})); levels {}; {} candidates{}\n", first,
               second, pair.gap_m, second, pair.direction.x() + 0.0, pair.direction.y() + 0.0,
               at.empty() ? std::string("none") : fmt::format("{}", fmt::join(at, ", ")), count,
               columns > 0 ? fmt::format(" ({} slab to column)", columns) : std::string());
    // The pair's slabs between two floors of the other building, and the columns each can strike.
    const analysis::Scene two = scene.pair_scene(pair);
    print_column_levels(two, two.column_levels(),
                        {model::floor_elevations(two.buildings[0]), model::floor_elevations(two.buildings[1])},
                        {first, second});
  }
}

/// The floor pairs that can touch, with both elevations, and the floors at no level.
void print_levels(const analysis::Scene& scene) {
  if (scene.is_row()) return print_row(scene);
  const std::vector<contact::Level> levels = scene.levels();
  const std::array<std::vector<double>, 2> z{model::floor_elevations(scene.buildings[0]),
                                             model::floor_elevations(scene.buildings[1])};
  fmt::print("Levels (floors at a common elevation, within {} m; only these can touch): {}\n",
             scene.contact.level_tolerance_m, levels.size());
  for (const contact::Level& l : levels) {
    fmt::print("  level {}: B1 floor {} ({:.6g} m) ↔ B2 floor {} ({:.6g} m)\n", l.index, l.floors[0],
               z[0][l.floors[0] - 1], l.floors[1], z[1][l.floors[1] - 1]);
  }
  const std::vector<contact::ColumnLevel> column_levels = scene.column_levels();
  for (std::size_t b = 0; b < 2; ++b) {
    std::vector<int> alone;
    for (int f = 1; f <= static_cast<int>(z[b].size()); ++f) {
      const bool at_level =
          std::any_of(levels.begin(), levels.end(), [&](const contact::Level& l) { return l.floors[b] == f; });
      const bool facing_columns = std::any_of(column_levels.begin(), column_levels.end(), [&](const auto& l) {
        return l.slab_building == static_cast<int>(b) && l.slab_floor == f;
      });
      if (!at_level && !facing_columns) alone.push_back(f);
    }
    if (!alone.empty()) {
      fmt::print("  B{} floors at no level{} (no slab of the other building there): {}\n", b + 1,
                 column_levels.empty() ? "" : " and facing no columns", fmt::join(alone, ", "));
    }
  }
  print_column_levels(scene, column_levels, z);
}

std::string_view format_name(excitation::RecordFormat format) {
  switch (format) {
    case excitation::RecordFormat::peer_at2: return "peer-at2";
    case excitation::RecordFormat::columns: return "columns";
    case excitation::RecordFormat::single: return "single";
  }
  return "?";
}

void print_spectral_scaling(const analysis::Scene& scene, const excitation::GroundMotion& motion) {
  if (!scene.excitation.scale_to_sa) return;
  const excitation::SaScaling sa = *analysis::resolved_excitation(scene).scale_to_sa;
  const char* measure = motion.is_pair() ? "RotD100 PSA" : "PSA";
  if (sa.design) {
    fmt::print(
        "  scaled by {:.6g} ({}): 5 %-damped {} fitted to the ASCE 7 spectrum (SDS {} g, SD1 {} g, TL {} s) "
        "over {:.4f}-{:.4f} s\n",
        motion.record_scale(), sa.text, measure, sa.design->sds_g, sa.design->sd1_g, sa.design->tl_s,
        sa.from * *sa.period_s, sa.to * *sa.period_s);
    return;
  }
  fmt::print("  scaled by {:.6g} ({}): 5 %-damped {} = {} g at T = {:.4f} s\n", motion.record_scale(), sa.text, measure,
             sa.target_g, *sa.period_s);
}

void print_excitation(const analysis::Scene& scene, const excitation::GroundMotion& motion) {
  const auto& spec = scene.excitation;
  const auto& t = motion.time_s();
  fmt::print("Excitation: {} ({})\n", spec.file.string(), format_name(spec.read.format));
  fmt::print("  {} samples from {:.4f} s to {:.4f} s (first step {:.4f} s)\n", t.size(), t.front(), t.back(),
             t[1] - t[0]);
  fmt::print("  peak |a_g| = {:.4f} m/s² = {:.4f} g at t = {:.4f} s, direction β = {} deg\n", motion.peak_mps2(),
             motion.peak_mps2() / spec.g_mps2, motion.peak_time_s(), spec.direction_deg);
  print_spectral_scaling(scene, motion);
  if (!spec.second) return;
  fmt::print("  second component (H2): {} ({}), on the pair's common time base ({} samples)\n",
             spec.second->file.string(), format_name(spec.second->read.format), t.size());
  fmt::print("  peak |a_g| = {:.4f} m/s² = {:.4f} g at t = {:.4f} s, direction β + 90 = {} deg\n", motion.peak_mps2(1),
             motion.peak_mps2(1) / spec.g_mps2, motion.peak_time_s(1), spec.direction_deg + 90.0);
}

/// Whether every entry equals the first (an empty list: true).
template <typename T>
bool all_equal(const std::vector<T>& values) {
  return std::all_of(values.begin(), values.end(), [&](const T& value) { return value == values.front(); });
}

/// "7 storeys of 3 m", or with unequal storeys "7 storeys of 4.5, 3, 3, 3, 3, 3, 3 m" (floor 1 first).
std::string storeys_text(const model::BuildingDefinition& b) {
  const std::vector<double>& h = b.storey_height_m;
  return all_equal(h) ? fmt::format("{} storeys of {} m", b.storeys, h.front())
                      : fmt::format("{} storeys of {} m", b.storeys, fmt::join(h, ", "));
}

/// "0.005 of the storey height", "[0.004, 0.005] of the storey heights", "0.01 m", "storey
/// yield shear [5200, 4100] kN", the section's keys, or "each column's own yield force": the
/// strength as the scene gave it (one number for all storeys).
std::string strength_text(const model::BuildingDefinition& d) {
  const model::HystereticLaw& law = d.hysteresis;
  const auto values = [](const std::vector<double>& v) {
    return all_equal(v) ? fmt::format("{}", v.front()) : fmt::format("[{}]", fmt::join(v, ", "));
  };
  if (model::every_column_has_own_strength(d)) return "each column's own yield force";
  if (const auto& f = d.flexural_strength) {
    return fmt::format("yield force 2 M_n / H from the section (rho_l {}, f_y {} MPa, f'c {} MPa, N {}, cover {} D)",
                       values(f->longitudinal_ratio), f->steel_yield_strength_MPa, f->concrete_strength_MPa,
                       f->axial_load_kN ? fmt::format("{} kN", *f->axial_load_kN) : std::string("the gravity share"),
                       f->cover_ratio);
  }
  if (!law.yield_drift_m.empty()) return fmt::format("yield drift {} m", values(law.yield_drift_m));
  if (!law.yield_drift_ratio.empty()) {
    return fmt::format("yield drift {} of the storey height", values(law.yield_drift_ratio));
  }
  return fmt::format("storey yield shear {} kN", values(law.yield_shear_kN));
}

/// IMK's backbone and deterioration as given: "Up 0.06 m, Upc 0.15 m, FmaxFy 1.2, FresFy 0.2;
/// Lamda S 1, C 1, A 0, K 2 m (0: off), c 1, 1, 1, 1, D 1, 1" (the positive side's, and the
/// negative side's where it differs).
std::string imk_text(const model::HystereticLaw& law) {
  const auto values = [](const std::vector<double>& v) {
    if (v.empty()) return std::string("none");
    return all_equal(v) ? fmt::format("{} m", v.front()) : fmt::format("[{}] m", fmt::join(v, ", "));
  };
  std::string text =
      fmt::format("Up {}, Upc {}, Uu {}, FmaxFy {}, FresFy {}", values(law.imk_up_pos_m), values(law.imk_upc_pos_m),
                  values(law.imk_uu_pos_m), *law.imk_fmax_fy_pos, law.imk_fres_fy_pos);
  const bool symmetric = law.imk_up_neg_m.empty() && law.imk_upc_neg_m.empty() && law.imk_uu_neg_m.empty() &&
                         !law.imk_fmax_fy_neg && !law.imk_fres_fy_neg;
  if (!symmetric) {
    text += fmt::format(" (negative: Up {}, Upc {}, Uu {}, FmaxFy {}, FresFy {})",
                        values(law.imk_up_neg_m.empty() ? law.imk_up_pos_m : law.imk_up_neg_m),
                        values(law.imk_upc_neg_m.empty() ? law.imk_upc_pos_m : law.imk_upc_neg_m),
                        values(law.imk_uu_neg_m.empty() ? law.imk_uu_pos_m : law.imk_uu_neg_m),
                        law.imk_fmax_fy_neg.value_or(*law.imk_fmax_fy_pos),
                        law.imk_fres_fy_neg.value_or(law.imk_fres_fy_pos));
  }
  if (law.imk_kappa_f) text += fmt::format(", kappaF {}, kappaD {}", *law.imk_kappa_f, law.imk_kappa_d.value_or(0.0));
  return text + fmt::format("; Lamda S {}, C {}, A {}, K {} m (0: off), c {}, {}, {}, {}, D {}, {}", law.imk_lamda_s_m,
                            law.imk_lamda_c_m, law.imk_lamda_a_m, law.imk_lamda_k_m, law.imk_c_s, law.imk_c_c,
                            law.imk_c_a, law.imk_c_k, law.imk_d_pos, law.imk_d_neg);
}

/// Each storey's yield shear along x and y (kN): what the columns carry when they all yield
/// together in a translation, Σ k · d_y.
void print_storey_strengths(const model::Building& building) {
  const model::BuildingDefinition& d = building.definition;
  const bool storey_strength =
      !d.flexural_strength && std::none_of(d.columns.begin(), d.columns.end(),
                                           [](const model::Column& c) { return !c.yield_force_kN.empty(); });
  std::vector<std::string> storeys;
  for (int storey = 1; storey <= building.storeys(); ++storey) {
    const auto shear_kN = [&](int direction) {  // Σ k_c d_y,c over the storey's columns
      if (storey_strength) {  // one d_y for all: (Σ k_c) d_y, as printed before columns had their own
        return model::storey_column_stiffness(building, storey, direction) *
               model::column_yield_drift_m(building, storey, direction);
      }
      double sum_kN = 0.0;
      for (std::size_t c = 0; c < d.columns.size(); ++c) {
        sum_kN += model::column_stiffness(d.columns[c], d.E_kPa, d.storey_height_m[storey - 1],
                                          building.frame_factor)[direction] *
                  model::column_yield_drift_m(building, storey, c, direction);
      }
      return sum_kN;
    };
    storeys.push_back(fmt::format("{:.5g} | {:.5g}", shear_kN(0), shear_kN(1)));
  }
  const std::string source = d.flexural_strength && !model::every_column_has_own_strength(d)
                                 ? " (columns from their sections, 2 M_n / H)"
                                 : "";
  if (all_equal(storeys)) {
    fmt::print("  storey yield shear{} x | y: {} kN, every storey\n", source, storeys.front());
  } else {
    fmt::print("  storey yield shears{} x | y (kN), storey 1 first: {}\n", source, fmt::join(storeys, "; "));
  }
}

/// Building b's column shear capacities, if any, storey by storey along x and y (a range where
/// its columns differ), and, where its columns yield, how many of their springs are shear-critical:
/// a capacity below their yield force k d_y, so that they fail in shear before they yield.
void print_shear_capacities(const dynamics::CoupledSystem& system, int b) {
  const model::Building& building = system.building(b);
  const model::BuildingDefinition& d = building.definition;
  if (!model::has_shear_capacity(d)) return;
  std::vector<std::string> storeys;
  for (int storey = 1; storey <= d.storeys; ++storey) {
    std::array<std::string, 2> along;
    for (int direction = 0; direction < 2; ++direction) {
      std::vector<double> kN;  // of the columns that have one (0: none)
      for (std::size_t c = 0; c < d.columns.size(); ++c) {
        const double capacity_kN = model::column_shear_capacity_kN(building, storey, c, direction);
        if (capacity_kN > 0.0) kN.push_back(capacity_kN);
      }
      if (kN.empty()) kN.push_back(0.0);
      const auto [low, high] = std::minmax_element(kN.begin(), kN.end());
      along[direction] = *low == *high ? fmt::format("{:.5g}", *low) : fmt::format("{:.5g}-{:.5g}", *low, *high);
    }
    storeys.push_back(fmt::format("{} | {}", along[0], along[1]));
  }
  const std::string source = d.shear_capacity ? " (ASCE 41-17 Eq. 10-3)" : "";
  const std::string after = d.shear_failure_loses_stiffness() ? "; a column that fails loses its stiffness" : "";
  if (all_equal(storeys)) {
    fmt::print("  column shear capacity{} x | y: {} kN, every storey{}\n", source, storeys.front(), after);
  } else {
    fmt::print("  column shear capacity{} x | y (kN), storey 1 first: {}{}\n", source, fmt::join(storeys, "; "), after);
  }
  int springs = 0, critical = 0;
  for (const dynamics::YieldingSpring& s : system.springs().all()) {
    if (s.building != b || s.shear_capacity_kN <= 0.0) continue;  // no capacity: not checked
    ++springs;
    if (s.shear_capacity_kN < s.stiffness_kN_per_m * s.yield_drift_m) ++critical;
  }
  if (springs > 0) {
    fmt::print("    {} of {} column springs shear-critical (capacity below their yield force k d_y)\n", critical,
               springs);
  }
}

/// For each pair whose buildings give slab_thickness_m, each slab's axial stiffness along the
/// pair's direction, the two in series and the contact's linear stiffness against them: the
/// members' own scale for a contact stiffness (docs/model.md §6a).
void print_slab_axial_stiffness(const analysis::Scene& scene) {
  const analysis::ContactLawInfo& law = analysis::contact_law_info(scene.contact.law);
  for (const analysis::BuildingPair& pair : scene.pairs()) {
    const model::BuildingDefinition& a = scene.buildings[static_cast<std::size_t>(pair.first)];
    const model::BuildingDefinition& b = scene.buildings[static_cast<std::size_t>(pair.second)];
    if (!a.slab_thickness_m && !b.slab_thickness_m) continue;
    const model::Point2 direction = model::clearance(a.slab, b.slab).direction;
    std::vector<std::string> parts;
    std::vector<double> stiffnesses;
    for (const model::BuildingDefinition* building : {&a, &b}) {
      if (!building->slab_thickness_m) continue;
      stiffnesses.push_back(model::slab_axial_stiffness_kN_per_m(*building, direction));
      parts.push_back(fmt::format("{} {:.4g} kN/m", building->name, stiffnesses.back()));
    }
    std::string verdict;
    if (scene.pair_scene(pair).levels().empty()) {  // no slab meets a slab: the two in series mean nothing
      verdict =
          "; no common level: the slabs strike the other building's columns, whose own flexibility is in "
          "series with the contact (docs/model.md §6b)";
    } else if (stiffnesses.size() == 2) {
      const double series = stiffnesses[0] * stiffnesses[1] / (stiffnesses[0] + stiffnesses[1]);
      parts.push_back(fmt::format("in series {:.4g} kN/m", series));
      if (law.stiffness_unit == "kN/m") {
        verdict = fmt::format("; the {} stiffness {:g} kN/m is {:.3g} times that", law.name,
                              scene.contact.used_stiffness(), scene.contact.used_stiffness() / series);
      }
    }
    fmt::print("  slab axial stiffness E t w / L, {} - {} along ({:.3g}, {:.3g}): {}{}\n", a.name, b.name,
               direction.x() + 0.0, direction.y() + 0.0, fmt::join(parts, ", "), verdict);  // + 0: no "-0"
  }
}

}  // namespace

/// The command-line options of `run` replace their scene keys. `--method` keeps the file's keys
/// its method uses and lists the others as not used (the file's keys were checked against the
/// file's method); the options themselves are checked against the method run (Scene::validate).
void apply_run_options(const RunCommand& command, analysis::SolverSettings& solver) {
  if (command.method) solver = analysis::with_method(solver, *command.method);
  for (const auto& [setting, value] : command.settings) solver.set(setting, value);
  if (command.halving) {
    if (!analysis::applies(analysis::method_info(solver.method), analysis::Setting::event_location)) {
      throw InputError("--halving", *command.halving, fmt::format("does not apply to method {}", solver.method));
    }
    if (*command.halving != "on" && *command.halving != "off") {
      throw InputError("--halving", *command.halving, "expected on or off");
    }
    if (*command.halving == "off") solver.event_location = "end-of-step";
  }
}

/// `--history` and `--peaks` replace output.history and output.peaks (checked by Scene::validate).
void apply_output_options(const RunCommand& command, analysis::OutputSettings& output) {
  if (command.contact_free_reference) output.contact_free_reference = true;
  if (command.member_forces) output.member_forces = true;
  if (command.history) {
    if (*command.history != "on" && *command.history != "off") {
      throw InputError("--history", *command.history, "expected on or off");
    }
    output.history = *command.history == "on";
  }
  if (command.peaks) {
    output.peaks.clear();
    if (*command.peaks == "all") {
      output.peaks.assign(analysis::kPeakGroups.begin(), analysis::kPeakGroups.end());
    } else if (*command.peaks != "none") {
      for (std::string_view rest = *command.peaks;;) {
        const std::size_t comma = rest.find(',');
        output.peaks.emplace_back(rest.substr(0, comma));
        if (comma == std::string_view::npos) break;
        rest.remove_prefix(comma + 1);
      }
    }
  }
}

/// The options `command` names scene keys and run limits by: `--rtol` for `solver.rtol` when the
/// user gave --rtol (a value from the scene file keeps its key). The run limits have no scene key:
/// their options are named whether given or defaulted.
std::map<std::string, std::string> option_names(const RunCommand& c) {
  std::map<std::string, std::string> names;
  for (const analysis::LimitSpec& limit : analysis::limit_specs()) {
    names["limits." + std::string(limit.key)] = limit.option;
  }
  if (c.method) names["solver.method"] = "--method";
  if (c.history) names["output.history"] = "--history";
  if (c.peaks) names["output.peaks"] = "--peaks";
  for (const auto& entry : c.settings) {
    const analysis::SettingSpec& setting = analysis::spec(entry.first);
    names["solver." + std::string(setting.key)] = setting.option;
  }
  return names;
}

analysis::RunLimits run_limits(const RunCommand& command) {
  analysis::RunLimits limits;
  for (const analysis::LimitSpec& limit : analysis::limit_specs()) {
    const auto given = command.limits.find(limit.option);
    if (given != command.limits.end()) analysis::set_key(limits, limit, "limits", given->second);
  }
  return limits;
}

int run_run(const RunCommand& command, const std::string& command_line) {
  analysis::Scene scene =
      io::read_scene(command.scene, {.gaps = command.gaps, .contact = command.contact, .record = command.record});
  try {
    apply_run_options(command, scene.solver);
    apply_output_options(command, scene.output);
  } catch (const InputError& error) {
    throw error.renamed(option_names(command)).in_context(command.scene);
  }
  const analysis::RunLimits limits = run_limits(command);
  const std::filesystem::path folder = command.out_dir.empty()
                                           ? std::filesystem::path("out") / io::folder_name(scene.name)
                                           : std::filesystem::path(command.out_dir);
  std::optional<analysis::RunReport> report;
  io::Provenance provenance;
  std::filesystem::path created;
  // History and impacts reach the folder as they are computed: a run killed outright leaves them
  // as .partial files (and no summary.json); an orderly end renames them and adds the summary.
  io::StreamedRunFiles files(folder);
  std::optional<ProgressLine> progress;
  if (ProgressLine::wanted(command.no_progress)) {
    progress.emplace();
    files.on_progress(
        [&progress](double t_s, double end_s, std::size_t impacts) { progress->update(t_s, end_s, impacts); });
  }
  try {
    scene.validate();
    limits.validate();
    created = io::require_writable_folder(folder, "--out");  // before the run, not after an hour of it
    provenance = io::make_provenance(scene, command_line);
    files.impact_fields(io::impact_field_set(analysis::scene_candidates(scene)));
    const InterruptRequests interrupts;
    report = analysis::run_scene(scene, limits, &files);
  } catch (const InputError& error) {
    files.abandon();
    if (!created.empty()) std::filesystem::remove_all(created);  // a refused run leaves nothing
    // A law the method cannot run, both given as options, is the options' fault, not the scene's.
    if (error.key() == "contact.law" && command.contact.contains("--contact-law")) {
      throw InputError("--contact-law", error.value(), error.reason() + (command.method ? " (--method)" : ""),
                       command.scene);
    }
    throw error.renamed(option_names(command), command.scene);
  }
  if (progress) progress->clear();
  files.finish(*report, provenance);
  fmt::print("{}", io::full_report(*report));
  fmt::print("Wrote {}/summary.json, impacts.csv{}\n", folder.string(),
             scene.output.history ? ", history.csv, contacts_history.csv" : "");
  return report->result.status == solvers::RunStatus::completed ? 0 : 3;
}

int run_study(const StudyCommand& command, const std::string& command_line) {
  analysis::Scene scene = io::read_scene(command.scene, {.gaps = command.gaps});
  if (!command.pair.empty()) {
    try {
      const analysis::BuildingPair pair = scene.named_pair(command.pair, "--pair");
      if (scene.is_row()) {
        fmt::print("Pair {} of the row '{}', studied alone (its own scene of two: the other buildings left out)\n",
                   command.pair, scene.name);
        scene = scene.pair_scene(pair);
      }
    } catch (const InputError& error) {
      throw error.in_context(command.scene);
    }
  }
  analysis::StudyOptions options;
  options.repeat = command.repeat;
  options.quick = command.quick;
  options.validate();
  analysis::require_study_scene(scene);  // before the header and the folder
  const std::string folder =
      command.out_dir.empty() ? "out/" + io::folder_name(scene.name + "-study") : command.out_dir;
  io::require_writable_folder(folder, "--out");
  const io::Provenance provenance = io::make_provenance(scene, command_line);
  fmt::print("Work-precision study of '{}' at gap {:.6g} m; every run against {}; run time = median of {}\n",
             scene.name, scene.contact.gap_m, analysis::study_reference(scene), options.repeat);
  fmt::print("Impact-time errors: before the first sustained contact, and over impacts faster than 1 cm/s.\n");
  fmt::print("Errors at or below twice the reference's own error estimate are shown as 'at ref'.\n");
  fmt::print("{:<16} {:>10} {:>9} {:>8} {:>7} {:>4} {:>5} {:>13} {:>11} {:>11} {:>9} {:>10} {:>10} {:>12}\n", "method",
             "rtol|dt[s]", "run [s]", "steps", "impacts", "miss", "extra", "pre-hold [s]", "all [s]", "fast [s]",
             "dI/I", "u err [m]", "v err [m]", "phi err[rad]");
  auto at_reference = [](bool at, double value) { return at ? std::string("at ref") : fmt::format("{:.3e}", value); };
  auto print_row = [&](const analysis::StudyRow& r) {
    const analysis::RunErrors& e = r.errors;
    fmt::print(
        "{:<16} {:>10.0e} {:>9.4f} {:>8} {:>7} {:>4} {:>5} {:>13.3e} {:>11} {:>11.3e} {:>9.2e} {:>10} {:>10.3e} "
        "{:>12.3e}{}\n",
        r.method, r.value, r.run_time_s, r.steps, r.impacts, e.missing, e.extra, e.impact_time_before_hold_s,
        at_reference(r.impact_time_at_reference, e.impact_time_all_s), e.impact_time_s, e.impulse_relative,
        at_reference(r.history_u_at_reference, e.history_u_m), e.history_v_m, e.history_phi_rad,
        r.status == "completed" ? "" : "  " + r.status);
  };
  bool ladder_started = false;
  auto print_stiffness_row = [&](const analysis::StiffnessRow& r) {
    if (!ladder_started) {
      fmt::print("Contact-stiffness ladder: each compliant law on each method that runs it, at most {} s a run\n",
                 options.stiffness_run_limit_s);
      fmt::print("{:<10} {:<12} {:>10} {:<9} {:>9} {:>8} {:>9} {:>7} {:>7} {:>12}\n", "law", "method", "stiffness",
                 "unit", "run [s]", "steps", "rhs", "Jac", "impacts", "peak F [kN]");
      ladder_started = true;
    }
    fmt::print("{:<10} {:<12} {:>10.3g} {:<9} {:>9.4f} {:>8} {:>9} {:>7} {:>7} {:>12.4g}{}\n", r.law, r.method,
               r.stiffness, r.stiffness_unit, r.run_time_s, r.steps, r.rhs_evaluations, r.jacobian_evaluations,
               r.impacts, r.peak_force_kN, r.status == "completed" ? "" : "  " + r.status);
  };
  const InterruptRequests interrupts;
  const analysis::StudyResult study = analysis::run_study(scene, options, print_row, print_stiffness_row);
  io::write_study(study, provenance, folder);
  if (!study.truncation_rows.empty()) {
    fmt::print(
        "Truncation ladder: the exact path keeping the modes below a cut-off, the rest static, against the "
        "full one\n");
    fmt::print("{:>11} {:>7} {:>9} {:>8} {:>7} {:>4} {:>5} {:>13} {:>11} {:>11} {:>11}\n", "cutoff[Hz]", "modes",
               "run [s]", "steps", "impacts", "miss", "extra", "pre-hold [s]", "all [s]", "u err [m]", "peak u [m]");
    for (const analysis::TruncationRow& r : study.truncation_rows) {
      const analysis::RunErrors& e = r.errors;
      fmt::print("{:>11} {:>7} {:>9.4f} {:>8} {:>7} {:>4} {:>5} {:>13.3e} {:>11.3e} {:>11.3e} {:>11.3e}{}\n",
                 r.cutoff_hz > 0.0 ? fmt::format("{:g}", r.cutoff_hz) : std::string("full"),
                 fmt::format("{}/{}", r.modes_kept, r.modes_total), r.run_time_s, r.steps, r.impacts, e.missing,
                 e.extra, e.impact_time_before_hold_s, e.impact_time_all_s, e.history_u_m, e.peak_u_m,
                 r.status == "completed" ? "" : "  " + r.status);
    }
  }
  if (study.interrupted) {
    fmt::print(
        "Interrupted after {} of the study's runs; wrote them to {}/study.csv, stiffness.csv, truncation.csv "
        "and study.json\n",
        study.rows.size() + study.stiffness_rows.size() + study.truncation_rows.size(), folder);
    return 3;
  }
  const bool exact_reference = study.reference_method == analysis::reference_method().name;
  fmt::print(
      "Reference: {}, {} impacts, {:.3f} s; its own error estimate (against {}): impact times {:.3e} s, u {:.3e} m. "
      "Wrote {}/study.csv, stiffness.csv, truncation.csv and study.json; draw them with tools/plot_study.py {}\n",
      exact_reference ? "exact path" : study.reference_method, study.reference.impacts.size(),
      study.reference_run_time_s, exact_reference ? "held stretches at hold_rtol x 100" : "the same at rtol x 10",
      study.reference_error.impact_time_all_s, study.reference_error.history_u_m, folder, folder);
  return 0;
}

int run_modes(const ModesCommand& command) {
  const analysis::Scene scene = io::read_scene(command.scene);
  if (!command.json_file.empty()) io::require_writable_file(command.json_file, "--json");
  const auto buildings = analysis::summarise_buildings(scene);
  for (const auto& building : buildings) print_modes_table(building, command.count);
  if (!command.json_file.empty()) {
    io::write_json(io::modes_json(buildings), command.json_file);
    fmt::print("Wrote {}\n", command.json_file);
  }
  return 0;
}

int run_check(const CheckCommand& command) {
  const analysis::Scene scene =
      io::read_scene(command.scene, {.gaps = command.gaps, .contact = command.contact, .record = command.record});
  analysis::require_compliant_law_where_needed(scene);
  const auto buildings = analysis::summarise_buildings(scene);
  const dynamics::CoupledSystem system = analysis::build_system(scene);
  const excitation::GroundMotion& motion = system.ground_motion();

  fmt::print("Scene '{}' ({}) is valid.\n", scene.name, scene.file.string());
  int total_dof = 0;
  for (std::size_t i = 0; i < buildings.size(); ++i) {
    const auto& b = buildings[i];
    const auto& definition = scene.buildings[i];
    total_dof += b.dof;
    fmt::print(
        "Building {} '{}': {}, {} DOF, total mass {:.1f} t, frame factor "
        "{:.8f}{}\n",
        i + 1, b.name, storeys_text(definition), b.dof, b.total_mass_t, b.frame_factor,
        b.frame_factor_solved ? " (solved for the target period)" : "");
    fmt::print("  floor mass {:.1f} t (top {:.1f} t), polar moment {:.1f} t·m² (top {:.1f} t·m²)\n",
               definition.mass_t.front(), definition.mass_t.back(), definition.polar_moment_tm2.front(),
               definition.polar_moment_tm2.back());
    fmt::print(
        "  T1 = {:.4f} s, T2 = {:.4f} s, T3 = {:.4f} s; Rayleigh a0 = {:.5f} 1/s, "
        "a1 = {:.6f} s\n",
        b.modes[0].period_s, b.modes[1].period_s, b.modes[2].period_s, b.rayleigh.a0_per_s, b.rayleigh.a1_s);
    if (definition.p_delta)
      fmt::print("  P-Δ: storeys lowered by the gravity load above them (g = {} m/s²)\n", definition.g_mps2);
    const model::HystereticLaw& law = definition.hysteresis;
    if (law.yields()) {
      const std::string shape = law.is_smooth() ? fmt::format(", A {}, beta {}, gamma {}, n {}", law.bouc_wen_a,
                                                              law.bouc_wen_beta, law.bouc_wen_gamma, law.bouc_wen_n)
                                                : std::string();
      if (law.degrades()) {
        fmt::print("  columns {} in x and y: {}, {}\n", model::to_string(law.kind), strength_text(definition),
                   imk_text(law));
      } else {
        fmt::print("  columns {} in x and y: {}, hardening ratio {}{}\n", model::to_string(law.kind),
                   strength_text(definition), law.hardening_ratio, shape);
      }
      print_storey_strengths(system.building(static_cast<int>(i)));
    }
    print_shear_capacities(system, static_cast<int>(i));
  }
  // One hysteretic variable per Bouc–Wen spring (dynamics/yielding_springs.hpp).
  const int hysteretic_states = system.springs().smooth_count();
  fmt::print("Coupled system: {} DOF ({} first-order states{})\n", total_dof, 2 * total_dof + hysteretic_states,
             hysteretic_states > 0 ? fmt::format(", {} of them Bouc-Wen's z", hysteretic_states) : std::string());
  print_levels(scene);
  print_excitation(scene, motion);
  const std::string law =
      scene.contact.law == "impulse"
          ? std::string()
          : fmt::format(", law {} (stiffness {} {})", scene.contact.law, scene.contact.used_stiffness(),
                        analysis::contact_law_info(scene.contact.law).stiffness_unit);
  fmt::print("Contact: {}, restitution k = {}{}\n",
             scene.is_row() ? std::string("gaps per pair (above)") : fmt::format("gap {} m", scene.contact.gap_m),
             scene.contact.restitution, law);
  print_slab_axial_stiffness(scene);
  const auto candidates = analysis::scene_candidates(scene);
  const auto column_pairs = std::count_if(candidates.begin(), candidates.end(), [](const auto& c) { return c.column; });
  if (column_pairs == 0) {
    fmt::print("Contact candidates: {} (vertex of one slab against an edge of the other, same level)\n",
               candidates.size());
  } else {
    fmt::print(
        "Contact candidates: {} ({} slab vertex against slab edge at a level, {} column against slab edge, "
        "level 0)\n",
        candidates.size(), candidates.size() - static_cast<std::size_t>(column_pairs), column_pairs);
  }
  if (const auto corners =
          std::count_if(candidates.begin(), candidates.end(), [](const auto& c) { return c.corner; })) {
    fmt::print(
        "  {} of them corner candidates, listed last: a vertex that can reach the edge only round a corner of "
        "the other slab (docs/model.md §5a)\n",
        corners);
  }
  for (const auto& c : candidates) fmt::print("  level {}: {}\n", c.level, contact::describe(c));
  const analysis::UsedSettings used = analysis::resolve(scene.solver, &system);
  fmt::print("Solver: {} ({}): {}\n", scene.solver.method, used.method->description,
             analysis::describe_used_settings(used));
  for (const analysis::RunWarning& warning : analysis::scene_warnings(scene)) {
    fmt::print("Warning ({}): {}\n", warning.code, warning.message);
  }
  return 0;
}

int run_methods(const MethodsCommand& command) {
  nlohmann::json list = nlohmann::json::array();
  for (const analysis::MethodInfo& method : analysis::methods()) {
    std::vector<std::string> keys;
    for (analysis::Setting s : method.settings) keys.emplace_back(analysis::spec(s).key);
    if (!command.json) {
      fmt::print("{:<12} {}\n{:<12} uses {}; yielding columns: {}\n", method.name, method.description, "",
                 fmt::join(keys, ", "), method.yielding_columns ? "yes (form physical)" : "no");
      continue;
    }
    nlohmann::json series = nlohmann::json::array();
    for (const analysis::StudySeries& s : method.series) {
      series.push_back({{"label", s.label}, {"colour", s.style.colour}, {"marker", s.style.marker}});
    }
    list.push_back({{"name", method.name},
                    {"description", method.description},
                    {"settings", keys},
                    {"event_driven", method.event_driven},
                    {"reference", method.reference},
                    {"yielding_columns", method.yielding_columns},
                    {"study",
                     {{"setting", analysis::spec(method.ladder_setting).key},
                      {"ladder", method.ladder},
                      {"quick_ladder", method.quick_ladder},
                      {"series", series}}}});
  }
  if (command.json) {
    fmt::print("{}\n", list.dump(2));
    return 0;
  }
  fmt::print("\nContact laws ([contact] law, --contact-law):\n");
  for (const analysis::ContactLawInfo& law : analysis::contact_laws()) {
    const std::string keys = law.stiffness_key.empty()
                                 ? "no keys"
                                 : fmt::format("{} ({}, default {:g}: {})", law.stiffness_key, law.stiffness_unit,
                                               law.default_stiffness, law.stiffness_source);
    const std::string runs = law.methods.empty() ? "every method" : fmt::format("{}", fmt::join(law.methods, ", "));
    fmt::print("{:<12} {}\n{:<12} uses {}; runs on {}\n", law.name, law.description, "", keys, runs);
  }
  return 0;
}

int run_laws(const LawsCommand& command) {
  require_range("--restitution", command.restitution, *analysis::contact_setting_spec("restitution").range);
  nlohmann::json list = nlohmann::json::array();
  for (const analysis::ContactLawInfo& law : analysis::contact_laws()) {
    const nlohmann::json rebound =
        law.rebound ? nlohmann::json(law.rebound(command.restitution)) : nlohmann::json(nullptr);
    if (!command.json) {
      const std::string stiffness = law.stiffness_key.empty()
                                        ? "no stiffness"
                                        : fmt::format("default {} = {:g} {} ({})", law.stiffness_key,
                                                      law.default_stiffness, law.stiffness_unit, law.stiffness_source);
      // Without a closed form the rebound depends on the masses and the approach speed: say where it is measured.
      const std::string rebound_text =
          law.rebound
              ? fmt::format("{:.6g}", rebound.get<double>())
              : "no closed form (measured on a two-slab impact: docs/guide/contact-laws.md, 'Which law for what')";
      fmt::print("{:<12} {}\n{:<12} {}; rebound at e = {}: {}\n", law.name, law.description, "", stiffness,
                 command.restitution, rebound_text);
      continue;
    }
    const auto or_null = [](std::string_view text) {
      return text.empty() ? nlohmann::json(nullptr) : nlohmann::json(text);
    };
    list.push_back({{"name", law.name},
                    {"description", law.description},
                    {"stiffness_key", or_null(law.stiffness_key)},
                    {"stiffness_unit", or_null(law.stiffness_unit)},
                    {"default_stiffness", law.default_stiffness},
                    {"stiffness_source", law.stiffness_source},
                    {"methods", law.methods},
                    {"restitution", command.restitution},
                    {"rebound", rebound}});
  }
  if (command.json) fmt::print("{}\n", list.dump(2));
  return 0;
}

}  // namespace pounding::cli
