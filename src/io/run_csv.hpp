#pragma once
// The lines of history.csv and impacts.csv, shared by the writer that writes a finished run and
// the one that streams a run as it goes, so both produce the same bytes. Impact rows follow
// impact_schema.hpp, the list summary.json's impacts follow too.

#include <Eigen/Core>
#include <ostream>
#include <string>
#include <vector>

#include "pounding/solvers/run_result.hpp"

namespace pounding::io {

void write_impacts_header(std::ostream& out);
void write_impact_row(const solvers::ImpactRecord& impact, std::ostream& out);
/// One header line: the columns, comma-separated.
void write_csv_header(const std::vector<std::string>& columns, std::ostream& out);
void write_history_row(double t_s, const Eigen::VectorXd& values, std::ostream& out);

}  // namespace pounding::io
