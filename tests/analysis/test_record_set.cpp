#include <boost/test/unit_test.hpp>

#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <numbers>

#include "pounding/analysis/record_set.hpp"
#include "pounding/analysis/run_scene.hpp"
#include "pounding/io/record_list.hpp"
#include "pounding/io/scene_reader.hpp"

using namespace pounding;
namespace tt = boost::test_tools;

namespace {

const std::filesystem::path kExamples = POUNDING_EXAMPLES_DIR;

/// Every field of two rows but the wall time, compared exactly (NaN equal to NaN).
void require_same_row(const analysis::RecordGap& a, const analysis::RecordGap& b) {
  auto same = [](double x, double y) { return x == y || (std::isnan(x) && std::isnan(y)); };
  BOOST_TEST_INFO(a.record);
  BOOST_TEST(a.record == b.record);
  BOOST_TEST(a.status == b.status);
  BOOST_TEST(a.message == b.message);
  BOOST_TEST(same(a.pga_g, b.pga_g));
  BOOST_TEST(same(a.duration_s, b.duration_s));
  BOOST_TEST(same(a.needed_gap_m, b.needed_gap_m));
  BOOST_TEST(a.level == b.level);
  BOOST_TEST((a.floors == b.floors));
  BOOST_TEST(same(a.t_s, b.t_s));
  BOOST_TEST(same(a.rules.abs_m, b.rules.abs_m));
  BOOST_TEST(same(a.rules.srss_m, b.rules.srss_m));
  BOOST_TEST(same(a.rules.ddc_m, b.rules.ddc_m));
  BOOST_TEST(a.steps == b.steps);
}

}  // namespace

BOOST_AUTO_TEST_CASE(StatisticsMatchTheirClosedForms) {
  // ln x = 0, 1, 2: mean 1, sample standard deviation 1, so the 84th percentile is e².
  const double e = std::numbers::e;
  const analysis::SetStatistic odd = analysis::set_statistic({e * e, 1.0, e});
  BOOST_TEST(odd.count == 3);
  BOOST_TEST(odd.mean == (1.0 + e + e * e) / 3.0, tt::tolerance(1e-15));
  BOOST_TEST(odd.median == e);
  BOOST_TEST(odd.log_mean == 1.0, tt::tolerance(1e-15));
  BOOST_TEST(odd.log_std == 1.0, tt::tolerance(1e-15));
  BOOST_TEST(odd.p84_lognormal == e * e, tt::tolerance(1e-14));

  // 0.1·2^k, k = 0…3: ln x = ln 0.1 + k ln 2, mean ln 0.1 + 1.5 ln 2, sample variance
  // (ln 2)²·(2·1.5² + 2·0.5²)/3 = (ln 2)²·5/3; the median is the mean of 0.2 and 0.4.
  // Values that are not positive and finite (a record under which no pair closes) are left out.
  const double inf = std::numeric_limits<double>::infinity();
  const analysis::SetStatistic even = analysis::set_statistic({0.8, -inf, 0.1, 0.4, 0.0, 0.2, std::nan("")});
  const double ln2 = std::numbers::ln2;
  BOOST_TEST(even.count == 4);
  BOOST_TEST(even.mean == 0.375, tt::tolerance(1e-15));
  BOOST_TEST(even.median == 0.3, tt::tolerance(1e-15));
  BOOST_TEST(even.log_std == ln2 * std::sqrt(5.0 / 3.0), tt::tolerance(1e-14));
  BOOST_TEST(even.p84_lognormal == std::exp(std::log(0.1) + 1.5 * ln2 + ln2 * std::sqrt(5.0 / 3.0)),
             tt::tolerance(1e-14));

  // One value has a mean and a median but no spread: no 84th percentile.
  const analysis::SetStatistic one = analysis::set_statistic({0.25});
  BOOST_TEST(one.mean == 0.25);
  BOOST_TEST(one.median == 0.25);
  BOOST_TEST(std::isnan(one.p84_lognormal));
  BOOST_TEST(analysis::set_statistic({}).count == 0);
}

BOOST_AUTO_TEST_CASE(OneAndTwoThreadsGiveIdenticalResultsAndTheRowsAreSingleRuns) {
  const analysis::Scene scene = io::read_scene(kExamples / "paper" / "el-centro-true-time.toml");
  std::vector<analysis::RecordEntry> set = io::read_record_list(kExamples / "records" / "set.txt", scene.excitation);
  BOOST_TEST_REQUIRE(set.size() >= 5u);
  for (analysis::RecordEntry& entry : set) entry.excitation.duration_s = 6.0;  // the strong part, for a short test
  analysis::RecordEntry unreadable = set.back();  // a two-column text file read as a PEER record fails
  unreadable.excitation.read = {};
  unreadable.name = "unreadable";
  set.insert(set.begin() + 2, unreadable);

  int reported = 0;
  const analysis::RecordSetResult one = analysis::record_set_gaps(scene, set, 1);
  const analysis::RecordSetResult two =
      analysis::record_set_gaps(scene, set, 2, [&](const analysis::RecordGap&) { ++reported; });
  BOOST_TEST(reported == static_cast<int>(set.size()));
  BOOST_TEST_REQUIRE(one.records.size() == set.size());
  BOOST_TEST_REQUIRE(two.records.size() == set.size());
  for (std::size_t k = 0; k < set.size(); ++k) require_same_row(one.records[k], two.records[k]);
  BOOST_TEST(one.failed == 1);
  BOOST_TEST(two.failed == 1);
  BOOST_TEST(!one.records[2].completed());
  BOOST_TEST(one.records[2].message.find("PEER header") != std::string::npos, one.records[2].message);
  BOOST_TEST(one.worst == two.worst);
  BOOST_TEST(one.needed_gap_m.p84_lognormal == two.needed_gap_m.p84_lognormal);

  // A row is the needed gap of the scene under that record alone; the worst is the largest.
  analysis::Scene alone = scene;
  alone.excitation = set[0].excitation;
  const analysis::NeededGap gap = analysis::needed_gap(alone);
  BOOST_TEST(one.records[0].needed_gap_m == gap.needed_gap_m);
  BOOST_TEST(one.records[0].rules.srss_m == gap.rules.srss_m);
  BOOST_TEST(one.records[0].pga_g == 0.32, tt::tolerance(1e-12));  // the scene's scaling
  std::vector<double> gaps;
  for (const analysis::RecordGap& r : one.records) {
    if (r.completed()) gaps.push_back(r.needed_gap_m);
    if (r.completed()) BOOST_TEST(r.needed_gap_m <= one.records[static_cast<std::size_t>(one.worst)].needed_gap_m);
  }
  BOOST_TEST(one.needed_gap_m.mean == analysis::set_statistic(gaps).mean);
}

BOOST_AUTO_TEST_CASE(RunWithRecordOptionsEqualsASceneThatNamesTheRecord) {
  // The paper scene with Newhall given as options, against a scene file that names Newhall: the
  // paper's re-spacing and cut of El Centro must not carry over, its PGA is replaced.
  const std::filesystem::path records = kExamples / "records";
  const std::filesystem::path paper_file = kExamples / "paper" / "paper.toml";
  const analysis::Scene by_options = io::read_scene(
      paper_file,
      {.gap_m = 0.28, .record = {.file = records / "northridge1994_newhall360_peer_RSN1044.AT2", .pga_g = 0.4}});

  std::ifstream in(paper_file);
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const std::size_t from = text.find("[excitation]"), to = text.find("[contact]");
  BOOST_TEST_REQUIRE((from != std::string::npos && to != std::string::npos));
  text.replace(from, to - from,
               "[excitation]\n"
               "file = \"../records/northridge1994_newhall360_peer_RSN1044.AT2\"\n"
               "format = \"peer-at2\"\n"
               "units = \"g\"\n"
               "scale_to_pga_g = 0.4\n\n");
  const analysis::Scene by_file = io::parse_scene(text, paper_file, {.gap_m = 0.28});

  const analysis::RunReport a = analysis::run_scene(by_options);
  const analysis::RunReport b = analysis::run_scene(by_file);
  BOOST_TEST_REQUIRE((a.result.status == solvers::RunStatus::completed));
  BOOST_TEST_REQUIRE(a.result.impacts.size() == b.result.impacts.size());
  BOOST_TEST(a.result.impacts.size() > 0u);
  for (std::size_t i = 0; i < a.result.impacts.size(); ++i) {
    const solvers::ImpactRecord &x = a.result.impacts[i], &y = b.result.impacts[i];
    BOOST_TEST(x.t_s == y.t_s);
    BOOST_TEST(x.impulse_kNs == y.impulse_kNs);
    BOOST_TEST(x.approach_velocity_mps == y.approach_velocity_mps);
    BOOST_TEST(x.level == y.level);
    BOOST_TEST(x.vertex == y.vertex);
  }
}

BOOST_AUTO_TEST_CASE(AnEntrysChoiceAppliedToTheSceneGivesItsExcitation) {
  // A sweep sends a worker the entry's choice (a few values), not its ExcitationSpec: applied to
  // the same scene it must give the very record the list reader built, sample for sample.
  const analysis::Scene scene = io::read_scene(kExamples / "paper" / "el-centro-true-time.toml");
  for (const std::filesystem::path& list : {kExamples / "records" / "set.txt", kExamples / "records"}) {
    const std::vector<analysis::RecordEntry> set = io::read_record_list(list, scene.excitation);
    BOOST_TEST_REQUIRE(set.size() >= 4u);
    for (const analysis::RecordEntry& entry : set) {
      BOOST_TEST_INFO(entry.source);
      BOOST_TEST_REQUIRE(entry.choice.file.has_value());
      BOOST_TEST(entry.choice.file->filename().string() == entry.name);
      const excitation::GroundMotion expected = excitation::load_ground_motion(entry.excitation);
      const excitation::GroundMotion rebuilt =
          excitation::load_ground_motion(excitation::with_record(scene.excitation, entry.choice));
      BOOST_TEST(rebuilt.time_s() == expected.time_s(), tt::per_element());
      BOOST_TEST(rebuilt.accel_mps2() == expected.accel_mps2(), tt::per_element());
      BOOST_TEST(rebuilt.direction_rad() == expected.direction_rad());
    }
  }
}
