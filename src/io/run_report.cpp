#include "pounding/io/run_report.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>

#include "pounding/analysis/contact_laws.hpp"

namespace pounding::io {
namespace {

/// "gap 0.2 m", or a row's "gaps B1:B2 0.2 m, B2:B3 0.1 m".
std::string gaps_text(const analysis::RunReport& report) {
  if (report.pairs.empty()) return fmt::format("gap {} m", report.gap_m);
  std::vector<std::string> gaps;
  for (const analysis::BuildingPair& p : report.pairs) {
    gaps.push_back(fmt::format("{}:{} {:.6g} m", report.building_names.at(static_cast<std::size_t>(p.first)),
                               report.building_names.at(static_cast<std::size_t>(p.second)), p.gap_m));
  }
  return fmt::format("gaps {}", fmt::join(gaps, ", "));
}

/// A fixed-step run (hht): its statistics and energy balance have their own terms.
bool fixed_step(const analysis::RunReport& report) { return report.used.method && !report.used.method->event_driven; }

/// "level 3 (B1 floor 3, B2 floor 2, 9 m)": where a contact is; `buildings` the pair (1-based).
std::string where(int level, const std::array<int, 2>& floors, double elevation_m,
                  const std::array<int, 2>& buildings = {1, 2}) {
  return fmt::format("level {} (B{} floor {}, B{} floor {}, {:.6g} m)", level, buildings[0], floors[0], buildings[1],
                     floors[1], elevation_m);
}
std::string where(const solvers::ContactIdentity& r) {
  if (r.level == 0) {  // slab to column: the slab's building strikes the column's
    return fmt::format("slab to column (B{} floor {}, {:.6g} m, on B{}'s storey {})", r.striking_building,
                       solvers::floor_of(r, r.striking_building), r.elevation_m, r.struck_building,
                       solvers::floor_of(r, r.struck_building));
  }
  return where(r.level, r.floors, r.elevation_m, r.buildings);
}

/// "B1 vertex 3" or, slab to column, "B1's slab on B2 column 4": who is in contact.
std::string who(const solvers::ContactIdentity& r) {
  if (r.level == 0) return fmt::format("B{}'s slab on B{} column {}", r.striking_building, r.struck_building, r.column);
  return fmt::format("B{} vertex {}", r.striking_building, r.vertex);
}

/// "B1 vertex 3 strikes" or, slab to column, "B1's slab strikes B2 column 4 at 0.5 of the storey".
std::string striker(const solvers::ImpactRecord& r) {
  if (r.level == 0) {
    return fmt::format("B{}'s slab strikes B{} column {} at {:.3g} of the storey height", r.striking_building,
                       r.struck_building, r.column, r.height_ratio);
  }
  return fmt::format("{} strikes", who(r));
}

/// " (0.5 of its capacity)", with the verdict above 1; empty without a capacity (NaN).
std::string capacity_text(double ratio) {
  if (std::isnan(ratio)) return {};
  return fmt::format(" ({:.3g} of its capacity{})", ratio,
                     ratio > 1.0 ? ": EXCEEDED, the column would fail in shear" : "");
}

/// Per struck column (building, column, storey): its slab-to-column impacts and the largest
/// peak force, with the shear and moment it causes (the impact's column_demand), and the largest
/// shear with the column's sway.
void append_column_demands(const std::vector<solvers::ImpactRecord>& impacts, std::string& text) {
  struct Column {
    int impacts = 0;
    const solvers::ImpactRecord* largest_force = nullptr;
    const solvers::ImpactRecord* largest_total = nullptr;
  };
  std::map<std::array<int, 3>, Column> worst;
  for (const solvers::ImpactRecord& i : impacts) {
    if (i.level != 0) continue;
    Column& column = worst[{i.struck_building, i.column, solvers::floor_of(i, i.struck_building)}];
    ++column.impacts;
    if (column.largest_force == nullptr || i.peak_force_kN > column.largest_force->peak_force_kN)
      column.largest_force = &i;
    if (column.largest_total == nullptr || i.column_total_shear_kN > column.largest_total->column_total_shear_kN)
      column.largest_total = &i;
  }
  if (worst.empty()) return;
  auto out = std::back_inserter(text);
  fmt::format_to(out, "Column demands (slab to column; the fixed-fixed column under the peak force):\n");
  for (const auto& [where, column] : worst) {
    const solvers::ImpactRecord& i = *column.largest_force;
    fmt::format_to(out,
                   "  B{} column {} storey {} at {:.3g}: {} impact{}, peak force {:.1f} kN at {:.4f} s, shear {:.1f} "
                   "kN{}, moment {:.1f} kN·m\n",
                   where[0], where[1], where[2], i.height_ratio, column.impacts, column.impacts == 1 ? "" : "s",
                   i.peak_force_kN, i.t_s, i.column_shear_kN, capacity_text(i.column_shear_ratio), i.column_moment_kNm);
    const solvers::ImpactRecord& total = *column.largest_total;
    fmt::format_to(out, "    with its sway shear: {:.1f} kN at {:.4f} s (sway {:.1f} kN){}\n",
                   total.column_total_shear_kN, total.column_total_shear_t_s, total.column_sway_shear_kN,
                   capacity_text(total.column_total_shear_ratio));
  }
}

void append_contacts(const analysis::RunReport& report, std::string& text) {
  const solvers::RunResult& r = report.result;
  auto out = std::back_inserter(text);
  std::map<int, int> by_level;
  for (const auto& i : r.impacts) ++by_level[i.level];
  fmt::format_to(out, "Impacts: {}", r.impacts.size());
  for (const auto& [level, count] : by_level) {
    if (level == 0) continue;
    const contact::Level& l = report.levels.at(static_cast<std::size_t>(level - 1));
    fmt::format_to(out, "; {}: {}", where(l.index, l.floors, l.elevation_m, {l.pair[0] + 1, l.pair[1] + 1}), count);
  }
  if (by_level.count(0)) fmt::format_to(out, "; slab to column: {}", by_level[0]);
  text += '\n';
  if (!r.impacts.empty()) {
    const auto& first = r.impacts.front();
    fmt::format_to(out, "  first at t = {:.6f} s on {} ({}), approach {:.4f} m/s, impulse {:.2f} kN·s\n", first.t_s,
                   where(first), striker(first), first.approach_velocity_mps, first.impulse_kNs);
  }
  append_column_demands(r.impacts, text);
  fmt::format_to(out, "Touches (contact without impact): {}\n", r.touches.size());
  for (const auto& t : r.touches) {
    fmt::format_to(out, "  t = {:.6f} s, {}, {}\n", t.t_s, where(t), who(t));
  }
  fmt::format_to(out, "Sustained contacts: {}\n", r.sustained_contacts.size());
  for (const auto& s : r.sustained_contacts) {
    fmt::format_to(out, "  {}, {}: {:.6f} s to {:.6f} s ({}), max force {:.1f} kN\n", where(s), who(s), s.start_s,
                   s.release_s, s.release_reason, s.max_force_kN);
  }
}

/// Per floor: the peak absolute accelerations (m/s² and g) and the drift ratios of the storey
/// below it (%, at the CM and at the worst corner), each with its instant: the groups computed.
void append_design_peaks(const analysis::RunReport& report, std::string& text) {
  const solvers::OutputSelection& outputs = report.result.outputs;
  if (!outputs.acceleration_peaks && !outputs.drift_peaks) return;
  auto out = std::back_inserter(text);
  const double g = report.g_mps2;
  const char* part = report.contact_law == "impulse" ? "smooth part: each impact adds an impulse (impacts)"
                                                     : "contact forces included";
  for (const auto& building : report.result.peaks) {
    if (outputs.acceleration_peaks) {
      fmt::format_to(out, "{} of {} (absolute accelerations, {}):\n",
                     outputs.drift_peaks ? "Accelerations and storey drifts" : "Accelerations", building.name, part);
    } else {
      fmt::format_to(out, "Storey drifts of {}:\n", building.name);
    }
    for (const auto& f : building.floors) {
      fmt::format_to(out, "  floor {}: ", f.floor);
      if (outputs.acceleration_peaks) {
        fmt::format_to(out, "|ax| {:.3f} m/s² = {:.3f} g at {:.3f} s, |ay| {:.3f} m/s² = {:.3f} g at {:.3f} s{}",
                       std::abs(f.ax_abs_mps2.value), std::abs(f.ax_abs_mps2.value) / g, f.ax_abs_mps2.t_s,
                       std::abs(f.ay_abs_mps2.value), std::abs(f.ay_abs_mps2.value) / g, f.ay_abs_mps2.t_s,
                       outputs.drift_peaks ? "; " : "");
      }
      if (outputs.drift_peaks) {
        const solvers::WorstCornerDrift corner = solvers::worst_corner_drift(f);
        fmt::format_to(out, "drift x {:.3f} % at {:.3f} s, y {:.3f} % at {:.3f} s, corner {} {} {:.3f} % at {:.3f} s",
                       100 * std::abs(f.drift_x.value), f.drift_x.t_s, 100 * std::abs(f.drift_y.value), f.drift_y.t_s,
                       corner.corner, corner.axis, 100 * std::abs(corner.peak.value), corner.peak.t_s);
      }
      text += '\n';
    }
  }
}

/// Per storey of a yielding building: its largest ductility in x and y, first yield and
/// hysteretic energy (the per-column values are in yielding.csv).
void append_yielding(const analysis::RunReport& report, std::string& text) {
  if (report.springs.empty()) return;
  auto out = std::back_inserter(text);
  // A storey given as a matrix yields as storey springs (docs/model.md §2a), not as columns.
  const auto storey_spring = [](const dynamics::YieldingSpring& s) { return s.column.starts_with("storey_stiffness"); };
  const std::size_t storey_springs = std::count_if(report.springs.begin(), report.springs.end(), storey_spring);
  const std::string_view what = storey_springs == 0                       ? "columns"
                                : storey_springs == report.springs.size() ? "storey springs"
                                                                          : "columns and storey springs";
  fmt::format_to(out, "Yielding {}: {} yield events, hysteretic energy {:.3f} kJ\n", what,
                 report.result.statistics.yield_events, report.result.energy.hysteretic_kJ);
  for (const analysis::StoreyYielding& s : analysis::storey_yielding(report.springs, report.result.springs)) {
    fmt::format_to(
        out, "  B{} storey {}: ductility x {:.3f}, y {:.3f}; {}; hysteretic {:.3f} kJ\n", s.building + 1, s.storey,
        s.peak_ductility[0], s.peak_ductility[1],
        std::isfinite(s.first_yield_t_s) ? fmt::format("first yield {:.6f} s", s.first_yield_t_s) : "elastic",
        s.hysteretic_kJ);
    if (s.degrading_springs > 0) {
      fmt::format_to(out, "    degrading columns: {} of {} springs failed by their law and lost their force{}\n",
                     s.degrading_failures, s.degrading_springs,
                     s.degrading_failures > 0 ? fmt::format(", first at {:.6f} s", s.first_degrading_failure_t_s) : "");
    }
    if (s.springs_with_capacity == 0) continue;
    fmt::format_to(
        out,
        "    column shear: {} of {} springs reached their capacity{}; largest demand/capacity {:.3f} ({:.1f} kN of "
        "{:.1f} kN, {} {})\n",
        s.shear_failures, s.springs_with_capacity,
        s.shear_failures > 0 ? fmt::format(", first at {:.6f} s", s.first_shear_failure_t_s) : "",
        s.largest_demand_capacity_ratio, s.critical_peak_force_kN, s.critical_capacity_kN, s.critical_column,
        s.critical_direction);
  }
}

/// The struck columns that reached their shear capacity under a slab's push (or that none did).
void append_struck_column_failures(const analysis::RunReport& report, std::string& text) {
  const solvers::RunResult& r = report.result;
  if (!r.struck_columns_watched) return;
  auto out = std::back_inserter(text);
  if (r.struck_column_failures.empty()) {
    fmt::format_to(out, "Struck columns: none reached its shear capacity with its sway\n");
    return;
  }
  fmt::format_to(out, "Struck columns failed in shear (the push's shear with the sway at the capacity): {}\n",
                 r.struck_column_failures.size());
  for (const solvers::StruckColumnFailure& f : r.struck_column_failures) {
    fmt::format_to(
        out, "  {} {} storey {} along {} at {:.6f} s: {:.4g} kN of {:.4g} kN (sway {:.4g} kN, force {:.4g} kN){}{}\n",
        r.peaks.at(static_cast<std::size_t>(f.struck_building - 1)).name, f.column_key, f.storey,
        f.axis == 0 ? "x" : "y", f.t_s, f.shear_kN, f.capacity_kN, f.sway_shear_kN, f.force_kN,
        f.sway_over_capacity ? "; its sway alone was over it as the push began" : "",
        f.loses_stiffness ? "; loses its stiffness" : "");
  }
}

/// Per building with member forces: its largest storey shear along x and y and torque, and its
/// largest column shear, each with its storey and instant.
void append_member_forces(const analysis::RunReport& report, std::string& text) {
  using Kind = solvers::MemberForce::Kind;
  const solvers::RunResult& r = report.result;
  if (r.member_forces.empty()) return;
  std::vector<std::array<const solvers::MemberForce*, 4>> largest(r.peaks.size());  // Vx, Vy, T, column V
  auto keep = [](const solvers::MemberForce*& held, const solvers::MemberForce& q) {
    if (held == nullptr || std::abs(q.peak.value) > std::abs(held->peak.value)) held = &q;
  };
  for (const solvers::MemberForce& q : r.member_forces) {
    auto& held = largest.at(static_cast<std::size_t>(q.building));
    if (q.column >= 0) {
      if (q.kind == Kind::shear_x || q.kind == Kind::shear_y) keep(held[3], q);
    } else {
      keep(held[static_cast<std::size_t>(q.kind)], q);
    }
  }
  auto out = std::back_inserter(text);
  for (std::size_t b = 0; b < largest.size(); ++b) {
    const auto& [vx, vy, torque, column] = largest[b];
    if (vx == nullptr) continue;
    auto at = [](const solvers::MemberForce& q) {
      return fmt::format("storey {}, t = {:.4f} s", q.storey, q.peak.t_s);
    };
    fmt::format_to(
        out, "Member forces {}: storey shear |Vx| {:.1f} kN ({}), |Vy| {:.1f} kN ({}), torque |T| {:.1f} kNm ({})",
        r.peaks[b].name, std::abs(vx->peak.value), at(*vx), std::abs(vy->peak.value), at(*vy),
        std::abs(torque->peak.value), at(*torque));
    if (column != nullptr) {
      fmt::format_to(out, "; column shear |V| {:.1f} kN ({} along {}, {})", std::abs(column->peak.value),
                     column->column_key, column->kind == Kind::shear_x ? "x" : "y", at(*column));
    }
    fmt::format_to(out, "\n");
  }
}

/// Per storey: the peak drift ratios at the CM with contact over those of the contact-free run.
void append_pounding_demand(const analysis::RunReport& report, std::string& text) {
  if (!report.contact_free) return;
  const solvers::RunResult& with = report.result;
  const solvers::RunResult& without = *report.contact_free;
  auto out = std::back_inserter(text);
  auto ratio = [](double a, double b) {
    return std::abs(b) > analysis::kDemandFloor ? fmt::format("x{:.3f}", std::abs(a) / std::abs(b)) : "-";
  };
  fmt::format_to(out, "Pounding-induced demand (peak storey drift ratio at the CM, with contact / without):\n");
  for (std::size_t b = 0; b < with.peaks.size(); ++b) {
    for (std::size_t f = 0; f < with.peaks[b].floors.size(); ++f) {
      const solvers::FloorPeaks& p = with.peaks[b].floors[f];
      const solvers::FloorPeaks& q = without.peaks[b].floors[f];
      fmt::format_to(out, "  {} storey {}: x {:.3f} % / {:.3f} % ({}), y {:.3f} % / {:.3f} % ({})\n",
                     with.peaks[b].name, p.floor, 100.0 * std::abs(p.drift_x.value), 100.0 * std::abs(q.drift_x.value),
                     ratio(p.drift_x.value, q.drift_x.value), 100.0 * std::abs(p.drift_y.value),
                     100.0 * std::abs(q.drift_y.value), ratio(p.drift_y.value, q.drift_y.value));
    }
  }
}

/// "IO 1 % exceeded (by 0.35 %), LS 2 % met (margin 0.65 %), CP 4 % met (margin 2.65 %)".
std::string verdicts_text(const std::array<analysis::LevelVerdict, 3>& levels) {
  std::vector<std::string> parts;
  for (const analysis::LevelVerdict& v : levels) {
    parts.push_back(fmt::format("{} {:g} % {} ({} {:.3f} %)", v.level, 100.0 * v.drift_ratio,
                                v.exceeded ? "exceeded" : "met", v.exceeded ? "by" : "margin",
                                100.0 * std::abs(v.margin)));
  }
  return fmt::format("{}", fmt::join(parts, ", "));
}

/// Per building with [building.limit_states]: its peak storey drift ratio against each level.
void append_limit_states(const analysis::RunReport& report, std::string& text) {
  auto out = std::back_inserter(text);
  for (const analysis::DriftLimitState& state : report.limit_states) {
    const analysis::PeakStoreyDrift& p = state.peak;
    fmt::format_to(out, "Limit states {} ({}): peak storey drift {:.3f} % (storey {}, {} {}, t = {:.4f} s): {}\n",
                   state.name, state.structural_type, 100.0 * p.ratio, p.storey, p.where, p.axis, p.t_s,
                   verdicts_text(state.levels));
    if (state.peak_without_contact) {
      fmt::format_to(out, "  without contact: peak storey drift {:.3f} % (storey {}): {}\n",
                     100.0 * state.peak_without_contact->ratio, state.peak_without_contact->storey,
                     verdicts_text(*state.levels_without_contact));
    }
  }
}

/// Per building: its largest residual drift, whether it had come to rest, and every storey's.
void append_residual_drifts(const analysis::RunReport& report, std::string& text) {
  auto out = std::back_inserter(text);
  for (const analysis::BuildingResidualDrift& b : report.residual_drifts) {
    const analysis::StoreyResidualDrift& worst = b.largest;
    fmt::format_to(
        out, "Residual drift {} at t = {:.3f} s{}: largest {:.4f} % (storey {}, {} {}), {}\n", b.name,
        report.result.end_s,
        report.free_vibration_s > 0.0 ? fmt::format(" (after a {:g} s quiet tail)", report.free_vibration_s) : "",
        100.0 * worst.largest, worst.storey, worst.where, worst.axis,
        b.settled ? fmt::format("at rest (oscillation {:.4f} %)", 100.0 * b.oscillation)
                  : fmt::format("still oscillating by about {:.4f} %: [excitation] free_vibration_s lets "
                                "it come to rest",
                                100.0 * b.oscillation));
    if (b.damage_state) {
      const analysis::ResidualDamageState& state = analysis::residual_damage_states()[*b.damage_state];
      fmt::format_to(out, "  damage state {} (residual drift from {:g} %): {}\n", state.name, 100.0 * state.drift_ratio,
                     state.meaning);
    } else {
      fmt::format_to(out, "  below damage state DS1 ({:g} %)\n",
                     100.0 * analysis::residual_damage_states()[0].drift_ratio);
    }
    for (const analysis::StoreyResidualDrift& s : b.storeys) {
      fmt::format_to(out, "  storey {}: x {:.4f} %, y {:.4f} % at the CM; largest {:.4f} % ({} {})\n", s.storey,
                     100.0 * s.x, 100.0 * s.y, 100.0 * s.largest, s.where, s.axis);
    }
  }
}

void append_response(const analysis::RunReport& report, std::string& text) {
  const solvers::RunResult& r = report.result;
  auto out = std::back_inserter(text);
  // The top level is where the buildings pound hardest; each building's own floor there (a row:
  // its highest floor at a level).
  for (std::size_t b = 0; b < r.peaks.size() && !report.levels.empty() && r.outputs.displacement_peaks; ++b) {
    int top_floor = 0;
    for (const contact::Level& l : report.levels) {
      for (int side = 0; side < 2; ++side) {
        if (l.pair[side] == static_cast<int>(b)) top_floor = std::max(top_floor, l.floors[side]);
      }
    }
    if (top_floor == 0) continue;  // a row's building at no level
    const auto& building = r.peaks[b];
    const auto& top = building.floors.at(static_cast<std::size_t>(top_floor - 1));
    fmt::format_to(
        out, "Peaks {} floor {}: |u| {:.2f} cm at {:.3f} s, |v| {:.2f} cm at {:.3f} s, |φ| {:.3e} rad at {:.3f} s\n",
        building.name, top.floor, 100 * std::abs(top.u_m.value), top.u_m.t_s, 100 * std::abs(top.v_m.value),
        top.v_m.t_s, std::abs(top.phi_rad.value), top.phi_rad.t_s);
  }
  append_design_peaks(report, text);
  append_yielding(report, text);
  append_member_forces(report, text);
  append_struck_column_failures(report, text);
  append_pounding_demand(report, text);
  append_limit_states(report, text);
  append_residual_drifts(report, text);
  const auto& st = r.statistics;
  if (st.max_interpenetration_candidate >= 0) {
    fmt::format_to(
        out, "Largest overlap: {:.3e} m at {:.6f} s, {}\n", st.max_interpenetration_m, st.max_interpenetration_t_s,
        contact::describe(report.candidates.at(static_cast<std::size_t>(st.max_interpenetration_candidate))));
  } else {
    text += "Largest overlap: none\n";
  }
  const auto& e = r.energy;
  std::string algorithmic =
      fixed_step(report) ? fmt::format(", algorithmic dissipation {:.3f} kJ", e.algorithmic_dissipation_kJ) : "";
  if (!report.springs.empty()) algorithmic += fmt::format(", hysteretic {:.3f} kJ", e.hysteretic_kJ);
  fmt::format_to(
      out, "Energy: input {:.3f} kJ, damping {:.3f} kJ, impacts {:.3f} kJ{}, residual {:.3e} kJ ({:.2e} of input)\n",
      e.input_kJ, e.damping_kJ, e.impact_loss_kJ, algorithmic, e.residual_kJ(),
      e.input_kJ != 0 ? e.residual_kJ() / e.input_kJ : 0.0);
}

void append_solver(const analysis::RunReport& report, std::string& text) {
  const solvers::RunResult& r = report.result;
  const auto& s = r.statistics;
  auto out = std::back_inserter(text);
  if (fixed_step(report)) {
    fmt::format_to(
        out,
        "Solver: {} steps ({} solves), {} factorisations, {} halvings, smallest step {:.3e} s, {} unresolved; "
        "run time {:.3f} s\n",
        s.steps, s.rhs_evaluations, s.jacobian_evaluations, s.halvings, s.smallest_step_s, s.unresolved_contacts,
        s.wall_time_s);
  } else {
    fmt::format_to(out, "Solver: {} steps, {} rhs, {} root evaluations, {} Jacobians, {} restarts; run time {:.3f} s\n",
                   s.steps, s.rhs_evaluations, s.root_evaluations, s.jacobian_evaluations, s.restarts, s.wall_time_s);
  }
  if (s.corner_candidates > 0) {
    fmt::format_to(out,
                   "Corners: {} corner candidates (a vertex and a side edge, or an edge facing away), {} of them "
                   "armed; {} contacts handed round a corner\n",
                   s.corner_candidates, s.corner_candidates_armed, s.corner_handovers);
  }
  if (s.iterative_lcp_solves > 0) {
    fmt::format_to(
        out,
        "Contact problems solved by projected Gauss-Seidel (more than 12 coupled contacts, or no exact active "
        "set): {}, largest relative residual {:.1e}\n",
        s.iterative_lcp_solves, s.largest_lcp_residual);
  }
}

/// One line per warning, each after a line break (the brief report has no final one).
void append_warnings(const analysis::RunReport& report, std::string& text) {
  for (const analysis::RunWarning& warning : report.warnings) {
    if (!text.empty() && text.back() != '\n') text += '\n';
    fmt::format_to(std::back_inserter(text), "Warning ({}): {}", warning.code, warning.message);
  }
}

}  // namespace

std::string method_settings_text(const analysis::RunReport& report) {
  return analysis::describe_used_settings(report.used);
}

std::string brief_report(const analysis::RunReport& report) {
  const solvers::RunResult& r = report.result;
  const std::string first = r.impacts.empty() ? "" : fmt::format(", first at t = {:.6f} s", r.impacts.front().t_s);
  std::string text =
      fmt::format("{}: {}, {}, {} impact{}{}, run time {:.3f} s", report.scene, r.method, solvers::to_string(r.status),
                  r.impacts.size(), r.impacts.size() == 1 ? "" : "s", first, r.statistics.wall_time_s);
  append_warnings(report, text);
  return text;
}

std::string full_report(const analysis::RunReport& report) {
  const solvers::RunResult& r = report.result;
  const analysis::ContactLawInfo& info = analysis::contact_law_info(report.contact_law);
  const std::string law =
      info.stiffness_key.empty()
          ? std::string()
          : fmt::format(", {} law k_c = {:.6g} {}, {} = {:.4g}", report.contact_law, report.contact_stiffness,
                        info.stiffness_unit, info.damping_key == "damping_ratio" ? "xi" : "xi v0/k_h",
                        report.contact_damping);
  std::string text =
      fmt::format("Run '{}' with {} ({}), {}, k = {}{}: {}{}\n", report.scene, r.method, method_settings_text(report),
                  gaps_text(report), report.restitution, law, solvers::to_string(r.status),
                  r.status_detail.empty() ? "" : " (" + r.status_detail + ")");
  append_contacts(report, text);
  append_response(report, text);
  append_solver(report, text);
  append_warnings(report, text);
  if (!report.warnings.empty()) text += '\n';
  return text;
}

}  // namespace pounding::io
