#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <unistd.h>

#include "pounding/analysis/run_scene.hpp"
#include "pounding/io/run_stream.hpp"
#include "pounding/io/run_writer.hpp"
#include "pounding/io/scene_reader.hpp"

using namespace pounding;
namespace fs = std::filesystem;

namespace {

std::string contents(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  BOOST_REQUIRE_MESSAGE(in, "cannot read " << file);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// A fresh, empty folder for one check (the pid keeps concurrent test runs apart).
fs::path scratch(const std::string& name) {
  const fs::path folder =
      fs::temp_directory_path() / ("pounding-test-run-stream-" + std::to_string(::getpid()) + "-" + name);
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

/// summary.json without its wall time, the one value two runs of one scene do not share.
nlohmann::json summary_without_wall_time(const fs::path& folder) {
  nlohmann::json summary = nlohmann::json::parse(contents(folder / "summary.json"));
  summary["statistics"].erase("wall_time_s");
  return summary;
}

std::size_t lines(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

}  // namespace

// The paper scene pounds (impacts on several floors) and has event rows between the samples, so
// both CSVs exercise every kind of row; one event-driven path and HHT, the two recorders' users.
BOOST_AUTO_TEST_CASE(streamed_files_equal_the_in_memory_writers) {
  for (const std::string method : {"cvode-bdf", "hht"}) {
    BOOST_TEST_CONTEXT("method " << method) {
      analysis::Scene scene = io::read_scene(POUNDING_EXAMPLES_DIR "/paper/paper.toml");
      scene.solver.method = method;
      const fs::path in_memory = scratch(method + "-memory"), streamed = scratch(method + "-streamed");

      const io::Provenance provenance = io::make_provenance(scene);
      const analysis::RunReport kept = analysis::run_scene(scene);
      io::write_run(kept, provenance, in_memory);
      io::StreamedRunFiles files(streamed);
      const analysis::RunReport sent = analysis::run_scene(scene, {}, &files);
      files.finish(sent, provenance);

      BOOST_TEST(kept.result.impacts.size() > 10u);
      BOOST_TEST(kept.result.history.rows.size() > 1000u);
      BOOST_TEST(sent.result.history.rows.empty());  // streamed, so not also kept in memory
      BOOST_TEST(sent.result.history.time_s.empty());
      BOOST_TEST(sent.result.history.columns == kept.result.history.columns);
      const std::string history = contents(streamed / "history.csv");
      BOOST_TEST(lines(history) == kept.result.history.rows.size() + 1);
      BOOST_TEST((history == contents(in_memory / "history.csv")));
      BOOST_TEST((contents(streamed / "impacts.csv") == contents(in_memory / "impacts.csv")));
      // The paper scene holds contacts in sustained contact (cvode-bdf), whose forces are rows.
      const std::string contacts = contents(streamed / "contacts_history.csv");
      BOOST_TEST(lines(contacts) == kept.result.history.contact_forces.size() + 1);
      if (method == "cvode-bdf") BOOST_TEST(kept.result.history.contact_forces.size() > 10u);
      BOOST_TEST((contacts == contents(in_memory / "contacts_history.csv")));
      BOOST_TEST(summary_without_wall_time(streamed) == summary_without_wall_time(in_memory));
      for (const auto& entry : fs::directory_iterator(streamed)) {
        BOOST_TEST(entry.path().extension() != ".partial", "left behind: " << entry.path());
      }
      fs::remove_all(in_memory);
      fs::remove_all(streamed);
    }
  }
}

// What a kill leaves: the files as they stand mid-run hold their header and every row sent so
// far, and an earlier run's summary.json is gone, so no summary disagrees with them.
BOOST_AUTO_TEST_CASE(an_unfinished_stream_leaves_partial_files_and_no_summary) {
  const fs::path folder = scratch("unfinished");
  std::ofstream(folder / "summary.json") << "{}\n";  // an earlier run's
  io::StreamedRunFiles files(folder, 3600.0);        // no timed flush: rows must reach disk anyway
  files.history_columns({"t_s", "B1_f1_u_m"});
  for (int k = 0; k < 20000; ++k) files.history_row(0.01 * k, Eigen::VectorXd::Constant(1, 1e-3 * k));
  solvers::ImpactRecord impact;
  impact.t_s = 1.5;
  files.impact(impact);

  BOOST_TEST(!fs::exists(folder / "summary.json"));
  BOOST_TEST(!fs::exists(folder / "history.csv"));
  const std::string history = contents(folder / "history.csv.partial");
  BOOST_TEST(history.starts_with("t_s,B1_f1_u_m\n0,0\n"));
  BOOST_TEST(lines(history) > 15000u);  // all but what the stream's buffer still holds
  const std::string impacts = contents(folder / "impacts.csv.partial");
  BOOST_TEST(lines(impacts) == 2u);  // header and the impact: flushed at once
  BOOST_TEST(impacts.find("\n1.5,") != std::string::npos);

  files.abandon();  // a refused run: the streamed files go
  BOOST_TEST(fs::is_empty(folder));
  fs::remove(folder);
}
