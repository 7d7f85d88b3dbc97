#include "pounding/analysis/record_set.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>

#include "pounding/analysis/run_scene.hpp"
#include "pounding/input_error.hpp"
#include "parallel.hpp"

namespace pounding::analysis {
namespace {

/// The row's needed gap, governing level and rules from a contact-free run that took steps.
void take_gap(RecordGap& row, const NeededGap& gap) {
  row.needed_gap_m = gap.needed_gap_m;
  row.level = gap.level;
  row.closes = gap.entry >= 0;
  row.t_s = gap.t_s;
  if (row.closes) row.floors = gap.levels[static_cast<std::size_t>(gap.entry)].level.floors;
  row.rules = gap.rules;
}

/// needed_gap(scene) under one record; any failure (a record that cannot be read, a run that
/// fails) becomes the row's message.
RecordGap record_gap(Scene scene, const RecordEntry& entry, const solvers::RunBudget& budget) {
  RecordGap row;
  row.record = entry.name;
  row.source = entry.source;
  const auto clock_start = std::chrono::steady_clock::now();
  try {
    scene.excitation = entry.excitation;
    // Read here for the processed peak and length; needed_gap reads it again (milliseconds,
    // against seconds for the run).
    const excitation::GroundMotion motion = excitation::load_ground_motion(resolved_excitation(scene));
    // A pair: its larger component's.
    row.pga_g = std::max(motion.peak_mps2(), motion.is_pair() ? motion.peak_mps2(1) : 0.0) / scene.excitation.g_mps2;
    row.duration_s = motion.end_s() - motion.start_s();
    const NeededGap gap = needed_gap(scene, budget);
    row.steps = gap.steps;
    row.status = std::string(solvers::to_string(gap.status));  // interrupted / time_limit: a partial run
    row.message = gap.status_detail;
    // Stopped before its first step (the set was interrupted while it waited), a run has no gap,
    // not the gap at rest: its row stays empty rather than show round-off as a needed gap.
    if (gap.status == solvers::RunStatus::completed || gap.steps > 0) {
      take_gap(row, gap);
    } else {
      row.message = "not started: " + row.message;
    }
  } catch (const std::exception& error) {
    row.message = error.what();
  }
  row.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return row;
}

std::vector<double> column(const std::vector<RecordGap>& rows, double (*value)(const RecordGap&)) {
  std::vector<double> values;
  for (const RecordGap& row : rows) {
    if (row.completed()) values.push_back(value(row));
  }
  return values;
}

}  // namespace

SetStatistic set_statistic(const std::vector<double>& values) {
  std::vector<double> x;
  for (double v : values) {
    if (v > 0.0 && std::isfinite(v)) x.push_back(v);
  }
  SetStatistic s;
  s.count = static_cast<int>(x.size());
  if (x.empty()) return s;
  std::sort(x.begin(), x.end());
  const std::size_t n = x.size();
  double sum = 0.0, log_sum = 0.0;
  for (double v : x) sum += v, log_sum += std::log(v);
  s.mean = sum / static_cast<double>(n);
  s.median = n % 2 == 1 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
  s.log_mean = log_sum / static_cast<double>(n);
  if (n < 2) return s;  // one value has no spread to fit
  double squares = 0.0;
  for (double v : x) squares += (std::log(v) - s.log_mean) * (std::log(v) - s.log_mean);
  s.log_std = std::sqrt(squares / static_cast<double>(n - 1));
  s.p84_lognormal = std::exp(s.log_mean + s.log_std);
  return s;
}

std::vector<RecordEntry> pair_records(const Scene& row, const std::vector<RecordEntry>& records, double turned_deg) {
  std::vector<RecordEntry> turned;
  Scene shaken = row;
  for (const RecordEntry& entry : records) {
    shaken.excitation = entry.excitation;
    RecordEntry& pair_entry = turned.emplace_back(entry);
    pair_entry.excitation = resolved_excitation(shaken);
    if (pair_entry.excitation.scale_to_sa) pair_entry.excitation.scale_to_sa->building = 0;  // its period resolved
    pair_entry.excitation.direction_deg = std::fmod(pair_entry.excitation.direction_deg + turned_deg, 360.0);
    pair_entry.choice = {};
  }
  return turned;
}

RecordSetResult record_set_gaps(const Scene& scene, const std::vector<RecordEntry>& records, unsigned threads,
                                const std::function<void(const RecordGap&)>& progress,
                                const solvers::RunBudget& budget) {
  if (records.empty()) throw InputError("records", "none", "a record set needs at least one record");
  const auto clock_start = std::chrono::steady_clock::now();
  RecordSetResult result;
  result.records.resize(records.size());
  std::mutex progress_mutex;
  detail::parallel_for(records.size(), threads, [&](std::size_t k) {
    result.records[k] = record_gap(scene, records[k], budget);
    if (progress) {
      const std::lock_guard<std::mutex> lock(progress_mutex);
      progress(result.records[k]);
    }
  });
  const std::vector<RecordGap>& rows = result.records;
  result.needed_gap_m = set_statistic(column(rows, [](const RecordGap& r) { return r.needed_gap_m; }));
  result.abs_m = set_statistic(column(rows, [](const RecordGap& r) { return r.rules.abs_m; }));
  result.srss_m = set_statistic(column(rows, [](const RecordGap& r) { return r.rules.srss_m; }));
  result.ddc_m = set_statistic(column(rows, [](const RecordGap& r) { return r.rules.ddc_m; }));
  for (std::size_t k = 0; k < rows.size(); ++k) {
    if (!rows[k].completed()) {
      ++result.failed;
    } else if (std::isfinite(rows[k].needed_gap_m) &&
               (result.worst < 0 || rows[k].needed_gap_m > rows[static_cast<std::size_t>(result.worst)].needed_gap_m)) {
      result.worst = static_cast<long>(k);
    }
  }
  result.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return result;
}

}  // namespace pounding::analysis
