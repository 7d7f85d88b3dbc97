#include "pounding/io/output_schema.hpp"

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
  return {{"history", history}, {"impacts", impacts}, {"peaks", peaks}, {"energy", energy}};
}

}  // namespace pounding::io
