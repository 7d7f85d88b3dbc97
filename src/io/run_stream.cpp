#include "pounding/io/run_stream.hpp"

#include <fmt/format.h>
#include <stdexcept>
#include <system_error>

#include "pounding/io/json_report.hpp"
#include "pounding/io/output_files.hpp"
#include "pounding/io/run_writer.hpp"
#include "run_csv.hpp"

namespace pounding::io {

StreamedRunFiles::StreamedRunFiles(std::filesystem::path folder, double flush_interval_s)
    : folder_(std::move(folder)), flush_interval_(flush_interval_s) {}

std::filesystem::path StreamedRunFiles::partial(const char* name) const {
  return folder_ / fmt::format("{}.partial", name);
}

void StreamedRunFiles::history_columns(const std::vector<std::string>& columns) {
  std::filesystem::create_directories(folder_);
  // A summary.json vouches for the files beside it, so it goes first; then an earlier run's
  // results, so that a killed run leaves only its own .partial files, never a mix of two runs.
  std::filesystem::remove(folder_ / "summary.json");
  std::filesystem::remove(folder_ / "impacts.csv");
  remove_history_files(folder_);
  with_history_ = !columns.empty();
  if (with_history_) {
    history_ = std::make_unique<ExclusiveOutput>(partial("history.csv"));
    contacts_ = std::make_unique<ExclusiveOutput>(partial("contacts_history.csv"));
    write_csv_header(columns, history_->stream());
    write_contact_forces_header(contacts_->stream());
    history_->stream().flush();
    contacts_->stream().flush();
  }
  impacts_ = std::make_unique<ExclusiveOutput>(partial("impacts.csv"));
  opened_ = true;
  write_impacts_header(impacts_->stream(), fields_);
  impacts_->stream().flush();
  last_flush_ = std::chrono::steady_clock::now();
}

void StreamedRunFiles::history_row(double t_s, const Eigen::VectorXd& values) {
  write_history_row(t_s, values, history_->stream());
  flush_history_if_due();
}

void StreamedRunFiles::contact_force(const solvers::ContactForceSample& sample) {
  write_contact_force_row(sample, contacts_->stream());  // follows its history row, whose flush is due-checked
}

void StreamedRunFiles::impact(const solvers::ImpactRecord& impact) {
  write_impact_row(impact, impacts_->stream(), fields_);
  impacts_->stream().flush();  // impacts are few and the run's main result: none waits in a buffer
}

void StreamedRunFiles::flush_history_if_due() {
  // The stream's own buffer already reaches the kernel every few kB; this bounds how old the
  // newest row on disk can be when rows come slowly (stiff stretches, many events).
  const auto now = std::chrono::steady_clock::now();
  if (now - last_flush_ < flush_interval_) return;
  history_->stream().flush();
  contacts_->stream().flush();
  last_flush_ = now;
}

void StreamedRunFiles::close_checked(std::unique_ptr<ExclusiveOutput>& out, const char* name) {
  out->close(folder_ / name);
  out.reset();
  commit_partial(partial(name), folder_ / name);
}

void StreamedRunFiles::finish(const analysis::RunReport& report, const Provenance& provenance) {
  if (!opened_) throw std::logic_error("StreamedRunFiles::finish before the run named its history columns");
  if (with_history_) {
    close_checked(history_, "history.csv");
    close_checked(contacts_, "contacts_history.csv");
  }
  close_checked(impacts_, "impacts.csv");
  write_yielding_csv(report, folder_);
  write_json(run_json(report, provenance), folder_ / "summary.json");
}

void StreamedRunFiles::abandon() {
  if (!opened_) return;
  history_.reset();
  contacts_.reset();
  impacts_.reset();
  std::error_code ignored;  // nothing to report: the run is being refused for its own reason
  std::filesystem::remove(partial("history.csv"), ignored);
  std::filesystem::remove(partial("contacts_history.csv"), ignored);
  std::filesystem::remove(partial("impacts.csv"), ignored);
  opened_ = false;
}

}  // namespace pounding::io
