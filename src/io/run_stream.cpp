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
  // A summary.json vouches for the files beside it; from here on they are this run's, unfinished.
  std::filesystem::remove(folder_ / "summary.json");
  with_history_ = !columns.empty();
  if (with_history_) {
    history_.open(partial("history.csv"), std::ios::binary | std::ios::trunc);
    contacts_.open(partial("contacts_history.csv"), std::ios::binary | std::ios::trunc);
    write_csv_header(columns, history_);
    write_contact_forces_header(contacts_);
    history_.flush();
    contacts_.flush();
  } else {
    remove_history_files(folder_);
  }
  impacts_.open(partial("impacts.csv"), std::ios::binary | std::ios::trunc);
  opened_ = true;
  write_impacts_header(impacts_);
  impacts_.flush();
  last_flush_ = std::chrono::steady_clock::now();
}

void StreamedRunFiles::history_row(double t_s, const Eigen::VectorXd& values) {
  write_history_row(t_s, values, history_);
  flush_history_if_due();
}

void StreamedRunFiles::contact_force(const solvers::ContactForceSample& sample) {
  write_contact_force_row(sample, contacts_);  // follows its history row, whose flush is due-checked
}

void StreamedRunFiles::impact(const solvers::ImpactRecord& impact) {
  write_impact_row(impact, impacts_);
  impacts_.flush();  // impacts are few and the run's main result: none waits in a buffer
}

void StreamedRunFiles::flush_history_if_due() {
  // The stream's own buffer already reaches the kernel every few kB; this bounds how old the
  // newest row on disk can be when rows come slowly (stiff stretches, many events).
  const auto now = std::chrono::steady_clock::now();
  if (now - last_flush_ < flush_interval_) return;
  history_.flush();
  contacts_.flush();
  last_flush_ = now;
}

void StreamedRunFiles::close_checked(std::ofstream& out, const char* name) {
  out.flush();
  const bool written = static_cast<bool>(out);
  out.close();
  if (!written) throw std::runtime_error(fmt::format("cannot write {} (disk full?)", (folder_ / name).string()));
  commit_partial(partial(name), folder_ / name);
}

void StreamedRunFiles::finish(const analysis::RunReport& report, const Provenance& provenance) {
  if (!opened_) throw std::logic_error("StreamedRunFiles::finish before the run named its history columns");
  if (with_history_) {
    close_checked(history_, "history.csv");
    close_checked(contacts_, "contacts_history.csv");
  }
  close_checked(impacts_, "impacts.csv");
  write_json(run_json(report, provenance), folder_ / "summary.json");
}

void StreamedRunFiles::abandon() {
  if (!opened_) return;
  history_.close();
  contacts_.close();
  impacts_.close();
  std::error_code ignored;  // nothing to report: the run is being refused for its own reason
  std::filesystem::remove(partial("history.csv"), ignored);
  std::filesystem::remove(partial("contacts_history.csv"), ignored);
  std::filesystem::remove(partial("impacts.csv"), ignored);
  opened_ = false;
}

}  // namespace pounding::io
