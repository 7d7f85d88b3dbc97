#include "pounding/io/output_schema.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "pounding/analysis/scene.hpp"
#include "pounding/io/impact_schema.hpp"
#include "pounding/solvers/history_schema.hpp"

namespace pounding::io {
namespace {

using json = nlohmann::ordered_json;
using Group = PeakField::Group;
using solvers::FloorPeaks;
using solvers::Peak;

json peak(const Peak& p) { return {{"value", p.value}, {"t_s", p.t_s}}; }

/// An acceleration peak (m/s²) also in g.
json peak_in_g(const Peak& p, double g_mps2) {
  return {{"value", p.value}, {"value_g", p.value / g_mps2}, {"t_s", p.t_s}};
}

json peak_list(const std::vector<Peak>& peaks) {
  json list = json::array();
  for (const Peak& p : peaks) list.push_back(peak(p));
  return list;
}

json worst_corner_json(const FloorPeaks& f) {
  const solvers::WorstCornerDrift w = solvers::worst_corner_drift(f);
  return {{"corner", w.corner}, {"axis", std::string(1, w.axis)}, {"value", w.peak.value}, {"t_s", w.peak.t_s}};
}

}  // namespace

const std::vector<PeakField>& peak_fields() {
  static const std::vector<PeakField> fields = {
      {Group::displacements, "u_m", "m", "x-displacement of the centre of mass, relative to the ground",
       [](const FloorPeaks& f, double) { return peak(f.u_m); }},
      {Group::displacements, "v_m", "m", "y-displacement of the centre of mass",
       [](const FloorPeaks& f, double) { return peak(f.v_m); }},
      {Group::displacements, "phi_rad", "rad", "rotation of the slab",
       [](const FloorPeaks& f, double) { return peak(f.phi_rad); }},
      {Group::displacements, "vertex_dx_m", "m",
       "x-displacement of each contact vertex (a list, in the order of the building's contact_vertices)",
       [](const FloorPeaks& f, double) { return peak_list(f.vertex_dx_m); }},
      {Group::accelerations, "ax_abs_mps2", "mps2",
       "absolute x-acceleration of the centre of mass (also as value_g); impulse law: its smooth part",
       [](const FloorPeaks& f, double g) { return peak_in_g(f.ax_abs_mps2, g); }},
      {Group::accelerations, "ay_abs_mps2", "mps2", "absolute y-acceleration of the centre of mass (also as value_g)",
       [](const FloorPeaks& f, double g) { return peak_in_g(f.ay_abs_mps2, g); }},
      {Group::accelerations, "phi_ddot_radps2", "radps2", "angular acceleration of the slab",
       [](const FloorPeaks& f, double) { return peak(f.phi_ddot_radps2); }},
      {Group::drifts, "drift_x", "", "x-drift ratio of the storey below the floor, at the centre of mass",
       [](const FloorPeaks& f, double) { return peak(f.drift_x); }},
      {Group::drifts, "drift_y", "", "y-drift ratio of the storey below, at the centre of mass",
       [](const FloorPeaks& f, double) { return peak(f.drift_y); }},
      {Group::drifts, "corner_drift_x", "", "x-drift ratio at each slab corner (a list, in outline order)",
       [](const FloorPeaks& f, double) { return peak_list(f.corner_drift_x); }},
      {Group::drifts, "corner_drift_y", "", "y-drift ratio at each slab corner (a list, in outline order)",
       [](const FloorPeaks& f, double) { return peak_list(f.corner_drift_y); }},
      {Group::drifts, "worst_corner_drift", "",
       "the largest corner drift over corners and axes: corner (1-based), axis (x or y), value, t_s",
       [](const FloorPeaks& f, double) { return worst_corner_json(f); }},
  };
  return fields;
}

bool asked(const solvers::OutputSelection& outputs, Group group) {
  switch (group) {
    case Group::displacements: return outputs.displacement_peaks;
    case Group::accelerations: return outputs.acceleration_peaks;
    case Group::drifts: return outputs.drift_peaks;
  }
  return false;
}

const std::vector<EnergyField>& energy_fields() {
  using solvers::EnergyAudit;
  static const std::vector<EnergyField> fields = {
      {"input_kJ", "kJ", "work of the ground motion on the relative motion",
       [](const EnergyAudit& e) { return e.input_kJ; }},
      {"kinetic_final_kJ", "kJ", "kinetic energy of the relative motion at the end",
       [](const EnergyAudit& e) { return e.kinetic_kJ; }},
      {"strain_final_kJ", "kJ", "strain energy at the end", [](const EnergyAudit& e) { return e.strain_kJ; }},
      {"damping_kJ", "kJ", "energy the structural damping dissipated",
       [](const EnergyAudit& e) { return e.damping_kJ; }},
      {"impact_loss_kJ", "kJ",
       "energy the impacts took from the slabs (compliant laws: the contact force's work, dissipated or still in the "
       "spring at the end)",
       [](const EnergyAudit& e) { return e.impact_loss_kJ; }},
      {"constraint_work_kJ", "kJ", "work of the forces holding sustained contacts (ideally 0)",
       [](const EnergyAudit& e) { return e.constraint_work_kJ; }},
      {"algorithmic_dissipation_kJ", "kJ", "hht: energy its update removes (0 for alpha = 0 and every other path)",
       [](const EnergyAudit& e) { return e.algorithmic_dissipation_kJ; }},
      {"hysteretic_kJ", "kJ", "energy the yielding columns dissipated (only in runs whose columns yield)",
       [](const EnergyAudit& e) { return e.hysteretic_kJ; }, true},
      {"residual_kJ", "kJ", "input + constraint work - everything above: the balance's error",
       [](const EnergyAudit& e) { return e.residual_kJ(); }},
      {"relative_residual", "", "residual over input (0 when the input is 0)",
       [](const EnergyAudit& e) { return e.input_kJ != 0.0 ? e.residual_kJ() / e.input_kJ : 0.0; }},
  };
  return fields;
}

const std::vector<ContactForceColumn>& contact_force_columns() {
  using solvers::ContactForceSample;
  static const std::vector<ContactForceColumn> columns = {
      {"t_s", "s", "time (an instant of history.csv)", [](const ContactForceSample& f) { return f.t_s; }},
      {"candidate", "", "0-based index into summary.json's candidates",
       [](const ContactForceSample& f) { return double(f.candidate); }},
      {"level", "", "1-based level (floors at a common elevation); 0 slab to column",
       [](const ContactForceSample& f) { return double(f.level); }},
      {"striking_building", "", "the building whose slab strikes (1-based)",
       [](const ContactForceSample& f) { return double(f.striking_building); }},
      {"vertex", "", "the striking vertex's 1-based number in its slab outline; 0 slab to column",
       [](const ContactForceSample& f) { return double(f.vertex); }},
      {"struck_edge", "",
       "the struck edge's 1-based number in the struck slab's outline (slab to column: the slab's edge)",
       [](const ContactForceSample& f) { return double(f.edge); }},
      {"gap_m", "m", "signed gap (< 0: overlap)", [](const ContactForceSample& f) { return f.gap_m; }},
      {"gap_rate_mps", "mps", "rate of the gap", [](const ContactForceSample& f) { return f.gap_rate_mps; }},
      {"force_kN", "kN",
       "normal contact force, > 0 pushing the slabs apart (compliant laws: the law's; impulse law: the force holding a "
       "sustained contact)",
       [](const ContactForceSample& f) { return f.force_kN; }},
  };
  return columns;
}

const std::vector<YieldingColumn>& yielding_columns() {
  using dynamics::YieldingSpring;
  using solvers::SpringResult;
  using Kind = YieldingColumn::Kind;
  static const std::vector<YieldingColumn> columns = {
      {"building", "", Kind::integer, "1-based building",
       [](const YieldingSpring& s, const SpringResult&) { return fmt::format("{}", s.building + 1); }},
      {"storey", "", Kind::integer,
       "1-based storey: the columns between floor storey - 1 (floor 0: the ground) and floor storey",
       [](const YieldingSpring& s, const SpringResult&) { return fmt::format("{}", s.storey); }},
      {"column", "", Kind::text, "the column's scene key, quoted (\"columns[3]\", \"column_grid[1] x[2] y[1]\")",
       [](const YieldingSpring& s, const SpringResult&) { return fmt::format("\"{}\"", s.column); }},
      {"direction", "", Kind::text, "x or y: the spring's direction of sway",
       [](const YieldingSpring& s, const SpringResult&) { return std::string(s.direction == 0 ? "x" : "y"); }},
      {"stiffness_kN_per_m", "kN/m", Kind::real, "initial stiffness k",
       [](const YieldingSpring& s, const SpringResult&) { return fmt::format("{}", s.stiffness_kN_per_m); }},
      {"hardening_ratio", "", Kind::real, "post-yield over initial stiffness",
       [](const YieldingSpring& s, const SpringResult&) { return fmt::format("{}", s.hardening_ratio); }},
      {"yield_drift_m", "m", Kind::real, "yield drift d_y",
       [](const YieldingSpring& s, const SpringResult&) { return fmt::format("{}", s.yield_drift_m); }},
      {"yield_force_kN", "kN", Kind::real, "force at the yield drift, k d_y (Bouc-Wen tends to it as n grows)",
       [](const YieldingSpring& s, const SpringResult&) {
         return fmt::format("{}", s.stiffness_kN_per_m * s.yield_drift_m);
       }},
      {"peak_drift_m", "m", Kind::real, "largest absolute drift over the run",
       [](const YieldingSpring&, const SpringResult& r) { return fmt::format("{}", r.peak_drift_m); }},
      {"peak_ductility", "", Kind::real, "peak drift over yield drift",
       [](const YieldingSpring& s, const SpringResult& r) {
         return fmt::format("{}", r.peak_drift_m / s.yield_drift_m);
       }},
      {"first_yield_t_s", "s", Kind::real, "when it first yielded; empty if it never did",
       [](const YieldingSpring&, const SpringResult& r) {
         return std::isfinite(r.first_yield_t_s) ? fmt::format("{}", r.first_yield_t_s) : std::string();
       }},
      {"yield_count", "", Kind::integer, "yielding phases",
       [](const YieldingSpring&, const SpringResult& r) { return fmt::format("{}", r.yield_count); }},
      {"hysteretic_kJ", "kJ", Kind::real, "energy it dissipated",
       [](const YieldingSpring&, const SpringResult& r) { return fmt::format("{}", r.hysteretic_kJ); }},
      {"final_drift_m", "m", Kind::real, "drift at the end of the run",
       [](const YieldingSpring&, const SpringResult& r) { return fmt::format("{}", r.final_drift_m); }},
      {"final_slip_m", "m", Kind::real, "slip of its plastic part at the end (the drift at zero force for alpha = 0)",
       [](const YieldingSpring&, const SpringResult& r) { return fmt::format("{}", r.final_slip_m); }},
      {"shear_capacity_kN", "kN", Kind::real,
       "its column's shear capacity V_c along its direction (this and the next three columns are written when some "
       "column has one); empty: none given",
       [](const YieldingSpring& s, const SpringResult&) {
         return s.shear_capacity_kN > 0.0 ? fmt::format("{}", s.shear_capacity_kN) : std::string();
       },
       true},
      {"peak_force_kN", "kN", Kind::real,
       "largest absolute force at the step ends and events (exact at a yielding phase's end)",
       [](const YieldingSpring&, const SpringResult& r) { return fmt::format("{}", r.peak_force_kN); }, true},
      {"demand_capacity_ratio", "", Kind::real, "peak force over shear capacity; empty: no capacity",
       [](const YieldingSpring& s, const SpringResult& r) {
         return s.shear_capacity_kN > 0.0 ? fmt::format("{}", r.peak_force_kN / s.shear_capacity_kN) : std::string();
       },
       true},
      {"shear_failure_t_s", "s", Kind::real,
       "when the absolute force first reached the shear capacity (located: the column's shear failure); empty if it "
       "never did",
       [](const YieldingSpring&, const SpringResult& r) {
         return std::isfinite(r.shear_failure_t_s) ? fmt::format("{}", r.shear_failure_t_s) : std::string();
       },
       true},
      {"degrading_failure_t_s", "s", Kind::real,
       "when its degrading (IMK) law failed and the column lost its force (a deterioration parameter past 1, its "
       "energy spent, the ultimate drift, or no residual strength); empty if it never did",
       [](const YieldingSpring&, const SpringResult& r) {
         return std::isfinite(r.degrading_failure_t_s) ? fmt::format("{}", r.degrading_failure_t_s) : std::string();
       },
       false, true},
  };
  return columns;
}

std::vector<YieldingColumn> yielding_columns(const std::vector<dynamics::YieldingSpring>& springs) {
  const bool capacities = std::any_of(springs.begin(), springs.end(),
                                      [](const dynamics::YieldingSpring& s) { return s.shear_capacity_kN > 0.0; });
  const bool degrading =
      std::any_of(springs.begin(), springs.end(), [](const dynamics::YieldingSpring& s) { return s.imk.has_value(); });
  std::vector<YieldingColumn> written;
  for (const YieldingColumn& c : yielding_columns()) {
    if ((capacities || !c.shear_capacity_only) && (degrading || !c.degrading_only)) written.push_back(c);
  }
  return written;
}

json output_schema_json() {
  using solvers::HistoryQuantity;
  static constexpr std::string_view kPer[] = {"slab", "contact_vertex", "corner"};
  json history = json::array({{{"column", "t_s"}, {"unit", "s"}, {"per", "row"}, {"description", "time"}}});
  for (const HistoryQuantity& q : solvers::history_quantities()) {
    history.push_back({{"column", "B{b}_f{f}_" + q.column()},  // {n} stays a placeholder
                       {"unit", q.unit},
                       {"per", kPer[static_cast<int>(q.per)]},
                       {"description", q.description}});
  }
  // With output.member_forces, after the slabs: solvers/member_forces.hpp.
  static constexpr std::array<std::array<std::string_view, 4>, 7> kMemberForces{{
      {"B{b}_s{j}_Vx_kN", "kN", "storey", "storey j's shear along x: the sum of its columns' forces (model.md §2c)"},
      {"B{b}_s{j}_Vy_kN", "kN", "storey", "storey j's shear along y"},
      {"B{b}_s{j}_T_kNm", "kNm", "storey", "storey j's torque about the CM"},
      {"B{b}_s{j}_col{n}_Vx_kN", "kN", "column", "column n's shear along x (a yielding column's spring force)"},
      {"B{b}_s{j}_col{n}_Vy_kN", "kN", "column", "column n's shear along y"},
      {"B{b}_s{j}_col{n}_Mx_kNm", "kNm", "column", "column n's end moment under its sway along x, Vx H / 2"},
      {"B{b}_s{j}_col{n}_My_kNm", "kNm", "column", "column n's end moment under its sway along y, Vy H / 2"},
  }};
  for (const auto& [column, unit, per, description] : kMemberForces) {
    history.push_back({{"column", column},
                       {"unit", unit},
                       {"per", per},
                       {"description", description},
                       {"only_when", "output.member_forces"}});
  }
  json impacts = json::array();
  for (const ImpactField& f : impact_fields()) {
    impacts.push_back(
        {{"key", f.json_key()}, {"csv_columns", f.csv_columns()}, {"unit", f.unit}, {"description", f.description}});
    if (f.scenes == (ImpactField::kSlabToColumn | ImpactField::kRow)) {
      impacts.back()["only_when"] = "slabs can strike columns, or a row: a contact pair other than buildings 1 and 2";
    } else if (f.scenes == ImpactField::kSlabToColumn) {
      impacts.back()["only_when"] = "slabs can strike columns";
    } else if (f.scenes == ImpactField::kRow) {
      impacts.back()["only_when"] = "a row: a contact pair other than buildings 1 and 2";
    }
  }
  json peaks = json::array();
  for (const PeakField& f : peak_fields()) {
    peaks.push_back({{"key", f.key},
                     {"unit", f.unit},
                     {"group", analysis::kPeakGroups[static_cast<std::size_t>(f.group)]},
                     {"description", f.description}});
  }
  json energy = json::array();
  for (const EnergyField& f : energy_fields()) {
    energy.push_back({{"key", f.key}, {"unit", f.unit}, {"description", f.description}});
    if (f.yielding_only) energy.back()["only_when"] = "columns yield";
  }
  json contact_forces = json::array();
  for (const ContactForceColumn& c : contact_force_columns()) {
    contact_forces.push_back({{"column", c.name}, {"unit", c.unit}, {"description", c.description}});
  }
  static constexpr std::string_view kKind[] = {"integer", "real", "text"};
  json yielding = json::array();
  for (const YieldingColumn& c : yielding_columns()) {
    yielding.push_back({{"column", c.name},
                        {"unit", c.unit},
                        {"kind", kKind[static_cast<int>(c.kind)]},
                        {"description", c.description}});
    if (c.shear_capacity_only)
      yielding.back()["only_when"] =
          "some yielding column has a shear capacity (column_shear_capacity_kN, [building.shear_capacity] or its own "
          "shear_capacity_kN)";
    if (c.degrading_only) yielding.back()["only_when"] = "some column's law is imk-peak-oriented or imk-pinching";
  }
  return {{"history", history},
          {"impacts", impacts},
          {"peaks", peaks},
          {"energy", energy},
          {"contact_forces", contact_forces},
          {"yielding", yielding}};
}

}  // namespace pounding::io
