#include "pounding/io/gap_writer.hpp"

#include <cmath>
#include <fmt/format.h>
#include <ostream>

#include "pounding/io/json_report.hpp"
#include "pounding/io/output_files.hpp"

namespace pounding::io {
namespace {

using nlohmann::json;

json pair_json(const analysis::NeededGap& gap, long candidate) {
  return candidate < 0 ? json(nullptr) : json(contact::describe(gap.candidates[static_cast<std::size_t>(candidate)]));
}

/// A level whose pairs never close has no finite needed gap: null, not −inf.
json finite_or_null(double value) { return std::isfinite(value) ? json(value) : json(nullptr); }

json level_json(const analysis::NeededGap& gap, const analysis::LevelGap& l) {
  json located = {{"level", l.level.index}, {"floors", {l.level.floors[0], l.level.floors[1]}}};
  if (l.column) {  // a slab facing columns: which slab, and where up the struck storey
    located.update(
        {{"slab_to_column",
          {{"slab_building", l.slab_building + 1}, {"storey", l.storey}, {"height_ratio", l.height_ratio}}}});
  }
  located.update(json{{"elevation_m", l.level.elevation_m},
                      {"needed_gap_m", finite_or_null(l.needed_gap_m)},
                      {"t_s", l.candidate >= 0 ? json(l.t_s) : json(nullptr)},
                      {"pair", pair_json(gap, l.candidate)},
                      {"peak_towards_m", {l.peak_towards_m[0], l.peak_towards_m[1]}},
                      {"peak_towards_t_s", {l.peak_t_s[0], l.peak_t_s[1]}},
                      {"rules", {{"abs_m", l.rules.abs_m}, {"srss_m", l.rules.srss_m}, {"ddc_m", l.rules.ddc_m}}}});
  return located;
}

void write_levels_csv(const analysis::NeededGap& gap, std::ostream& out) {
  out << "level,floor_b1,floor_b2,elevation_m,needed_gap_m,t_s,delta_b1_m,delta_b2_m,abs_m,srss_m,ddc_m,pair\n";
  for (const analysis::LevelGap& l : gap.levels) {
    out << fmt::format(
        "{},{},{},{},{},{},{},{},{},{},{},\"{}\"\n", l.level.index, l.level.floors[0], l.level.floors[1],
        l.level.elevation_m, l.needed_gap_m, l.t_s, l.peak_towards_m[0], l.peak_towards_m[1], l.rules.abs_m,
        l.rules.srss_m, l.rules.ddc_m,
        l.candidate >= 0 ? contact::describe(gap.candidates[static_cast<std::size_t>(l.candidate)]) : "");
  }
}

void write_history_csv(const analysis::NeededGap& gap, std::ostream& out) {
  out << "t_s";
  for (const analysis::LevelGap& l : gap.levels) {
    if (l.column) {
      out << fmt::format(",touch_gap_B{}_f{}_columns_m", l.slab_building + 1, l.level.floors[l.slab_building]);
    } else {
      out << fmt::format(",touch_gap_level_{}_m", l.level.index);
    }
  }
  out << '\n';
  for (std::size_t k = 0; k < gap.history_t_s.size(); ++k) {
    out << fmt::format("{}", gap.history_t_s[k]);
    for (const auto& column : gap.history_touch_gap_m) out << fmt::format(",{}", column[k]);
    out << '\n';
  }
}

void write_curve_csv(const std::vector<analysis::SeverityPoint>& curve, std::ostream& out) {
  out << "gap_m,status,impacts,max_impulse_kNs,max_approach_mps,energy_lost_kJ,wall_time_s\n";
  for (const analysis::SeverityPoint& p : curve) {
    out << fmt::format("{},{},{},{},{},{},{}\n", p.gap_m, p.status, p.impacts, p.max_impulse_kNs, p.max_approach_mps,
                       p.energy_lost_kJ, p.wall_time_s);
  }
}

/// A text field of a CSV row: quoted, with inner quotes doubled (messages hold commas and quotes).
std::string csv_text(const std::string& text) {
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
  return quoted + "\"";
}

/// A level or floor of a CSV row; empty for 0 (none: the record's run never started or failed).
std::string csv_level(int level) { return level > 0 ? std::to_string(level) : ""; }

/// A number of a CSV row; empty where it does not exist.
std::string csv_number(double value) { return std::isfinite(value) ? fmt::format("{}", value) : ""; }

void write_records_csv(const analysis::RecordSetResult& set, std::ostream& out) {
  out << "record,source,status,message,pga_g,duration_s,needed_gap_m,level,floor_b1,floor_b2,t_s,abs_m,srss_m,ddc_m,"
         "steps,wall_time_s\n";
  for (const analysis::RecordGap& r : set.records) {
    out << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", csv_text(r.record), csv_text(r.source),
                       r.status, csv_text(r.message), csv_number(r.pga_g), csv_number(r.duration_s),
                       csv_number(r.needed_gap_m), csv_level(r.level), csv_level(r.floors[0]), csv_level(r.floors[1]),
                       csv_number(r.t_s), csv_number(r.rules.abs_m), csv_number(r.rules.srss_m),
                       csv_number(r.rules.ddc_m), r.steps, r.wall_time_s);
  }
}

json statistic_json(const analysis::SetStatistic& s) {
  return {{"count", s.count},
          {"mean", finite_or_null(s.mean)},
          {"median", finite_or_null(s.median)},
          {"log_mean", finite_or_null(s.log_mean)},
          {"log_std", finite_or_null(s.log_std)},
          {"p84_lognormal", finite_or_null(s.p84_lognormal)}};
}

json record_json(const analysis::RecordGap& r) {
  const bool governed = r.completed() && r.closes;
  return {{"record", r.record},
          {"source", r.source},
          {"status", r.status},
          {"message", r.message},
          {"pga_g", finite_or_null(r.pga_g)},
          {"duration_s", finite_or_null(r.duration_s)},
          {"needed_gap_m", finite_or_null(r.needed_gap_m)},
          {"level", r.level > 0 ? json(r.level) : json(nullptr)},
          {"floor", governed ? json({r.floors[0], r.floors[1]}) : json(nullptr)},
          {"t_s", governed ? finite_or_null(r.t_s) : json(nullptr)},
          {"rules",
           {{"abs_m", finite_or_null(r.rules.abs_m)},
            {"srss_m", finite_or_null(r.rules.srss_m)},
            {"ddc_m", finite_or_null(r.rules.ddc_m)}}},
          {"steps", r.steps},
          {"wall_time_s", r.wall_time_s}};
}

}  // namespace

json record_set_json(const std::string& scene, const analysis::RecordSetResult& set) {
  json records = json::array();
  for (const analysis::RecordGap& r : set.records) records.push_back(record_json(r));
  return {{"scene", scene},
          {"records", records},
          {"statistics",
           {{"needed_gap_m", statistic_json(set.needed_gap_m)},
            {"abs_m", statistic_json(set.abs_m)},
            {"srss_m", statistic_json(set.srss_m)},
            {"ddc_m", statistic_json(set.ddc_m)},
            {"lognormal_std", "sample standard deviation of ln x (divisor n - 1); p84 = exp(log_mean + log_std)"}}},
          {"worst", set.worst >= 0 ? json(set.records[static_cast<std::size_t>(set.worst)].record) : json(nullptr)},
          {"failed", set.failed},
          {"wall_time_s", set.wall_time_s}};
}

void write_record_set(const std::string& scene, const analysis::RecordSetResult& set, const Provenance& provenance,
                      const std::filesystem::path& folder) {
  std::filesystem::create_directories(folder);
  json document = record_set_json(scene, set);
  document["provenance"] = provenance_json(provenance);
  write_json(document, folder / "records.json");
  write_atomically(folder / "records.csv", [&](std::ostream& out) { write_records_csv(set, out); });
}

json gap_json(const std::string& scene, const analysis::NeededGap& gap,
              const std::vector<analysis::SeverityPoint>& curve) {
  json levels = json::array();
  for (const analysis::LevelGap& l : gap.levels) levels.push_back(level_json(gap, l));
  json modes = json::array();
  for (const analysis::GapMode& m : gap.modes) {
    modes.push_back({{"mode", m.mode}, {"period_s", m.period_s}, {"damping_ratio", m.damping_ratio}});
  }
  json unconservative = json::array();
  for (const analysis::RuleVerdict& v : analysis::rule_verdicts(gap)) {
    if (v.unconservative()) unconservative.push_back({{"rule", v.rule}, {"short_by_m", -v.margin_m}});
  }
  const analysis::LevelGap* governing = gap.entry >= 0 ? &gap.levels[static_cast<std::size_t>(gap.entry)] : nullptr;
  json document = {
      {"scene", scene},
      {"scene_gap_m", gap.scene_gap_m},
      {"needed_gap_m", finite_or_null(gap.needed_gap_m)},
      {"status", solvers::to_string(gap.status)},
      {"status_detail", gap.status_detail},
      {"end_s", gap.end_s},
      {"level", gap.level},
      {"floor", governing ? json({governing->level.floors[0], governing->level.floors[1]}) : json(nullptr)},
      {"t_s", governing ? json(gap.t_s) : json(nullptr)},
      {"pair", pair_json(gap, gap.candidate)},
      {"levels", levels},
      {"modes", modes},
      {"rho", gap.rho},
      {"rules", {{"abs_m", gap.rules.abs_m}, {"srss_m", gap.rules.srss_m}, {"ddc_m", gap.rules.ddc_m}}},
      {"unconservative", unconservative},
      {"extrema", gap.extrema},
      {"steps", gap.steps},
      {"wall_time_s", gap.wall_time_s}};
  if (gap.yielding) document["yield_events"] = gap.yield_events;  // the contact-free run's, yielding scenes only
  if (const auto& amplified = gap.amplified_elastic) {
    json short_of = json::array();
    for (const analysis::RuleVerdict& v : analysis::rule_verdicts(amplified->rules, gap.needed_gap_m)) {
      if (v.unconservative()) short_of.push_back({{"rule", v.rule}, {"short_by_m", -v.margin_m}});
    }
    document["amplified_elastic"] = {
        {"factor", amplified->factor},
        {"status", solvers::to_string(amplified->status)},
        {"elastic_needed_gap_m", finite_or_null(amplified->elastic_needed_gap_m)},
        {"rules",
         {{"abs_m", amplified->rules.abs_m}, {"srss_m", amplified->rules.srss_m}, {"ddc_m", amplified->rules.ddc_m}}},
        {"unconservative", short_of}};
  }
  if (const auto& all = gap.all_angles) {
    document["all_angles"] = {
        {"method", all->method},
        {"step_deg", all->step_deg},
        {"record_angle_deg", all->record_angle_deg},
        {"sample_interval_s", all->method == "superposition" ? json(all->sample_interval_s) : json(nullptr)},
        {"needed_gap_m", all->worst.needed_gap_m},
        {"angle_deg", all->worst.angle_deg},
        {"level", all->worst_level},
        {"t_s", all->worst_t_s},
        {"pair", pair_json(gap, all->worst_candidate)},
        {"refine_tolerance_deg", all->refine_tolerance_deg},
        {"envelope_largest", {{"angle_deg", all->estimate.angle_deg}, {"needed_gap_m", all->estimate.needed_gap_m}}},
        {"runs", all->runs},
        {"status", solvers::to_string(all->status)}};
    if (!all->status_detail.empty()) document["all_angles"]["status_detail"] = all->status_detail;
  }
  if (!curve.empty()) {
    json points = json::array();
    for (const analysis::SeverityPoint& p : curve) {
      points.push_back({{"gap_m", p.gap_m},
                        {"status", p.status},
                        {"impacts", p.impacts},
                        {"max_impulse_kNs", p.max_impulse_kNs},
                        {"max_approach_mps", p.max_approach_mps},
                        {"energy_lost_kJ", p.energy_lost_kJ}});
    }
    document["curve"] = points;
  }
  return document;
}

void write_gap(const std::string& scene, const analysis::NeededGap& gap,
               const std::vector<analysis::SeverityPoint>& curve, const Provenance& provenance,
               const std::filesystem::path& folder) {
  std::filesystem::create_directories(folder);
  json document = gap_json(scene, gap, curve);
  document["provenance"] = provenance_json(provenance);
  write_json(document, folder / "gap.json");
  write_atomically(folder / "gap.csv", [&](std::ostream& out) { write_levels_csv(gap, out); });
  write_atomically(folder / "gap_history.csv", [&](std::ostream& out) { write_history_csv(gap, out); });
  if (!curve.empty()) {
    write_atomically(folder / "gap_curve.csv", [&](std::ostream& out) { write_curve_csv(curve, out); });
  }
  if (gap.all_angles) {
    write_atomically(folder / "gap_angles.csv", [&](std::ostream& out) {
      out << "angle_deg,needed_gap_m\n";
      for (const analysis::AngleGap& a : gap.all_angles->envelope) {
        out << a.angle_deg << ',';
        if (std::isfinite(a.needed_gap_m)) out << a.needed_gap_m;  // empty: no pair closes at that angle
        out << '\n';
      }
    });
  }
}

}  // namespace pounding::io
