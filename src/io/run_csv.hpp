#pragma once
// The lines of history.csv, contacts_history.csv and impacts.csv, shared by the writer that writes a finished run and
// the one that streams a run as it goes, so both produce the same bytes. Impact rows follow
// impact_schema.hpp, the list summary.json's impacts follow too.

#include <Eigen/Core>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "pounding/io/impact_schema.hpp"
#include "pounding/solvers/run_result.hpp"

namespace pounding::io {

/// `fields`: which of the fields marked for some scenes only to write (impact_schema.hpp).
void write_impacts_header(std::ostream& out, ImpactFieldSet fields);
void write_impact_row(const solvers::ImpactRecord& impact, std::ostream& out, ImpactFieldSet fields);
/// One header line: the columns, comma-separated.
void write_csv_header(const std::vector<std::string>& columns, std::ostream& out);
void write_history_row(double t_s, const Eigen::VectorXd& values, std::ostream& out);
/// contacts_history.csv: one row per contact carrying a force at a history instant (tidy, long
/// form: a column per candidate would mostly hold zeros), its columns contact_force_columns()
/// (output_schema.hpp).
void write_contact_forces_header(std::ostream& out);
void write_contact_force_row(const solvers::ContactForceSample& sample, std::ostream& out);
/// Removes an earlier run's history.csv and contacts_history.csv from `folder`, for a run that
/// writes neither: no file may stand beside a summary.json that is not its run's.
void remove_history_files(const std::filesystem::path& folder);
/// yielding.csv: one row per yielding column spring, its columns yielding_columns() (output_schema.hpp);
/// removed for a run whose columns stay elastic.
void write_yielding_csv(const analysis::RunReport& report, const std::filesystem::path& folder);

}  // namespace pounding::io
