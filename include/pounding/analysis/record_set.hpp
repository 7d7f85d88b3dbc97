#pragma once
// The needed gap (analysis::needed_gap) of one scene under each record of a set, run by run on
// threads, and the statistics engineers take over a design suite: mean, median and the 84th
// percentile of a lognormal fit. Units: m, s, g.

#include <array>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "pounding/analysis/needed_gap.hpp"
#include "pounding/analysis/scene.hpp"
#include "pounding/excitation/record_choice.hpp"

namespace pounding::analysis {

/// One record of a set: the scene's excitation with the record's own file and options.
struct RecordEntry {
  std::string name;    // the record file's name, for tables
  std::string source;  // where it was listed ("set.txt:4"), or the folder it was found in
  excitation::ExcitationSpec excitation;
  /// What the list said of the record (its resolved file and the fields given): applied to the
  /// same scene with excitation::with_record it gives `excitation` again, so a sweep can send a
  /// worker these few values instead of the spec.
  excitation::RecordChoice choice{};
};

/// The needed gap under one record. A record that cannot be read or run is a row with status
/// "failed" and the reason in `message`; its numbers are NaN.
struct RecordGap {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::string record;
  std::string source;
  std::string status = "failed";  // "completed" | "failed" | "interrupted" | "time_limit" (message says where)
  std::string message;
  double pga_g = kNaN;              // processed peak |a_g|
  double duration_s = kNaN;         // of the processed record
  double needed_gap_m = kNaN;       // −inf if no pair ever closes
  int level = 0;                    // governing level (0: none, or a slab facing columns)
  bool closes = false;              // some pair closes (NeededGap::entry ≥ 0)
  std::array<int, 2> floors{0, 0};  // its floors of building 1 and 2 (slab to column: the slab's floor and the storey)
  double t_s = kNaN;                // when the governing pair closes most
  GapRules rules{kNaN, kNaN, kNaN};
  long steps = 0;
  double wall_time_s = 0.0;
  bool completed() const { return status == "completed"; }
};

/// Mean, median and lognormal 84th percentile exp(m + s) of the positive finite values, where m
/// and s are the mean and the sample standard deviation (divisor n − 1) of their logarithms.
/// Values that are not positive and finite (a record under which no pair closes) are left out.
struct SetStatistic {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  int count = 0;  // values used
  double mean = kNaN;
  double median = kNaN;
  double log_mean = kNaN;  // m
  double log_std = kNaN;   // s (needs two values)
  double p84_lognormal = kNaN;
};
SetStatistic set_statistic(const std::vector<double>& values);

struct RecordSetResult {
  std::vector<RecordGap> records;                   // in the order of the set
  SetStatistic needed_gap_m, abs_m, srss_m, ddc_m;  // over the completed records
  long worst = -1;                                  // index of the record with the largest needed gap (−1: none)
  int failed = 0;
  double wall_time_s = 0.0;
};

/// A row's record set as one of its pairs sees it, run on the pair's own scene
/// (Scene::pair_scene_facing_x, whose plan is turned by `turned_deg`): each record's shaking
/// direction turned with the plan, and a spectral scaling at a building's period resolved for the
/// whole row, so that every pair is shaken by the motion the row is. (Each entry's `choice` is
/// left empty: it no longer applies to the pair's scene.)
std::vector<RecordEntry> pair_records(const Scene& row, const std::vector<RecordEntry>& records, double turned_deg);

/// Runs needed_gap(scene) with each record's excitation, `threads` runs at a time (0: every
/// core); `progress` is called after each record (from any thread, one call at a time). The
/// results do not depend on `threads`: the runs share nothing but the (copied) scene. `budget`
/// bounds each run; after a SIGINT/SIGTERM every run still to come stops at once (interrupted).
/// @throws InputError if `records` is empty. A record's own failure never throws: it is a row.
RecordSetResult record_set_gaps(const Scene& scene, const std::vector<RecordEntry>& records, unsigned threads = 0,
                                const std::function<void(const RecordGap&)>& progress = {},
                                const solvers::RunBudget& budget = {});

}  // namespace pounding::analysis
