#include "pounding/io/study_writer.hpp"

#include <fmt/format.h>
#include <ostream>
#include <string>

#include "pounding/analysis/methods.hpp"
#include "pounding/io/json_report.hpp"
#include "pounding/io/output_files.hpp"

namespace pounding::io {
namespace {

const char* kCsvHeader =
    "method,setting,value,status,run_time_s,steps,rhs_evaluations,restarts,impacts,matched,missing,extra,"
    "impact_time_error_s,impact_time_error_all_s,impact_time_error_before_hold_s,impulse_relative_error,history_u_"
    "error_m,history_v_error_m,history_phi_error_rad,"
    "peak_u_error_m,peak_v_error_m,peak_phi_error_rad,impact_time_at_reference,history_u_at_reference\n";

/// The error columns a study row and a truncation row share, in their CSV order.
nlohmann::json errors_json(const analysis::RunErrors& e) {
  return {{"matched", e.matched},
          {"missing", e.missing},
          {"extra", e.extra},
          {"impact_time_error_s", e.impact_time_s},
          {"impact_time_error_all_s", e.impact_time_all_s},
          {"impact_time_error_before_hold_s", e.impact_time_before_hold_s},
          {"impulse_relative_error", e.impulse_relative},
          {"history_u_error_m", e.history_u_m},
          {"history_v_error_m", e.history_v_m},
          {"history_phi_error_rad", e.history_phi_rad},
          {"peak_u_error_m", e.peak_u_m},
          {"peak_v_error_m", e.peak_v_m},
          {"peak_phi_error_rad", e.peak_phi_rad}};
}

std::string errors_csv(const analysis::RunErrors& e) {
  return fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{}", e.matched, e.missing, e.extra, e.impact_time_s,
                     e.impact_time_all_s, e.impact_time_before_hold_s, e.impulse_relative, e.history_u_m, e.history_v_m,
                     e.history_phi_rad, e.peak_u_m, e.peak_v_m, e.peak_phi_rad);
}

nlohmann::json row_json(const analysis::StudyRow& row) {
  nlohmann::json json = {{"method", row.method},
                         {"setting", row.setting},
                         {"value", row.value},
                         {"status", row.status},
                         {"run_time_s", row.run_time_s},
                         {"steps", row.steps},
                         {"rhs_evaluations", row.rhs_evaluations},
                         {"restarts", row.restarts},
                         {"impacts", row.impacts},
                         {"impact_time_at_reference", row.impact_time_at_reference},
                         {"history_u_at_reference", row.history_u_at_reference}};
  json.update(errors_json(row.errors));
  return json;
}

void write_study_csv(const analysis::StudyResult& study, std::ostream& out) {
  out << kCsvHeader;
  for (const auto& row : study.rows) {
    out << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{}\n", row.method, row.setting, row.value, row.status,
                       row.run_time_s, row.steps, row.rhs_evaluations, row.restarts, row.impacts,
                       errors_csv(row.errors), row.impact_time_at_reference, row.history_u_at_reference);
  }
}

const char* kStiffnessCsvHeader =
    "law,method,stiffness,stiffness_unit,status,run_time_s,steps,rhs_evaluations,jacobian_evaluations,impacts,"
    "peak_force_kN\n";

nlohmann::json stiffness_row_json(const analysis::StiffnessRow& row) {
  return {{"law", row.law},
          {"method", row.method},
          {"stiffness", row.stiffness},
          {"stiffness_unit", row.stiffness_unit},
          {"status", row.status},
          {"run_time_s", row.run_time_s},
          {"steps", row.steps},
          {"rhs_evaluations", row.rhs_evaluations},
          {"jacobian_evaluations", row.jacobian_evaluations},
          {"impacts", row.impacts},
          {"peak_force_kN", row.peak_force_kN}};
}

void write_stiffness_csv(const analysis::StudyResult& study, std::ostream& out) {
  out << kStiffnessCsvHeader;
  for (const auto& r : study.stiffness_rows) {
    out << fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", r.law, r.method, r.stiffness, r.stiffness_unit, r.status,
                       r.run_time_s, r.steps, r.rhs_evaluations, r.jacobian_evaluations, r.impacts, r.peak_force_kN);
  }
}

const char* kTruncationCsvHeader =
    "modes_cutoff_hz,modes_kept,modes_total,status,run_time_s,steps,impacts,matched,missing,extra,"
    "impact_time_error_s,impact_time_error_all_s,impact_time_error_before_hold_s,impulse_relative_error,"
    "history_u_error_m,history_v_error_m,history_phi_error_rad,peak_u_error_m,peak_v_error_m,peak_phi_error_rad\n";

nlohmann::json truncation_row_json(const analysis::TruncationRow& row) {
  nlohmann::json json = {{"modes_cutoff_hz", row.cutoff_hz},
                         {"modes_kept", row.modes_kept},
                         {"modes_total", row.modes_total},
                         {"status", row.status},
                         {"run_time_s", row.run_time_s},
                         {"steps", row.steps},
                         {"impacts", row.impacts}};
  json.update(errors_json(row.errors));
  return json;
}

void write_truncation_csv(const analysis::StudyResult& study, std::ostream& out) {
  out << kTruncationCsvHeader;
  for (const auto& r : study.truncation_rows) {
    out << fmt::format("{},{},{},{},{},{},{},{}\n", r.cutoff_hz, r.modes_kept, r.modes_total, r.status, r.run_time_s,
                       r.steps, r.impacts, errors_csv(r.errors));
  }
}

}  // namespace

namespace {

/// The plot style of every study series (the registry's), so plots need no table of their own.
nlohmann::json styles_json() {
  nlohmann::json styles = nlohmann::json::object();
  for (const analysis::MethodInfo& method : analysis::methods()) {
    for (const analysis::StudySeries& series : method.series) {
      styles[std::string(series.label)] = {{"colour", series.style.colour}, {"marker", series.style.marker}};
    }
  }
  return styles;
}

}  // namespace

nlohmann::json study_json(const analysis::StudyResult& study) {
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& row : study.rows) rows.push_back(row_json(row));
  nlohmann::json stiffness_rows = nlohmann::json::array();
  for (const auto& row : study.stiffness_rows) stiffness_rows.push_back(stiffness_row_json(row));
  nlohmann::json truncation_rows = nlohmann::json::array();
  for (const auto& row : study.truncation_rows) truncation_rows.push_back(truncation_row_json(row));
  return {{"scene", study.scene},
          {"gap_m", study.gap_m},
          {"interrupted", study.interrupted},
          {"reference",
           {{"method", study.reference_method},
            {"impacts", study.reference.impacts.size()},
            {"run_time_s", study.reference_run_time_s},
            {"error_estimate",
             {{"impact_time_s", study.reference_error.impact_time_all_s},
              {"impact_time_fast_s", study.reference_error.impact_time_s},
              {"history_u_m", study.reference_error.history_u_m},
              {"history_v_m", study.reference_error.history_v_m},
              {"history_phi_rad", study.reference_error.history_phi_rad},
              {"missing", study.reference_error.missing},
              {"extra", study.reference_error.extra}}}}},
          {"rows", rows},
          {"stiffness_ladder", stiffness_rows},
          {"truncation_ladder", truncation_rows},
          {"styles", styles_json()}};
}

void write_study(const analysis::StudyResult& study, const Provenance& provenance,
                 const std::filesystem::path& folder) {
  std::filesystem::create_directories(folder);
  nlohmann::json document = study_json(study);
  document["provenance"] = provenance_json(provenance);
  write_json(document, folder / "study.json");
  write_atomically(folder / "study.csv", [&](std::ostream& out) { write_study_csv(study, out); });
  write_atomically(folder / "stiffness.csv", [&](std::ostream& out) { write_stiffness_csv(study, out); });
  write_atomically(folder / "truncation.csv", [&](std::ostream& out) { write_truncation_csv(study, out); });
}

}  // namespace pounding::io
