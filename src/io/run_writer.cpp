#include "pounding/io/run_writer.hpp"

#include <algorithm>
#include <fmt/compile.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>

#include "pounding/analysis/contact_laws.hpp"
#include "pounding/io/impact_schema.hpp"
#include "pounding/io/json_report.hpp"
#include "pounding/io/output_schema.hpp"
#include "pounding/io/output_files.hpp"
#include "run_csv.hpp"

namespace pounding::io {
namespace {

// Keys in the order written, so a reader finds scene, method and status first (README.md).
using json = nlohmann::ordered_json;

json point(const model::Point2& p) { return json::array({p.x(), p.y()}); }

/// Where the contact is (its level, the floor of each building there, building 1's first, and
/// the level's elevation), then `fields`. Candidates and every contact record carry these three.
/// A row's: `buildings`, the pair (1-based) whose floors `floors` are, after them.
template <class Located>
json at_level(const Located& where, const json& fields, bool row = false) {
  json located = {{"level", where.level}, {"floors", where.floors}, {"elevation_m", where.elevation_m}};
  if constexpr (requires { where.buildings; }) {
    if (row) located["buildings"] = where.buildings;
  } else {
    if (row) located["buildings"] = {where.pair[0] + 1, where.pair[1] + 1};
  }
  located.update(fields);
  return located;
}

/// `before`, then who strikes whom as the impacts name it (striking_building; struck_building in a
/// row or where slabs can strike columns; vertex; column where slabs can strike columns), then `after`.
json who(const solvers::ContactIdentity& c, ImpactFieldSet set, json before, const json& after) {
  before["striking_building"] = c.striking_building;
  if (set.row || set.slab_to_column) before["struck_building"] = c.struck_building;
  before["vertex"] = c.vertex;
  if (set.slab_to_column) before["column"] = c.column;
  before.update(after);
  return before;
}

json levels_json(const std::vector<contact::Level>& levels, bool row) {
  json list = json::array();
  for (const contact::Level& l : levels) {
    list.push_back({{"level", l.index}, {"floors", l.floors}, {"elevation_m", l.elevation_m}});
    if (row) list.back()["buildings"] = {l.pair[0] + 1, l.pair[1] + 1};
  }
  return list;
}

/// A row's neighbouring pairs: buildings (1-based), names, gap, and the impacts between them.
json pairs_json(const analysis::RunReport& report) {
  json list = json::array();
  for (const analysis::BuildingPair& p : report.pairs) {
    const std::array<int, 2> buildings{p.first + 1, p.second + 1};
    const auto impacts = std::count_if(report.result.impacts.begin(), report.result.impacts.end(),
                                       [&](const solvers::ImpactRecord& i) { return i.buildings == buildings; });
    list.push_back({{"buildings", buildings},
                    {"names",
                     {report.building_names.at(static_cast<std::size_t>(p.first)),
                      report.building_names.at(static_cast<std::size_t>(p.second))}},
                    {"gap_m", p.gap_m},
                    {"direction", point(p.direction)},
                    {"impacts", impacts}});
  }
  return list;
}

json candidates_json(const std::vector<contact::Candidate>& candidates, bool row) {
  json list = json::array();
  for (const contact::Candidate& c : candidates) {
    list.push_back(at_level(c,
                            {{"striking_building", c.striking_building + 1},
                             {"vertex", contact::vertex_number(c)},
                             {"vertex_rest", point(c.vertex_rest)},
                             {"struck_building", c.struck_building + 1},
                             {"edge", c.edge_index + 1},
                             {"edge_rest", json::array({point(c.edge_start_rest), point(c.edge_end_rest)})}},
                            row));
    if (c.corner) list.back()["corner"] = true;  // reachable only round a corner (docs/model.md §4)
    if (c.column) {  // the column point (striking building's column) against the slab's edge
      list.back().update({{"column", c.column_index + 1},
                          {"storey", c.floor_of(c.striking_building)},
                          {"storey_height_m", c.storey_height_m},
                          {"height_ratio", c.height_ratio},
                          {"local_flexibility_m_per_kN", c.flexibility_m_per_kN}});
    }
  }
  return list;
}

json impacts_json(const std::vector<solvers::ImpactRecord>& impacts, ImpactFieldSet fields) {
  json list = json::array();
  for (const auto& i : impacts) list.push_back(impact_json(i, fields));
  return list;
}

/// Per building (with its contact vertices) and floor, the peak groups `outputs` asked for.
json peaks_json(const std::vector<solvers::BuildingPeaks>& peaks, const solvers::OutputSelection& outputs,
                double g_mps2) {
  json list = json::array();
  for (const auto& building : peaks) {
    json vertices = json::array(), floors = json::array();
    for (const auto& v : building.contact_vertices_rest) vertices.push_back(point(v));
    for (const auto& f : building.floors) {
      json floor = {{"floor", f.floor}};
      for (const PeakField& field : peak_fields()) {
        if (asked(outputs, field.group)) floor[std::string(field.key)] = field.value(f, g_mps2);
      }
      floors.push_back(floor);
    }
    list.push_back({{"building", building.name},
                    {"contact_vertices", building.contact_vertices},
                    {"contact_vertices_rest", vertices},
                    {"floors", floors}});
  }
  return list;
}

/// Which outputs the run computed ([output] history and peaks).
json outputs_json(const solvers::OutputSelection& outputs) {
  json groups = json::array();
  for (std::size_t k = 0; k < analysis::kPeakGroups.size(); ++k) {
    if (asked(outputs, static_cast<PeakField::Group>(k))) groups.push_back(analysis::kPeakGroups[k]);
  }
  json selection = {{"history", outputs.history}, {"peaks", groups}};
  if (outputs.member_forces) selection["member_forces"] = true;
  return selection;
}

json energy_json(const solvers::EnergyAudit& e, bool yielding) {
  json energy;
  for (const EnergyField& field : energy_fields()) {
    if (!field.yielding_only || yielding) energy[std::string(field.key)] = field.value(e);
  }
  return energy;
}

json finite_or_null(double value) { return std::isfinite(value) ? json(value) : json(nullptr); }

/// Per building and storey: the largest ductility in x and y over its columns, the first yield,
/// the hysteretic energy and the yielded springs (docs/model.md, "Yielding columns").
json yielding_json(const analysis::RunReport& report) {
  json buildings = json::array();
  for (const analysis::StoreyYielding& s : analysis::storey_yielding(report.springs, report.result.springs)) {
    if (buildings.empty() || buildings.back()["building"] != s.building + 1) {
      buildings.push_back({{"building", s.building + 1}, {"storeys", json::array()}});
    }
    json storey = {{"storey", s.storey},
                   {"peak_ductility_x", s.peak_ductility[0]},
                   {"peak_ductility_y", s.peak_ductility[1]},
                   {"first_yield_t_s", finite_or_null(s.first_yield_t_s)},
                   {"springs_yielded", s.springs_yielded},
                   {"springs", s.springs},
                   {"hysteretic_kJ", s.hysteretic_kJ}};
    if (s.degrading_springs > 0) {
      storey["degrading"] = {{"springs", s.degrading_springs},
                             {"failures", s.degrading_failures},
                             {"first_failure_t_s", finite_or_null(s.first_degrading_failure_t_s)}};
    }
    if (s.springs_with_capacity > 0) {
      storey["column_shear"] = {{"springs_with_capacity", s.springs_with_capacity},
                                {"failures", s.shear_failures},
                                {"first_failure_t_s", finite_or_null(s.first_shear_failure_t_s)},
                                {"largest_demand_capacity_ratio", s.largest_demand_capacity_ratio},
                                {"critical_column", s.critical_column},
                                {"critical_direction", std::string(1, s.critical_direction)},
                                {"critical_peak_force_kN", s.critical_peak_force_kN},
                                {"critical_shear_capacity_kN", s.critical_capacity_kN}};
    }
    buildings.back()["storeys"].push_back(std::move(storey));
  }
  // "bilinear", "bouc-wen", "imk-peak-oriented", "imk-pinching", or "mixed" when the buildings'
  // columns follow different laws.
  std::string law;
  for (const dynamics::YieldingSpring& spring : report.springs) {
    const std::string own = spring.bouc_wen                      ? "bouc-wen"
                            : spring.imk && spring.imk->pinching ? "imk-pinching"
                            : spring.imk                         ? "imk-peak-oriented"
                                                                 : "bilinear";
    law = law.empty() || law == own ? own : "mixed";
  }
  return {{"law", law},
          {"yield_events", report.result.statistics.yield_events},
          {"hysteretic_kJ", report.result.energy.hysteretic_kJ},
          {"per_spring", "yielding.csv"},
          {"buildings", buildings}};
}

/// A peak with and without contact, and their ratio: null where the contact-free one is below
/// kDemandFloor (a drift ratio or ductility of round-off size, e.g. y drift under x shaking).
json with_without(double with, double without) {
  return {{"with", with},
          {"without", without},
          {"ratio", without > analysis::kDemandFloor ? json(with / without) : json(nullptr)}};
}

json peak_drift_json(const analysis::PeakStoreyDrift& peak) {
  return {{"drift_ratio", peak.ratio},
          {"t_s", peak.t_s},
          {"storey", peak.storey},
          {"where", peak.where},
          {"axis", std::string(1, peak.axis)}};
}

json verdicts_json(const std::array<analysis::LevelVerdict, 3>& levels) {
  json list = json::array();
  for (const analysis::LevelVerdict& v : levels) {
    list.push_back({{"level", v.level},
                    {"drift_ratio_limit", v.drift_ratio},
                    {"limit_from", v.given ? "scene" : "structural_type"},
                    {"exceeded", v.exceeded},
                    {"margin", v.margin}});
  }
  return list;
}

/// Per building with [building.limit_states]: the peak storey drift ratio and each performance
/// level's verdict, with contact and (with the contact-free reference) without.
json limit_states_json(const analysis::RunReport& report) {
  json buildings = json::array();
  for (const analysis::DriftLimitState& state : report.limit_states) {
    json entry = {{"building", state.name},
                  {"structural_type", state.structural_type},
                  {"peak_storey_drift", peak_drift_json(state.peak)},
                  {"levels", verdicts_json(state.levels)}};
    if (state.peak_without_contact) {
      entry["without_contact"] = {{"peak_storey_drift", peak_drift_json(*state.peak_without_contact)},
                                  {"levels", verdicts_json(*state.levels_without_contact)}};
    }
    buildings.push_back(std::move(entry));
  }
  return {{"measure", "largest |storey drift ratio| over storeys, the CM and the slab corners, along x and y"},
          {"source", "FEMA 356 Table C1-3 (indicative transient drifts) unless the scene gives a limit"},
          {"buildings", buildings}};
}

json residual_json(const analysis::StoreyResidualDrift& storey) {
  return {{"storey", storey.storey},
          {"drift_ratio_x", storey.x},
          {"drift_ratio_y", storey.y},
          {"largest_drift_ratio", storey.largest},
          {"where", storey.where},
          {"axis", std::string(1, storey.axis)},
          {"oscillation_ratio", storey.oscillation}};
}

/// FEMA P-58's residual drift damage states, which each building's damage_state names.
json damage_states_json() {
  json states = json::array();
  for (const analysis::ResidualDamageState& s : analysis::residual_damage_states()) {
    states.push_back({{"name", s.name}, {"drift_ratio", s.drift_ratio}, {"meaning", s.meaning}});
  }
  return states;
}

/// Per building: every storey's drift ratio at the end of the run (FEMA P-58's residual drift once
/// at rest), the largest, and whether the building had come to rest.
json residual_drift_json(const analysis::RunReport& report) {
  json buildings = json::array();
  for (const analysis::BuildingResidualDrift& building : report.residual_drifts) {
    json storeys = json::array();
    for (const analysis::StoreyResidualDrift& storey : building.storeys) storeys.push_back(residual_json(storey));
    buildings.push_back(
        {{"building", building.name},
         {"first_period_s", building.first_period_s},
         {"largest", residual_json(building.largest)},
         {"oscillation_ratio", building.oscillation},
         {"settled", building.settled},
         {"damage_state", building.damage_state ? json(analysis::residual_damage_states()[*building.damage_state].name)
                                                : json(nullptr)},
         {"storeys", storeys}});
  }
  return {{"measure",
           "storey drift ratio at the end of the run (the CM's along x and y, signed; the largest |ratio| over the CM "
           "and the slab corners)"},
          {"t_s", report.result.end_s},
          {"free_vibration_s", report.free_vibration_s},
          {"oscillation",
           "|drift ratio rate| / omega_1 at the end, largest over the points: a first-mode vibration's amplitude still "
           "going on"},
          {"settled", fmt::format("oscillation at most a tenth of the largest residual or below {:g}",
                                  analysis::kSettledOscillation)},
          {"damage_states", damage_states_json()},
          {"buildings", buildings}};
}

/// Each storey's peak |V_x|, |V_y| (kN) by building and storey (1-based: [b][storey − 1]); empty
/// without member forces.
std::vector<std::vector<std::array<double, 2>>> storey_shear_peaks(const solvers::RunResult& result) {
  std::vector<std::vector<std::array<double, 2>>> peaks(result.member_forces.empty() ? 0 : result.peaks.size());
  for (const solvers::MemberForce& q : result.member_forces) {
    if (q.column >= 0 || q.kind == solvers::MemberForce::Kind::torque) continue;
    auto& storeys = peaks.at(static_cast<std::size_t>(q.building));
    if (storeys.size() < static_cast<std::size_t>(q.storey)) storeys.resize(static_cast<std::size_t>(q.storey));
    storeys[static_cast<std::size_t>(q.storey - 1)][q.kind == solvers::MemberForce::Kind::shear_x ? 0 : 1] =
        std::abs(q.peak.value);
  }
  return peaks;
}

/// The pounding-induced change of each storey's peak drift ratio at the CM (and of its columns'
/// ductility, when they yield, and of its shear, with member forces) against the same run
/// without contact.
json pounding_demand_json(const analysis::RunReport& report) {
  const solvers::RunResult& with = report.result;
  const solvers::RunResult& without = *report.contact_free;
  std::vector<analysis::StoreyYielding> yield_with, yield_without;
  if (!report.springs.empty()) {
    yield_with = analysis::storey_yielding(report.springs, with.springs);
    yield_without = analysis::storey_yielding(report.springs, without.springs);
  }
  const auto shear_with = storey_shear_peaks(with), shear_without = storey_shear_peaks(without);
  json buildings = json::array();
  for (std::size_t b = 0; b < with.peaks.size(); ++b) {
    json storeys = json::array();
    for (std::size_t f = 0; f < with.peaks[b].floors.size(); ++f) {
      const solvers::FloorPeaks& a = with.peaks[b].floors[f];
      const solvers::FloorPeaks& c = without.peaks[b].floors[f];
      json storey = {{"storey", a.floor},
                     {"drift_x", with_without(std::abs(a.drift_x.value), std::abs(c.drift_x.value))},
                     {"drift_y", with_without(std::abs(a.drift_y.value), std::abs(c.drift_y.value))}};
      if (!shear_with.empty() && !shear_without.empty()) {
        const std::size_t j = static_cast<std::size_t>(a.floor - 1);
        storey["storey_shear_x_kN"] = with_without(shear_with[b].at(j)[0], shear_without[b].at(j)[0]);
        storey["storey_shear_y_kN"] = with_without(shear_with[b].at(j)[1], shear_without[b].at(j)[1]);
      }
      for (std::size_t k = 0; k < yield_with.size(); ++k) {
        if (yield_with[k].building != static_cast<int>(b) || yield_with[k].storey != a.floor) continue;
        storey["ductility_x"] = with_without(yield_with[k].peak_ductility[0], yield_without[k].peak_ductility[0]);
        storey["ductility_y"] = with_without(yield_with[k].peak_ductility[1], yield_without[k].peak_ductility[1]);
        storey["column_force_x_kN"] =
            with_without(yield_with[k].peak_column_force_kN[0], yield_without[k].peak_column_force_kN[0]);
        storey["column_force_y_kN"] =
            with_without(yield_with[k].peak_column_force_kN[1], yield_without[k].peak_column_force_kN[1]);
      }
      storeys.push_back(std::move(storey));
    }
    buildings.push_back({{"building", with.peaks[b].name}, {"storeys", storeys}});
  }
  json demand = {{"reference", "the same scene and method without contact"},
                 {"reference_status", solvers::to_string(without.status)},
                 {"drift", "peak drift ratio of the storey below each floor, at the CM (as peaks' drift_x, drift_y)"},
                 {"column_force",
                  "yielding columns: the largest peak |force| of the storey's columns along x, y (kN; "
                  "yielding.csv's peak_force_kN)"},
                 {"buildings", buildings}};
  if (!shear_with.empty()) demand["storey_shear"] = "the storey's peak |Vx|, |Vy| (kN; member_forces)";
  return demand;
}

/// The struck columns that reached their shear capacity under a slab's push, in order of time.
json struck_column_failures_json(const solvers::RunResult& result) {
  json failures = json::array();
  for (const solvers::StruckColumnFailure& f : result.struck_column_failures) {
    failures.push_back({{"t_s", f.t_s},
                        {"struck_building", f.struck_building},
                        {"column", f.column},
                        {"column_key", f.column_key},
                        {"column_rest", point(f.column_rest)},
                        {"storey", f.storey},
                        {"axis", f.axis == 0 ? "x" : "y"},
                        {"striking_building", f.striking_building},
                        {"floors", f.floors},
                        {"candidate", f.candidate},
                        {"capacity_kN", f.capacity_kN},
                        {"shear_kN", f.shear_kN},
                        {"ratio", f.shear_kN / f.capacity_kN},
                        {"sway_shear_kN", f.sway_shear_kN},
                        {"force_kN", f.force_kN},
                        {"sway_over_capacity", f.sway_over_capacity},
                        {"loses_stiffness", f.loses_stiffness}});
  }
  return {{"definition",
           "a struck column whose shear with its sway, the larger of |V_s + N1 F n_a| and |V_s - N2 F n_a| along the "
           "plan axis nearer the edge's normal, reached its shear capacity during a compliant contact: located as a "
           "root (or found over it where the push began), once a column and axis (docs/model.md 6b); "
           "sway_over_capacity: its sway alone was over it then (an elastic column is checked only while pushed)"},
          {"failures", failures}};
}

/// The storeys' and columns' peak member forces (solvers/member_forces.hpp), building by building
/// and storey by storey, each column's after its storey's.
json member_forces_json(const solvers::RunResult& result) {
  json buildings = json::array();
  for (const solvers::MemberForce& q : result.member_forces) {
    const std::size_t b = static_cast<std::size_t>(q.building);
    if (buildings.size() <= b) buildings.push_back({{"building", result.peaks.at(b).name}, {"storeys", json::array()}});
    json& storeys = buildings[b]["storeys"];
    if (storeys.empty() || storeys.back()["storey"] != q.storey) storeys.push_back({{"storey", q.storey}});
    json& storey = storeys.back();
    json& entry = q.column < 0 ? storey : storey["columns"];
    if (q.column >= 0) {
      if (entry.is_null()) entry = json::array();
      if (entry.empty() || entry.back()["column"] != q.column_key) entry.push_back({{"column", q.column_key}});
    }
    (q.column < 0 ? entry : entry.back())[solvers::member_force_name(q.kind)] = {{"value", q.peak.value},
                                                                                 {"t_s", q.peak.t_s}};
  }
  return {{"definition",
           "the columns' own forces (a yielding column's spring force; no damping, no P-Delta): a storey's shears "
           "Vx, Vy (kN) and torque T (kN m, about the CM), a column's shears and end moments M = V H / 2 (Mx: "
           "under its sway along x); signed as the drift that calls them up"},
          {"instants", "the largest |value| over every step end, event and history sample (not located between them)"},
          {"buildings", buildings}};
}

json statistics_json(const solvers::SolverStatistics& s, const std::vector<contact::Candidate>& candidates) {
  const bool overlapped = s.max_interpenetration_candidate >= 0;
  json statistics = {
      {"steps", s.steps},
      {"rhs_evaluations", s.rhs_evaluations},
      {"root_evaluations", s.root_evaluations},
      {"jacobian_evaluations", s.jacobian_evaluations},
      {"error_test_failures", s.error_test_failures},
      {"restarts", s.restarts},
      {"events", s.events},
      {"interpolant_events", s.interpolant_events},
      {"off_segment_crossings", s.off_segment_crossings},
      {"halvings", s.halvings},
      {"smallest_step_s", s.smallest_step_s},
      {"unresolved_contacts", s.unresolved_contacts},
      {"iterative_lcp_solves", s.iterative_lcp_solves},
      {"largest_lcp_residual", s.largest_lcp_residual},
      {"max_interpenetration_m", s.max_interpenetration_m},
      {"max_interpenetration_t_s", overlapped ? json(s.max_interpenetration_t_s) : json(nullptr)},
      {"max_interpenetration_pair",
       overlapped ? json(contact::describe(candidates[static_cast<std::size_t>(s.max_interpenetration_candidate)]))
                  : json(nullptr)},
      {"wall_time_s", s.wall_time_s}};
  if (s.corner_candidates > 0) {  // only scenes with corners that can meet (docs/model.md §5a)
    statistics.update({{"corner_candidates", s.corner_candidates},
                       {"corner_candidates_armed", s.corner_candidates_armed},
                       {"corner_handovers", s.corner_handovers}});
  }
  return statistics;
}

/// The contact law and the parameters it ran with (impulse: none).
json contact_law_json(const analysis::RunReport& report) {
  json law = {{"name", report.contact_law}};
  const analysis::ContactLawInfo& info = analysis::contact_law_info(report.contact_law);
  if (!info.stiffness_key.empty()) {
    law[std::string(info.stiffness_key)] = report.contact_stiffness;
    law[std::string(info.damping_key)] = report.contact_damping;
  }
  return law;
}

/// What the acceleration outputs hold, and where the peaks were found.
json accelerations_json(const analysis::RunReport& report) {
  const bool impulse = report.contact_law == "impulse";
  return {{"content", impulse ? "smooth part" : "complete"},
          {"note", impulse ? "the impulse law's impacts add Dirac parts to both slabs' accelerations, left out here; "
                             "their impulses are in impacts (impulse_kNs)"
                           : "the contact forces are part of the accelerations"},
          {"g_mps2", report.g_mps2},
          {"peaks_located",
           "on the dense output: turning points of the rate (exact in free motion, a central "
           "difference while contact forces act), and every step end, event and sample"},
          {"drift_peaks_located", "on the dense output: turning points, and every step end, event and sample"}};
}

json setting_json(const analysis::SettingValue& value) {
  return std::visit([](const auto& v) { return json(v); }, value);
}

/// What the user gave, what the run used (the registry's settings of its method, with the real
/// order, Newton solver and absolute tolerances per component) and what was given but not used.
json warnings_json(const std::vector<analysis::RunWarning>& warnings) {
  json list = json::array();
  for (const analysis::RunWarning& w : warnings) list.push_back({{"code", w.code}, {"message", w.message}});
  return list;
}

json settings_json(const analysis::RunReport& report) {
  json given = json::object(), used = json::object();
  for (const analysis::SettingEntry& e : analysis::given_entries(report.solver))
    given[std::string(e.key)] = setting_json(e.value);
  for (const analysis::SettingEntry& e : analysis::used_entries(report.used))
    used[std::string(e.key)] = setting_json(e.value);
  if (const auto& c = report.used.atol_components) {
    used["atol_per_component"] = {{"u_m", c->displacement_m},
                                  {"v_m", c->displacement_m},
                                  {"phi_rad", c->rotation_rad},
                                  {"rates_factor_per_s", c->rate_per_s}};
  }
  if (report.used.method->event_driven) used["hold_velocity_mps"] = report.hold_velocity_mps;
  return {{"given", given}, {"used", used}, {"not_used", report.solver.not_used}};
}

json run_json_elastic(const analysis::RunReport& report, const Provenance& provenance) {
  const solvers::RunResult& r = report.result;
  std::map<int, int> counts;
  for (const auto& i : r.impacts) ++counts[i.level];
  json by_level = json::object();
  for (const auto& [level, count] : counts) {
    if (level > 0) by_level[std::to_string(level)] = count;  // lowest level first; 0 is slab to column
  }
  const bool row = !report.pairs.empty();
  const ImpactFieldSet fields = impact_field_set(report.candidates);
  json touches = json::array(), sustained = json::array();
  for (const auto& t : r.touches) {
    touches.push_back(at_level(t,
                               who(t, fields, {{"t_s", t.t_s}},
                                   {{"point", point(t.point)}, {"gap_rate_mps", t.gap_rate_mps}, {"gap_m", t.gap_m}}),
                               row));
  }
  for (const auto& s : r.sustained_contacts) {
    sustained.push_back(at_level(s,
                                 who(s, fields, json::object(),
                                     {{"start_s", s.start_s},
                                      {"release_s", s.release_s},
                                      {"release_reason", s.release_reason},
                                      {"max_force_kN", s.max_force_kN},
                                      {"max_gap_drift_m", s.max_gap_drift_m},
                                      {"impulse_kNs", s.impulse_kNs}}),
                                 row));
  }
  json summary = {{"scene", report.scene},
                  {"method", r.method},
                  {"status", solvers::to_string(r.status)},
                  {"status_detail", r.status_detail},
                  {"warnings", warnings_json(report.warnings)},
                  {"settings", settings_json(report)},
                  {"gap_m", row ? json(nullptr) : json(report.gap_m)},
                  {"restitution", report.restitution},
                  {"contact_law", contact_law_json(report)},
                  {"start_s", r.start_s},
                  {"end_s", r.end_s},
                  {"levels", levels_json(report.levels, row)},
                  {"outputs", outputs_json(r.outputs)},
                  {"history_levels", r.history.levels},
                  {"candidates", candidates_json(report.candidates, row)},
                  {"impact_count", r.impacts.size()},
                  {"impacts_by_level", by_level}};
  if (row) {
    summary["pairs"] = pairs_json(report);
    json by_pair = json::object();
    for (const json& pair : summary["pairs"])
      by_pair[fmt::format("{}:{}", pair["names"][0].get<std::string>(), pair["names"][1].get<std::string>())] =
          pair["impacts"];
    summary["impacts_by_pair"] = by_pair;
  }
  if (fields.slab_to_column) summary["impacts_slab_to_column"] = counts.count(0) ? counts[0] : 0;
  summary.update(json{{"impacts", impacts_json(r.impacts, fields)},
                      {"touches", touches},
                      {"sustained_contacts", sustained},
                      {"accelerations", accelerations_json(report)},
                      {"peaks", peaks_json(r.peaks, r.outputs, report.g_mps2)},
                      {"energy", energy_json(r.energy, !report.springs.empty())},
                      {"statistics", statistics_json(r.statistics, report.candidates)},
                      {"provenance", provenance_json(provenance)}});
  return summary;
}

}  // namespace

json run_json(const analysis::RunReport& report, const Provenance& provenance) {
  json summary = run_json_elastic(report, provenance);
  if (report.spectral_scaling) {
    const analysis::SpectralScaling& sa = *report.spectral_scaling;
    json scaling = {{"asked", sa.asked}};
    if (sa.design) {
      scaling["target"] = {
          {"spectrum", "asce7"}, {"sds_g", sa.design->sds_g}, {"sd1_g", sa.design->sd1_g}, {"tl_s", sa.design->tl_s}};
      scaling["periods_s"] = {sa.from_s, sa.to_s};
      scaling["period_count"] = excitation::kSaRangePeriods;
      scaling["fit"] = "least squares of ln Sa (geometric mean of the ratios)";
    } else {
      scaling["target_g"] = sa.target_g;
      scaling["period_s"] = sa.period_s;
    }
    scaling["damping_ratio"] = sa.damping_ratio;
    scaling["measure"] = sa.rotd100 ? "rotd100" : "psa";
    scaling["record_factor"] = sa.record_factor;
    summary["spectral_scaling"] = scaling;
  }
  if (report.springs.empty() && !report.contact_free && report.limit_states.empty() && report.residual_drifts.empty() &&
      report.result.member_forces.empty() && !report.result.struck_columns_watched) {
    return summary;
  }
  // The yielding and pounding-demand sections go before the energy audit.
  json extended;
  for (auto& [key, value] : summary.items()) {
    if (key == "energy") {
      if (!report.result.member_forces.empty()) extended["member_forces"] = member_forces_json(report.result);
      if (report.result.struck_columns_watched)
        extended["struck_column_failures"] = struck_column_failures_json(report.result);
      if (!report.springs.empty()) extended["yielding"] = yielding_json(report);
      if (report.contact_free) extended["pounding_demand"] = pounding_demand_json(report);
      if (!report.limit_states.empty()) extended["limit_states"] = limit_states_json(report);
      if (!report.residual_drifts.empty()) extended["residual_drift"] = residual_drift_json(report);
    }
    extended[key] = std::move(value);
  }
  return extended;
}

void write_yielding_rows(const analysis::RunReport& report, std::ostream& out) {
  const std::vector<YieldingColumn> columns = yielding_columns(report.springs);
  write_csv_header(column_names(columns), out);
  std::vector<std::string> cells(columns.size());
  for (std::size_t j = 0; j < report.springs.size(); ++j) {
    for (std::size_t c = 0; c < columns.size(); ++c)
      cells[c] = columns[c].cell(report.springs[j], report.result.springs[j]);
    out << fmt::format("{}\n", fmt::join(cells, ","));
  }
}

void write_yielding_csv(const analysis::RunReport& report, const std::filesystem::path& folder) {
  if (report.springs.empty()) {
    std::filesystem::remove(folder / "yielding.csv");
    return;
  }
  write_atomically(folder / "yielding.csv", [&](std::ostream& out) { write_yielding_rows(report, out); });
}

void write_impacts_header(std::ostream& out, ImpactFieldSet fields) {
  write_csv_header(impact_csv_columns(fields), out);
}

void write_impact_row(const solvers::ImpactRecord& impact, std::ostream& out, ImpactFieldSet fields) {
  out << impact_csv_row(impact, fields) << '\n';
}

void write_csv_header(const std::vector<std::string>& columns, std::ostream& out) {
  for (std::size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << columns[c];
  out << '\n';
}

void write_history_row(double t_s, const Eigen::VectorXd& values, std::ostream& out) {
  // The shortest text that reads back to the same double ("{}"), the whole line formatted in one
  // buffer with the format compiled, and written at once: a run writes hundreds of values a row.
  fmt::memory_buffer line;
  fmt::format_to(std::back_inserter(line), FMT_COMPILE("{}"), t_s);
  for (double value : values) fmt::format_to(std::back_inserter(line), FMT_COMPILE(",{}"), value);
  line.push_back('\n');
  out.write(line.data(), static_cast<std::streamsize>(line.size()));
}

void write_contact_forces_header(std::ostream& out) { write_csv_header(column_names(contact_force_columns()), out); }

void write_contact_force_row(const solvers::ContactForceSample& f, std::ostream& out) {
  fmt::memory_buffer line;
  for (const ContactForceColumn& c : contact_force_columns()) {
    if (line.size() > 0) line.push_back(',');
    fmt::format_to(std::back_inserter(line), "{}", c.value(f));
  }
  line.push_back('\n');
  out.write(line.data(), static_cast<std::streamsize>(line.size()));
}

void remove_history_files(const std::filesystem::path& folder) {
  std::filesystem::remove(folder / "history.csv");
  std::filesystem::remove(folder / "contacts_history.csv");
}

void write_run(const analysis::RunReport& report, const Provenance& provenance, const std::filesystem::path& folder) {
  std::filesystem::create_directories(folder);
  // summary.json goes last and an earlier run's goes first: whatever happens in between, a
  // summary never stands beside files from another run.
  std::filesystem::remove(folder / "summary.json");
  const solvers::RunResult& r = report.result;
  if (r.outputs.history) {
    write_atomically(folder / "history.csv", [&](std::ostream& out) {
      write_csv_header(r.history.columns, out);
      for (std::size_t k = 0; k < r.history.time_s.size(); ++k)
        write_history_row(r.history.time_s[k], r.history.rows[k], out);
    });
    write_atomically(folder / "contacts_history.csv", [&](std::ostream& out) {
      write_contact_forces_header(out);
      for (const solvers::ContactForceSample& f : r.history.contact_forces) write_contact_force_row(f, out);
    });
  } else {
    remove_history_files(folder);
  }
  write_atomically(folder / "impacts.csv", [&](std::ostream& out) {
    const ImpactFieldSet fields = impact_field_set(report.candidates);
    write_impacts_header(out, fields);
    for (const solvers::ImpactRecord& impact : r.impacts) write_impact_row(impact, out, fields);
  });
  write_yielding_csv(report, folder);
  write_json(run_json(report, provenance), folder / "summary.json");
}

}  // namespace pounding::io
