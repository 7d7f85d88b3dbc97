#include "pounding/io/spectrum_writer.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <ostream>

#include "pounding/io/output_files.hpp"
#include "pounding/io/provenance.hpp"
#include "pounding/version.hpp"

namespace pounding::io {
namespace {

using nlohmann::ordered_json;

void write_spectrum_csv(std::ostream& out, const SpectrumReport& report) {
  out << "record,period_s,sd_m,psv_mps,psa_mps2,psa_g,peak_time_s\n";
  for (std::size_t r = 0; r < report.records.size(); ++r) {
    for (const excitation::SpectrumOrdinate& o : report.records[r].ordinates) {
      out << fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", r + 1, o.period_s, o.sd_m, o.psv_mps,
                         o.psa_mps2, o.psa_mps2 / report.g_mps2, o.peak_time_s);
    }
  }
}

void write_rotd_csv(std::ostream& out, const SpectrumReport& report) {
  out << "period_s,rotd50_sd_m,rotd100_sd_m,rotd50_psa_g,rotd100_psa_g,rotd100_angle_deg\n";
  for (const excitation::RotDOrdinate& o : report.rotd) {
    out << fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", o.period_s, o.rotd50_sd_m, o.rotd100_sd_m,
                       o.rotd50_psa_mps2 / report.g_mps2, o.rotd100_psa_mps2 / report.g_mps2, o.rotd100_angle_deg);
  }
}

ordered_json record_json(const RecordSpectrum& record, double g_mps2) {
  ordered_json ordinates = ordered_json::array();
  for (const excitation::SpectrumOrdinate& o : record.ordinates) {
    ordinates.push_back({{"period_s", o.period_s},
                         {"sd_m", o.sd_m},
                         {"psv_mps", o.psv_mps},
                         {"psa_mps2", o.psa_mps2},
                         {"psa_g", o.psa_mps2 / g_mps2},
                         {"peak_time_s", o.peak_time_s}});
  }
  return {{"file", std::filesystem::absolute(record.file).lexically_normal().string()},
          {"sha256", record.sha256},
          {"accel_column", record.accel_column > 0 ? ordered_json(record.accel_column) : ordered_json(nullptr)},
          {"peak_accel_mps2", record.peak_accel_mps2},
          {"peak_accel_g", record.peak_accel_mps2 / g_mps2},
          {"dt_s", record.dt_s},
          {"ordinates", ordinates}};
}

ordered_json report_json(const SpectrumReport& report) {
  ordered_json document;
  document["damping_ratio"] = report.damping_ratio;
  document["g_mps2"] = report.g_mps2;
  document["method"] = "closed-form SDOF response to the piecewise-linear record, peaks located between samples";
  document["records"] = ordered_json::array();
  for (const RecordSpectrum& record : report.records) document["records"].push_back(record_json(record, report.g_mps2));
  if (!report.rotd.empty()) {
    ordered_json rotd = ordered_json::array();
    for (const excitation::RotDOrdinate& o : report.rotd) {
      rotd.push_back({{"period_s", o.period_s},
                      {"rotd50_sd_m", o.rotd50_sd_m},
                      {"rotd100_sd_m", o.rotd100_sd_m},
                      {"rotd50_psa_g", o.rotd50_psa_mps2 / report.g_mps2},
                      {"rotd100_psa_g", o.rotd100_psa_mps2 / report.g_mps2},
                      {"rotd100_angle_deg", o.rotd100_angle_deg}});
    }
    document["rotd"] = rotd;
  }
  document["marked_periods"] = ordered_json::array();
  for (const MarkedPeriod& m : report.marked) {
    ordered_json psa_g = ordered_json::array();
    for (double psa : m.psa_mps2) psa_g.push_back(psa / report.g_mps2);
    document["marked_periods"].push_back({{"label", m.label}, {"period_s", m.period_s}, {"psa_g", psa_g}});
  }
  Provenance provenance;
  provenance.program_version = std::string(program_version());
  provenance.git_commit = std::string(git_commit());
  provenance.command_line = report.command_line;
  provenance.date_utc = utc_now_iso8601();
  document["provenance"] = provenance_json(provenance);
  return document;
}

}  // namespace

void write_spectrum(const std::filesystem::path& folder, const SpectrumReport& report) {
  write_atomically(folder / "spectrum.csv", [&](std::ostream& out) { write_spectrum_csv(out, report); });
  if (!report.rotd.empty()) {
    write_atomically(folder / "rotd.csv", [&](std::ostream& out) { write_rotd_csv(out, report); });
  }
  write_atomically(folder / "spectrum.json", [&](std::ostream& out) { out << report_json(report).dump(2) << '\n'; });
}

}  // namespace pounding::io
