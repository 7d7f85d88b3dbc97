#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <unistd.h>

#include "pounding/analysis/run_scene.hpp"
#include "pounding/io/impact_schema.hpp"
#include "pounding/io/provenance.hpp"
#include "pounding/io/run_report.hpp"
#include "pounding/io/run_writer.hpp"
#include "pounding/io/scene_reader.hpp"
#include "pounding/io/sha256.hpp"

using namespace pounding;
namespace fs = std::filesystem;

namespace {

const fs::path kPaper = POUNDING_EXAMPLES_DIR "/paper/paper.toml";

/// The paper scene at its 0.20 m gap: 45 impacts on two levels and sustained contacts, run once.
const analysis::RunReport& paper_run() {
  static const analysis::RunReport report = analysis::run_scene(io::read_scene(kPaper));
  return report;
}

std::vector<std::string> split(const std::string& line, char separator) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  for (std::string field; std::getline(in, field, separator);) fields.push_back(field);
  return fields;
}

/// The documented flattening of one JSON impact into CSV columns (impact_schema.hpp), written
/// out here independently of the schema: arrays become key_component[_unit].
std::vector<std::string> flattened_keys(const nlohmann::ordered_json& impact) {
  std::vector<std::string> columns;
  for (const auto& [key, value] : impact.items()) {
    if (!value.is_array()) {
      columns.push_back(key);
    } else if (key == "floors") {
      columns.insert(columns.end(), {"floors_b1", "floors_b2"});
    } else {
      columns.insert(columns.end(), {key + "_x_m", key + "_y_m"});
    }
  }
  return columns;
}

std::string shell_output(const std::string& command) {
  std::string text;
  FILE* pipe = ::popen(command.c_str(), "r");
  BOOST_REQUIRE(pipe != nullptr);
  for (int c; (c = std::fgetc(pipe)) != EOF;) text += static_cast<char>(c);
  ::pclose(pipe);
  return text;
}

}  // namespace

// impacts.csv and summary.json's impacts carry the same fields, in the same order, with the same
// values: the header is the JSON keys flattened, and each row reads back to the JSON values.
BOOST_AUTO_TEST_CASE(impacts_csv_is_summary_impacts_flattened) {
  const analysis::RunReport& report = paper_run();
  BOOST_REQUIRE(report.result.impacts.size() > 10u);
  const fs::path folder = fs::temp_directory_path() / fmt::format("pounding-test-run-outputs-{}", ::getpid());
  io::write_run(report, io::Provenance{}, folder);
  const nlohmann::ordered_json summary = nlohmann::ordered_json::parse(std::ifstream(folder / "summary.json"));
  std::ifstream csv(folder / "impacts.csv");
  std::string header;
  std::getline(csv, header);

  const nlohmann::ordered_json first = io::impact_json(report.result.impacts.front());
  BOOST_TEST(first.contains("vertex_rest"));
  BOOST_TEST(split(header, ',') == flattened_keys(first), boost::test_tools::per_element());
  BOOST_TEST(io::impact_csv_columns() == flattened_keys(first), boost::test_tools::per_element());
  std::size_t k = 0;
  for (std::string line; std::getline(csv, line); ++k) {
    BOOST_REQUIRE(k < summary["impacts"].size());
    const std::vector<std::string> row = split(line, ',');
    std::vector<double> from_json;
    for (const auto& [key, value] : summary["impacts"][k].items()) {
      if (value.is_array()) {
        for (const auto& v : value) from_json.push_back(v.get<double>());
      } else {
        from_json.push_back(value.is_boolean() ? double(value.get<bool>()) : value.get<double>());
      }
    }
    BOOST_REQUIRE(row.size() == from_json.size());
    for (std::size_t c = 0; c < row.size(); ++c)
      BOOST_TEST(std::stod(row[c]) == from_json[c], "impact " << k << " column " << c);
  }
  BOOST_TEST(k == report.result.impacts.size());
  fs::remove_all(folder);
}

// summary.json's keys come in the documented order: scene, method, status and its warnings first,
// provenance last.
BOOST_AUTO_TEST_CASE(summary_keys_in_fixed_order) {
  const nlohmann::ordered_json summary = io::run_json(paper_run(), io::Provenance{});
  std::vector<std::string> keys;
  for (const auto& [key, value] : summary.items()) keys.push_back(key);
  BOOST_REQUIRE(keys.size() > 5u);
  BOOST_TEST((std::vector<std::string>(keys.begin(), keys.begin() + 6) ==
              std::vector<std::string>{"scene", "method", "status", "status_detail", "warnings", "settings"}));
  BOOST_TEST(keys.back() == "provenance");
}

// One numbering of vertices: every impact's, touch's and sustained contact's vertex (the 1-based
// slab-outline number) has its history.csv column on its own floor, and the peaks list the
// tracked vertices by the same numbers, at the rest points of those outline vertices.
BOOST_AUTO_TEST_CASE(history_columns_use_slab_outline_numbers) {
  const analysis::RunReport& report = paper_run();
  const analysis::Scene scene = io::read_scene(kPaper);
  const std::vector<std::string>& columns = report.result.history.columns;
  auto has_column = [&](int building, int floor, std::size_t vertex) {
    const std::string name = fmt::format("B{}_f{}_vtx{}_dx_m", building, floor, vertex);
    return std::find(columns.begin(), columns.end(), name) != columns.end();
  };
  BOOST_REQUIRE(!report.result.sustained_contacts.empty());
  for (const auto& i : report.result.impacts) {
    BOOST_TEST(has_column(i.striking_building, i.floors[i.striking_building - 1], i.vertex), "impact at " << i.t_s);
  }
  for (const auto& s : report.result.sustained_contacts) {
    BOOST_TEST(has_column(s.striking_building, s.floors[s.striking_building - 1], s.vertex), "hold from " << s.start_s);
  }
  for (const auto& t : report.result.touches) {
    BOOST_TEST(has_column(t.striking_building, t.floors[t.striking_building - 1], t.vertex), "touch at " << t.t_s);
  }
  for (std::size_t b = 0; b < 2; ++b) {
    const solvers::BuildingPeaks& peaks = report.result.peaks[b];
    BOOST_REQUIRE(peaks.contact_vertices.size() == peaks.contact_vertices_rest.size());
    for (std::size_t k = 0; k < peaks.contact_vertices.size(); ++k) {
      const int number = peaks.contact_vertices[k];
      BOOST_TEST(peaks.contact_vertices_rest[k] ==
                 scene.buildings[b].slab.vertex(static_cast<std::size_t>(number - 1)));
      BOOST_TEST(has_column(static_cast<int>(b) + 1, 7, static_cast<std::size_t>(number)));
    }
  }
}

// The reports say what the run says: counts, first impact time and status from the RunReport.
BOOST_AUTO_TEST_CASE(brief_and_full_reports) {
  const analysis::RunReport& report = paper_run();
  const solvers::RunResult& r = report.result;
  const std::string brief = io::brief_report(report);
  BOOST_TEST(brief.find('\n') == std::string::npos);
  BOOST_TEST(brief.starts_with("paper: cvode-bdf, completed, "));
  BOOST_TEST(brief.find(fmt::format("{} impacts, first at t = {:.6f} s", r.impacts.size(), r.impacts.front().t_s)) !=
                 std::string::npos,
             brief);
  const std::string full = io::full_report(report);
  BOOST_TEST(full.ends_with("\n"));
  BOOST_TEST(
      full.starts_with(fmt::format("Run 'paper' with cvode-bdf ({}), gap 0.2 m", io::method_settings_text(report))));
  BOOST_TEST(full.find(fmt::format("\nImpacts: {};", r.impacts.size())) != std::string::npos);
  BOOST_TEST(full.find(fmt::format("\nSustained contacts: {}\n", r.sustained_contacts.size())) != std::string::npos);
  const auto& first = r.impacts.front();
  BOOST_TEST(full.find(fmt::format("(B{} vertex {} strikes)", first.striking_building, first.vertex)) !=
             std::string::npos);
  BOOST_TEST(full.find("\nSolver: ") != std::string::npos);
}

// Provenance: the files' digests are their SHA-256, the paths absolute, the date ISO 8601 UTC.
BOOST_AUTO_TEST_CASE(provenance_of_a_scene) {
  const analysis::Scene scene = io::read_scene(kPaper);
  const io::Provenance p = io::make_provenance(scene, "pounding run paper.toml");
  BOOST_TEST(p.scene_file.is_absolute());
  BOOST_TEST(fs::equivalent(p.scene_file, kPaper));
  BOOST_TEST(p.scene_sha256 == io::sha256_file_hex(kPaper));
  BOOST_TEST(fs::equivalent(p.record_file, scene.excitation.file));
  BOOST_TEST(p.record_sha256.size() == 64u);
  BOOST_TEST(p.record_sha256 != p.scene_sha256);
  BOOST_TEST(p.date_utc.size() == 20u);
  BOOST_TEST((p.date_utc[4] == '-' && p.date_utc[10] == 'T' && p.date_utc.back() == 'Z'), p.date_utc);
  const nlohmann::ordered_json j = io::provenance_json(p);
  BOOST_TEST(j["scene_sha256"] == p.scene_sha256);
  BOOST_TEST(j["command_line"] == "pounding run paper.toml");
  BOOST_TEST(io::provenance_json(io::Provenance{})["scene_file"].is_null());
}

// The command line as written splits back, in a POSIX shell, into the very same arguments.
BOOST_AUTO_TEST_CASE(command_line_quoting_round_trips_through_a_shell) {
  const std::vector<std::string> arguments = {"pounding",  "run", "my scene.toml", "--out",
                                              "it's here", "",    "$HOME",         "a\"b"};
  const std::string line = io::command_line_text(arguments);
  BOOST_TEST(line.starts_with("pounding run 'my scene.toml' --out "));
  std::string expected;
  for (const std::string& a : arguments) expected += "[" + a + "]";
  const std::string script = "printf '[%s]' " + line;
  BOOST_TEST(shell_output("/bin/sh -c " + io::command_line_text({script})) == expected);
}
