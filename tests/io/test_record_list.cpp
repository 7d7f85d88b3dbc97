#include <boost/test/unit_test.hpp>

#include <fmt/format.h>

#include <functional>

#include "../support/fixtures.hpp"
#include "pounding/excitation/record_choice.hpp"
#include "pounding/input_error.hpp"
#include "pounding/io/record_list.hpp"
#include "pounding/io/scene_reader.hpp"

using namespace pounding;
using excitation::RecordFormat;

namespace {

const std::filesystem::path kExamples = POUNDING_EXAMPLES_DIR;
const std::filesystem::path kElCentro = kExamples / "records" / "elcentro1940_ns_0.02s.AT2";

/// The paper scene's excitation: El Centro as peer-at2 in g, re-spaced 0.05 s, cut to 12.2 s,
/// scaled to 0.32 g.
excitation::ExcitationSpec paper_excitation() { return io::read_scene(kExamples / "paper" / "paper.toml").excitation; }

/// Requires that reading `list` fails with an InputError at `file:line` naming `field` and `value`.
void require_list_error(const std::string& list, int line, const std::string& field, const std::string& value) {
  testing::TempDir dir;
  dir.write("a.AT2", "");
  const std::filesystem::path file = dir.write("set.txt", list);
  BOOST_CHECK_EXCEPTION(io::read_record_list(file, paper_excitation()), InputError, [&](const InputError& e) {
    BOOST_TEST_INFO(e.what());
    return e.file() == fmt::format("{}:{}", file.string(), line) && e.key() == field && e.value() == value;
  });
}

}  // namespace

BOOST_AUTO_TEST_CASE(LinesGiveTheirRecordWithTheScenesOptionsWhereTheyAreSilent) {
  testing::TempDir dir;
  dir.write("a.AT2", "");
  std::filesystem::create_directories(dir.path() / "sub folder");
  dir.write("sub folder/b.txt", "");
  const std::filesystem::path file = dir.write("set.txt",
                                               "# a comment\n"
                                               "\n"
                                               "a.AT2   # the scene's format and units\r\n"
                                               "\"sub folder/b.txt\" format=single units=cm/s2 dt_s=0.005 "
                                               "accel_column=2 scale=1.5 direction_deg=30\n"
                                               "a.AT2 pga_g=0.4 dt_s=0.01\n"
                                               "a.AT2 scale_to_pga_g=0.4 dt_s=0.01");  // no final newline
  const std::vector<analysis::RecordEntry> set = io::read_record_list(file, paper_excitation());
  BOOST_TEST_REQUIRE(set.size() == 4u);
  BOOST_TEST((set[3].choice.pga_g == set[2].choice.pga_g));  // scale_to_pga_g is pga_g's own name
  BOOST_TEST(*set[3].choice.pga_g == 0.4);

  const excitation::ExcitationSpec& a = set[0].excitation;
  BOOST_TEST(set[0].name == "a.AT2");
  BOOST_TEST(set[0].source == file.string() + ":3");
  BOOST_TEST((a.file == dir.path() / "a.AT2"));
  BOOST_TEST((a.read.format == RecordFormat::peer_at2 && a.units == excitation::AccelUnits::g));
  // The paper's re-spacing and cut belong to its El Centro file, not to another record.
  BOOST_TEST(!a.dt_override_s.has_value());
  BOOST_TEST(!a.duration_s.has_value());
  BOOST_TEST(a.scale_to_pga_g.value() == 0.32);

  const excitation::ExcitationSpec& b = set[1].excitation;
  BOOST_TEST(set[1].source == file.string() + ":4");
  BOOST_TEST((b.file == dir.path() / "sub folder" / "b.txt"));
  BOOST_TEST((b.read.format == RecordFormat::single && b.units == excitation::AccelUnits::cm_per_s2));
  BOOST_TEST(b.read.dt_s.value() == 0.005);  // `single`: the spacing itself
  BOOST_TEST(b.read.accel_column.value() == 2);
  BOOST_TEST(b.scale_factor == 1.5);
  BOOST_TEST(!b.scale_to_pga_g.has_value());  // a scale replaces the scene's PGA
  BOOST_TEST(b.direction_deg == 30.0);

  const excitation::ExcitationSpec& c = set[2].excitation;
  BOOST_TEST(c.dt_override_s.value() == 0.01);  // peer-at2: a re-spacing
  BOOST_TEST(c.scale_to_pga_g.value() == 0.4);
  BOOST_TEST(c.scale_factor == 1.0);
}

BOOST_AUTO_TEST_CASE(ErrorsNameTheListFileTheLineAndTheField) {
  require_list_error("a.AT2\n\n# fine so far\na.AT2 pga_g=abc\n", 4, "pga_g", "abc");
  require_list_error("a.AT2 colour=red\n", 1, "colour", "red");
  require_list_error("a.AT2 format=csv\n", 1, "format", "csv");
  require_list_error("a.AT2 units=furlong/s2\n", 1, "units", "furlong/s2");
  require_list_error("a.AT2 pga_g=0.3 scale=2\n", 1, "scale", "2");
  require_list_error("a.AT2 pga_g=0.3 pga_g=0.2\n", 1, "pga_g", "0.2");
  // The scene's names of the scaling keys (scale_factor, scale_to_pga_g, scale_to_sa) are the
  // fields' names, the short ones aliases: an error names the field as the line spelled it.
  require_list_error("a.AT2 scale_to_pga_g=0.3 scale_factor=2\n", 1, "scale_factor", "2");
  require_list_error("a.AT2 pga_g=0.3 scale_to_pga_g=0.2\n", 1, "scale_to_pga_g", "0.2");
  require_list_error("a.AT2 scale_to_pga_g=-1\n", 1, "scale_to_pga_g", "-1");
  require_list_error("a.AT2 scale_to_sa=0.5@T1\n", 1, "scale_to_sa", "0.5@T1");
  require_list_error("a.AT2 dt_s=2\n", 1, "dt_s", "2");
  require_list_error("a.AT2 direction_deg=400\n", 1, "direction_deg", "400");
  require_list_error("a.AT2 accel_column=1.5\n", 1, "accel_column", "1.5");
  require_list_error("a.AT2 accel_column=0\n", 1, "accel_column", "0");
  require_list_error("a.AT2 pga_g\n", 1, "", "pga_g");
  require_list_error("\"a.AT2 pga_g=1\n", 1, "file", "\"a.AT2 pga_g=1");
}

BOOST_AUTO_TEST_CASE(TheMissingFileValueIsTheResolvedPath) {
  testing::TempDir dir;
  const std::filesystem::path file = dir.write("set.txt", "# first a comment\ngone.AT2\n");
  BOOST_CHECK_EXCEPTION(io::read_record_list(file, paper_excitation()), InputError, [&](const InputError& e) {
    return e.file() == file.string() + ":2" && e.key() == "file" && e.value() == (dir.path() / "gone.AT2").string();
  });
}

BOOST_AUTO_TEST_CASE(AnEmptyListOrAMissingOneIsRefusedNamingTheOption) {
  testing::TempDir dir;
  const std::filesystem::path empty = dir.write("set.txt", "# nothing yet\n\n");
  auto names_option = [](const InputError& e) { return e.key() == "--records"; };
  BOOST_CHECK_EXCEPTION(io::read_record_list(empty, paper_excitation()), InputError, names_option);
  BOOST_CHECK_EXCEPTION(io::read_record_list(dir.path() / "none.txt", paper_excitation()), InputError, names_option);
  BOOST_CHECK_EXCEPTION(io::read_record_list(dir.path(), paper_excitation()), InputError, names_option);  // no .AT2
}

BOOST_AUTO_TEST_CASE(AFolderGivesItsAt2FilesSortedAsPeerRecordsInG) {
  testing::TempDir dir;
  for (const char* name : {"b.at2", "a.AT2", "c.txt", "d.AT2"}) dir.write(name, "");
  std::filesystem::create_directories(dir.path() / "e.AT2");  // a folder, not a record
  excitation::ExcitationSpec scene = paper_excitation();
  scene.read.format = RecordFormat::single;  // the scene's own record is of another kind
  scene.read.dt_s = 0.01;
  scene.units = excitation::AccelUnits::cm_per_s2;
  const std::vector<analysis::RecordEntry> set = io::read_record_list(dir.path(), scene);
  BOOST_TEST_REQUIRE(set.size() == 3u);
  BOOST_TEST(set[0].name == "a.AT2");
  BOOST_TEST(set[1].name == "b.at2");
  BOOST_TEST(set[2].name == "d.AT2");
  for (const analysis::RecordEntry& e : set) {
    BOOST_TEST((e.excitation.read.format == RecordFormat::peer_at2 && e.excitation.units == excitation::AccelUnits::g));
    BOOST_TEST(!e.excitation.read.dt_s.has_value());
  }
}

BOOST_AUTO_TEST_CASE(CommandLineRecordOptionsAreValidatedNamingTheOption) {
  const std::filesystem::path scene = kExamples / "paper" / "paper.toml";
  auto refused = [&](const excitation::RecordChoice& choice, const std::string& option, const std::string& value) {
    BOOST_CHECK_EXCEPTION(io::read_scene(scene, {.record = choice}), InputError, [&](const InputError& e) {
      BOOST_TEST_INFO(e.what());
      return e.key() == option && e.value() == value;
    });
  };
  refused({.file = "no-such-record.AT2"}, "--record", "no-such-record.AT2");
  refused({.format = "csv"}, "--record-format", "csv");
  refused({.units = "furlongs"}, "--units", "furlongs");
  refused({.pga_g = -1.0}, "--pga-g", "-1");
  refused({.scale_factor = 0.0}, "--scale", "0");
  refused({.scale_factor = 2.0, .pga_g = 0.3}, "--scale", "2");
  refused({.scale_factor = 100.0}, "--scale", "100");  // 31.9 g: found by reading the record now
  refused({.direction_deg = 361.0}, "--direction-deg", "361");
  refused({.file = kElCentro, .dt_s = 0.0}, "--record-dt", "0");
}

BOOST_AUTO_TEST_CASE(ARecordOptionKeepsTheRestOfTheScenesExcitation) {
  const std::filesystem::path scene = kExamples / "paper" / "paper.toml";
  const analysis::Scene paper = io::read_scene(scene);
  const analysis::Scene turned = io::read_scene(scene, {.record = {.direction_deg = 20.0}});
  BOOST_TEST(turned.excitation.direction_deg == 20.0);
  BOOST_TEST((turned.excitation.dt_override_s == paper.excitation.dt_override_s));  // same file: its options stay
  BOOST_TEST((turned.excitation.duration_s == paper.excitation.duration_s));
  const analysis::Scene scaled = io::read_scene(scene, {.record = {.scale_factor = 2.0}});
  BOOST_TEST(!scaled.excitation.scale_to_pga_g.has_value());
  BOOST_TEST(scaled.excitation.scale_factor == 2.0);
}

BOOST_AUTO_TEST_CASE(ALineMayNameAPairAndASpectralScaling) {
  testing::TempDir dir;
  dir.write("k.txt", "");
  const std::filesystem::path file =
      dir.write("pairs.txt",
                "k.txt format=single units=cm/s2 dt_s=0.005 accel_column=1 record2=k.txt record2_column=2 sa=0.5g@B1\n"
                "k.txt format=single units=cm/s2 dt_s=0.005 accel_column=1 sa=0.4g@1.2s\n");
  const std::vector<analysis::RecordEntry> set = io::read_record_list(file, paper_excitation());
  BOOST_TEST_REQUIRE(set.size() == 2u);
  BOOST_TEST(set[0].name == "k.txt+k.txt");
  const excitation::ExcitationSpec& pair = set[0].excitation;
  BOOST_TEST_REQUIRE(pair.second.has_value());
  BOOST_TEST((pair.second->file == dir.path() / "k.txt"));
  BOOST_TEST(pair.second->read.accel_column.value() == 2);
  BOOST_TEST(pair.second->read.dt_s.value() == 0.005);  // format single: H1's spacing
  BOOST_TEST(pair.scale_to_sa->building == 1);
  BOOST_TEST(!pair.scale_to_pga_g.has_value());  // a spectral scaling replaces the scene's PGA
  BOOST_TEST(set[1].name == "k.txt");
  BOOST_TEST(!set[1].excitation.second.has_value());
  BOOST_TEST(*set[1].excitation.scale_to_sa->period_s == 1.2);
  // A second component that is not there: named by its field and resolved path.
  const std::filesystem::path missing = dir.write("missing.txt", "k.txt record2=none.txt\n");
  BOOST_CHECK_EXCEPTION(io::read_record_list(missing, paper_excitation()), InputError, [&](const InputError& e) {
    BOOST_TEST_INFO(e.what());
    return e.key() == "record2" && e.value() == (dir.path() / "none.txt").string();
  });
  require_list_error("a.AT2 record2_column=2\n", 1, "record2_column", "2");
  require_list_error("a.AT2 sa=0.5@T1\n", 1, "sa", "0.5@T1");
}
