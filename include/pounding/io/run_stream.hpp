#pragma once
// Streams a run's history.csv, contacts_history.csv and impacts.csv into its output folder while it runs, so a run that
// is killed (SIGKILL, out of memory, a crash) leaves every row computed up to shortly before.

#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>

#include "pounding/analysis/run_scene.hpp"
#include "pounding/io/impact_schema.hpp"
#include "pounding/io/output_files.hpp"
#include "pounding/io/provenance.hpp"
#include "pounding/solvers/run_sink.hpp"

namespace pounding::io {

/// While the run goes, rows go to `history.csv.partial`, `contacts_history.csv.partial` and
/// `impacts.csv.partial` (each with its header): impacts flushed at every row, the histories at
/// least every `flush_interval_s` of wall time.
/// The files open when the run names its columns (just before its first row, once it has passed
/// its checks), each created afresh and never through a link (ExclusiveOutput); an earlier run's
/// outputs in the folder (summary.json, history.csv, contacts_history.csv, impacts.csv) are
/// removed then, so a folder never holds one run's files beside another's, even when this run
/// is killed. finish() renames them and writes summary.json last,
/// the same files write_run() writes for the same run, byte for byte in the CSVs. A run without
/// history (no columns) writes impacts.csv only, and removes an earlier run's histories.
class StreamedRunFiles final : public solvers::RunSink {
 public:
  explicit StreamedRunFiles(std::filesystem::path folder, double flush_interval_s = 1.0);

  void history_columns(const std::vector<std::string>& columns) override;
  void history_row(double t_s, const Eigen::VectorXd& values) override;
  void impact(const solvers::ImpactRecord& impact) override;
  void contact_force(const solvers::ContactForceSample& sample) override;
  void progress(double t_s, double end_s, std::size_t impacts) override {
    if (on_progress_) on_progress_(t_s, end_s, impacts);
  }
  /// Which fields impacts.csv carries beyond the common ones (impact_field_set of the run's
  /// candidates); set before the run starts.
  void impact_fields(ImpactFieldSet fields) { fields_ = fields; }
  /// Passes the run's progress (RunSink::progress) to `callback` (to show it; null: to nobody).
  void on_progress(std::function<void(double t_s, double end_s, std::size_t impacts)> callback) {
    on_progress_ = std::move(callback);
  }

  /// Renames the streamed files to history.csv, contacts_history.csv and impacts.csv, then
  /// writes summary.json.
  /// @throws std::runtime_error naming a file that could not be written (disk full, ...).
  void finish(const analysis::RunReport& report, const Provenance& provenance);
  /// Closes and removes the streamed files: the run was refused after all and leaves nothing.
  void abandon();

 private:
  std::filesystem::path partial(const char* name) const;
  void flush_history_if_due();
  void close_checked(std::unique_ptr<ExclusiveOutput>& out, const char* name);

  std::filesystem::path folder_;
  std::chrono::duration<double> flush_interval_;
  std::chrono::steady_clock::time_point last_flush_;
  std::unique_ptr<ExclusiveOutput> history_, contacts_, impacts_;
  bool opened_ = false;
  bool with_history_ = false;  // history.csv and contacts_history.csv are written
  ImpactFieldSet fields_;
  std::function<void(double, double, std::size_t)> on_progress_;
};

}  // namespace pounding::io
