#include <boost/test/unit_test.hpp>

#include <string>

#include "../support/fixtures.hpp"
#include "pounding/analysis/limit_states.hpp"
#include "pounding/analysis/modal_summary.hpp"
#include "pounding/input_error.hpp"
#include "pounding/io/scene_reader.hpp"

namespace tt = boost::test_tools;
using pounding::InputError;
using pounding::io::read_scene;
using pounding::testing::TempDir;

namespace {

// A small valid scene: 2- and 3-storey buildings 0.1 m apart, a 4-sample record beside it.
const std::string kScene = R"(name = "small"
[[building]]
name = "A"
storeys = 2
storey_height_m = 3.0
slab = [[-10.0, 0.0], [0.0, 0.0], [0.0, 8.0], [-10.0, 8.0]]
centre_of_mass = [-5.0, 4.0]
mass_t = 100.0
polar_moment_tm2 = "uniform"
E_kPa = 3.0e7
frame_factor = 1.0
columns = [[-10.0, 0.0, 0.4, 0.4], [0.0, 0.0, 0.4, 0.4], [0.0, 8.0, 0.4, 0.4], [-10.0, 8.0, 0.4, 0.4]]

[[building]]
name = "B"
storeys = 3
storey_height_m = 3.0
slab = [[0.1, 2.0], [10.1, 2.0], [10.1, 10.0], [0.1, 10.0]]
centre_of_mass = [5.1, 6.0]
mass_t = [120.0, 120.0, 110.0]
polar_moment_tm2 = [1600.0, 1600.0, 1500.0]
storey_stiffness = [[50000.0, 0.0, 0.0], [0.0, 60000.0, 0.0], [0.0, 0.0, 2.0e6]]
[building.damping]
ratio = 0.02
modes = [1, 2]

[excitation]
file = "record.txt"
format = "columns"
units = "m/s2"

[contact]
gap_m = 0.1
restitution = 0.5
)";

const std::string kRecord = "0 0\n0.01 1\n0.02 -1\n0.03 0\n";

/// The base scene with `from` replaced by `to` (which must occur exactly once).
std::string edited(const std::string& from, const std::string& to) {
  const auto at = kScene.find(from);
  BOOST_REQUIRE_MESSAGE(at != std::string::npos && kScene.find(from, at + 1) == std::string::npos,
                        "edit anchor not unique: " << from);
  return std::string(kScene).replace(at, from.size(), to);
}

struct Case {
  TempDir dir;
  std::filesystem::path file;
  explicit Case(const std::string& scene) {
    dir.write("record.txt", kRecord);
    file = dir.write("scene.toml", scene);
  }
};

/// Reads the scene and returns the error; fails the test if the scene was accepted.
std::string error_of(const std::string& scene, const pounding::io::SceneOverrides& overrides = {}) {
  Case c(scene);
  try {
    read_scene(c.file, overrides);
  } catch (const InputError& error) {
    return error.what();
  }
  BOOST_FAIL("scene accepted");
  return {};
}

bool mentions(const std::string& text, std::initializer_list<std::string> parts) {
  for (const auto& part : parts) {
    if (text.find(part) == std::string::npos) {
      BOOST_TEST_MESSAGE("'" << part << "' missing from: " << text);
      return false;
    }
  }
  return true;
}

}  // namespace

BOOST_AUTO_TEST_CASE(ValidSceneIsReadCompletely) {
  Case c(kScene);
  const auto scene = read_scene(c.file);
  BOOST_TEST(scene.name == "small");
  BOOST_TEST(scene.buildings[0].mass_t == std::vector<double>({100.0, 100.0}), tt::per_element());
  BOOST_TEST(scene.buildings[0].polar_moment_tm2[0] == 100.0 * (100 + 64) / 12.0, tt::tolerance(1e-12));
  BOOST_TEST(scene.buildings[1].storey_stiffness.size() == 3u);  // one matrix for every storey
  BOOST_TEST(scene.buildings[1].damping.modes[1] == 2);
  BOOST_TEST(scene.excitation.file == c.dir.path() / "record.txt");  // relative to the scene
  BOOST_TEST(scene.levels().size() == 2u);
  BOOST_TEST(!scene.solver.rtol.has_value());  // not given: the method's default is used
  BOOST_TEST(pounding::analysis::resolve(scene.solver).rtol == 1e-8);
}

BOOST_AUTO_TEST_CASE(GapOverrideMovesBuildingTwoAlongX) {
  Case c(kScene);
  const auto scene = read_scene(c.file, {.gap_m = 0.35});
  BOOST_TEST(scene.contact.gap_m == 0.35);
  BOOST_TEST(scene.buildings[1].slab.vertex(0).x() == 0.35, tt::tolerance(1e-12));
  BOOST_TEST(scene.buildings[1].centre_of_mass.x() == 5.35, tt::tolerance(1e-12));
  BOOST_TEST(scene.buildings[0].slab.vertex(1).x() == 0.0);  // building 1 stays
}

BOOST_AUTO_TEST_CASE(SyntaxErrorNamesFileAndLine) {
  BOOST_TEST(mentions(error_of(edited("storeys = 2", "storeys = = 2")), {"scene.toml:4"}));
}

BOOST_AUTO_TEST_CASE(UnknownKeyIsRefused) {
  BOOST_TEST(mentions(error_of(edited("frame_factor = 1.0", "frame_factor = 1.0\nframe_facter = 2")),
                      {"scene.toml", "building[1].frame_facter", "2", "unknown key"}));
  BOOST_TEST(mentions(error_of(kScene + "\n[solvr]\nrtol = 1\n"), {"solvr", "unknown key"}));
}

BOOST_AUTO_TEST_CASE(ATypoNamesTheKeyItProbablyMeant) {
  // A required key typed wrong is reported as missing, naming the typo; an optional one as
  // unknown, naming the known key.
  BOOST_TEST(mentions(error_of(edited("restitution = 0.5", "restitutoin = 0.5")),
                      {"contact.restitution", "missing", "\"restitutoin\" a typo"}));
  BOOST_TEST(mentions(error_of(edited("frame_factor = 1.0", "frame_factor = 1.0\nframe_facter = 2")),
                      {"building[1].frame_facter", "unknown key", "did you mean \"frame_factor\""}));
  const std::string far_off = error_of(edited("frame_factor = 1.0", "frame_factor = 1.0\nbanana = 2"));
  BOOST_TEST(mentions(far_off, {"building[1].banana", "unknown key"}));
  BOOST_TEST(far_off.find("did you mean") == std::string::npos);
}

BOOST_AUTO_TEST_CASE(MissingKeyIsRefused) {
  BOOST_TEST(mentions(error_of(edited("storey_height_m = 3.0\nslab = [[-10", "slab = [[-10")),
                      {"scene.toml", "building[1].storey_height_m", "missing", "required"}));
}

BOOST_AUTO_TEST_CASE(WrongTypeIsRefused) {
  BOOST_TEST(mentions(error_of(edited("storeys = 2", "storeys = \"two\"")),
                      {"scene.toml:4", "building[1].storeys", "two", "whole number"}));
  BOOST_TEST(mentions(error_of(edited("gap_m = 0.1", "gap_m = [0.1]")), {"contact.gap_m", "expected a number"}));
}

BOOST_AUTO_TEST_CASE(NonPositiveMassIsRefused) {
  BOOST_TEST(mentions(error_of(edited("mass_t = 100.0", "mass_t = -100.0")),
                      {"scene.toml", "building[1].mass_t", "-100", "positive"}));
  BOOST_TEST(mentions(error_of(edited("[120.0, 120.0, 110.0]", "[120.0, 0.0, 110.0]")),
                      {"scene.toml", "building[2].mass_t[2]", "0", "[1, 10000000000] t"}));
}

BOOST_AUTO_TEST_CASE(NonPositiveInertiaIsRefused) {
  BOOST_TEST(mentions(error_of(edited("[1600.0, 1600.0, 1500.0]", "[1600.0, 1600.0, -1500.0]")),
                      {"building[2].polar_moment_tm2[3]", "-1500", "[0.1, 100000000000000]"}));
}

BOOST_AUTO_TEST_CASE(NonPositiveHeightAndModulusAreRefused) {
  BOOST_TEST(mentions(error_of(edited("storeys = 2\nstorey_height_m = 3.0", "storeys = 2\nstorey_height_m = 0.0")),
                      {"building[1].storey_height_m", "0", "[1, 20] m"}));
  BOOST_TEST(mentions(error_of(edited("E_kPa = 3.0e7", "E_kPa = -3.0e7")),
                      {"building[1].E_kPa", "-30000000", "[1000000, 1000000000] kPa"}));
}

BOOST_AUTO_TEST_CASE(StoreyHeightsAreOneNumberOrOneAStorey) {
  Case scalar(kScene), list(edited("storeys = 2\nstorey_height_m = 3.0", "storeys = 2\nstorey_height_m = [3.0, 3.0]"));
  const auto a = read_scene(scalar.file), b = read_scene(list.file);
  BOOST_TEST(a.buildings[0].storey_height_m == std::vector<double>({3.0, 3.0}), tt::per_element());
  BOOST_TEST(b.buildings[0].storey_height_m == a.buildings[0].storey_height_m, tt::per_element());
  const Eigen::MatrixXd difference = pounding::model::make_building(a.buildings[0]).stiffness -
                                     pounding::model::make_building(b.buildings[0]).stiffness;
  BOOST_TEST(difference.cwiseAbs().maxCoeff() == 0.0);

  Case taller(edited("storeys = 3\nstorey_height_m = 3.0", "storeys = 3\nstorey_height_m = [3.0, 3.0, 4.5]"));
  BOOST_TEST(read_scene(taller.file).buildings[1].storey_height_m == std::vector<double>({3.0, 3.0, 4.5}),
             tt::per_element());
}

BOOST_AUTO_TEST_CASE(BadStoreyHeightListsAreRefusedEntryByEntry) {
  const std::string anchor = "storeys = 3\nstorey_height_m = 3.0";
  BOOST_TEST(mentions(error_of(edited(anchor, "storeys = 3\nstorey_height_m = [3.0, 3.0, -4.5]")),
                      {"scene.toml", "building[2].storey_height_m[3] = -4.5", "[1, 20] m"}));
  BOOST_TEST(mentions(error_of(edited(anchor, "storeys = 3\nstorey_height_m = [3.0, 25.0, 3.0]")),
                      {"scene.toml", "building[2].storey_height_m[2] = 25", "[1, 20] m"}));
  BOOST_TEST(mentions(error_of(edited(anchor, "storeys = 3\nstorey_height_m = [3.0, 3.0]")),
                      {"building[2].storey_height_m", "2 values", "one value per storey (3)"}));
  BOOST_TEST(mentions(error_of(edited(anchor, "storeys = 3\nstorey_height_m = [3.0, inf, 3.0]")),
                      {"building[2].storey_height_m[2] = inf", "[1, 20] m"}));
  // A single value is refused under the key typed (no index the user never wrote), with its line.
  BOOST_TEST(mentions(error_of(edited(anchor, "storeys = 3\nstorey_height_m = inf")),
                      {"scene.toml:", "building[2].storey_height_m = inf", "[1, 20] m"}));
  BOOST_TEST(mentions(error_of(edited(anchor, "storeys = 3\nstorey_height_m = 0.5")),
                      {"building[2].storey_height_m = 0.5", "[1, 20] m"}));
  BOOST_TEST(mentions(error_of(edited(anchor, "storeys = 3\nstorey_height_m = [3.0, \"x\", 3.0]")),
                      {"building[2].storey_height_m[2]", "expected a number"}));
}

BOOST_AUTO_TEST_CASE(RestitutionOutsideUnitIntervalIsRefused) {
  BOOST_TEST(mentions(error_of(edited("restitution = 0.5", "restitution = 1.5")),
                      {"scene.toml", "contact.restitution", "1.5", "[0, 1]"}));
  BOOST_TEST(mentions(error_of(edited("restitution = 0.5", "restitution = -0.1")), {"contact.restitution", "-0.1"}));
  BOOST_TEST(mentions(error_of(kScene, {.contact = {{"--restitution", 2.0}}}), {"--restitution", "2", "[0, 1]"}));
}

BOOST_AUTO_TEST_CASE(NegativeGapIsRefused) {
  BOOST_TEST(mentions(error_of(kScene, {.gap_m = -0.05}), {"scene.toml", "--gap", "-0.05", "[0, 10] m"}));
}

BOOST_AUTO_TEST_CASE(GapDisagreeingWithTheOutlinesIsRefused) {
  BOOST_TEST(mentions(error_of(edited("gap_m = 0.1", "gap_m = 0.2")),
                      {"contact.gap_m", "0.2", "clear distance along x is 0.1"}));
}

BOOST_AUTO_TEST_CASE(PolygonThatIsNotSimpleIsRefused) {
  BOOST_TEST(mentions(error_of(edited("[[-10.0, 0.0], [0.0, 0.0], [0.0, 8.0], [-10.0, 8.0]]",
                                      "[[-10.0, 0.0], [0.0, 8.0], [0.0, 0.0], [-10.0, 8.0]]")),
                      {"building[1].slab", "not simple"}));
}

BOOST_AUTO_TEST_CASE(ClockwisePolygonIsRefused) {
  BOOST_TEST(mentions(error_of(edited("[[-10.0, 0.0], [0.0, 0.0], [0.0, 8.0], [-10.0, 8.0]]",
                                      "[[-10.0, 0.0], [-10.0, 8.0], [0.0, 8.0], [0.0, 0.0]]")),
                      {"building[1].slab", "counter-clockwise"}));
}

BOOST_AUTO_TEST_CASE(CentreOfMassOutsideTheSlabIsRefused) {
  BOOST_TEST(mentions(error_of(edited("centre_of_mass = [-5.0, 4.0]", "centre_of_mass = [-5.0, 9.0]")),
                      {"building[1].centre_of_mass", "[-5, 9]", "outside the slab"}));
}

BOOST_AUTO_TEST_CASE(SlabsOverlappingAtRestAreRefused) {
  const std::string overlapping = edited("[[0.1, 2.0], [10.1, 2.0], [10.1, 10.0], [0.1, 10.0]]",
                                         "[[-0.1, 2.0], [10.1, 2.0], [10.1, 10.0], [-0.1, 10.0]]");
  BOOST_TEST(mentions(error_of(overlapping), {"scene.toml", "building[2].slab", "overlaps"}));
}

BOOST_AUTO_TEST_CASE(StiffnessThatIsNotPositiveDefiniteIsRefused) {
  BOOST_TEST(mentions(error_of(edited("[0.0, 0.0, 2.0e6]]", "[0.0, 0.0, -2.0e6]]")),
                      {"scene.toml", "building[2].storey_stiffness[1]", "positive definite"}));
  BOOST_TEST(mentions(error_of(edited("[50000.0, 0.0, 0.0], [0.0, 60000.0", "[50000.0, 1.0, 0.0], [0.0, 60000.0")),
                      {"building[2].storey_stiffness[1]", "symmetric"}));
}

BOOST_AUTO_TEST_CASE(MissingRecordIsRefused) {
  BOOST_TEST(mentions(error_of(edited("file = \"record.txt\"", "file = \"nowhere.txt\"")),
                      {"scene.toml", "excitation.file", "nowhere.txt", "no such record file"}));
}

BOOST_AUTO_TEST_CASE(UnknownFormatAndUnitsAreRefused) {
  BOOST_TEST(
      mentions(error_of(edited("format = \"columns\"", "format = \"csv\"")), {"excitation.format", "csv", "peer-at2"}));
  BOOST_TEST(mentions(error_of(edited("units = \"m/s2\"", "units = \"gal\"")), {"excitation.units", "gal"}));
}

BOOST_AUTO_TEST_CASE(DampingModesOutOfRangeAreRefused) {
  BOOST_TEST(mentions(error_of(edited("modes = [1, 2]", "modes = [1, 12]")),
                      {"building[2].damping.modes", "[1, 12]", "1..9"}));
}

BOOST_AUTO_TEST_CASE(ExclusiveStiffnessKeysAreRefusedTogether) {
  BOOST_TEST(mentions(error_of(edited("frame_factor = 1.0", "frame_factor = 1.0\ntarget_period_s = 0.2")),
                      {"building[1].target_period_s", "not both"}));
  BOOST_TEST(mentions(error_of(edited("storey_stiffness =", "E_kPa = 1.0\nstorey_stiffness =")),
                      {"building[2].storey_stiffness", "not both"}));
}

BOOST_AUTO_TEST_CASE(PaperSceneHasThePublishedPeriods) {
  const auto scene = read_scene(POUNDING_EXAMPLES_DIR "/paper/paper.toml");
  const auto buildings = pounding::analysis::summarise_buildings(scene);
  BOOST_TEST(buildings[0].modes[0].period_s == 0.765, tt::tolerance(1e-3));
  BOOST_TEST(buildings[1].modes[0].period_s == 1.119, tt::tolerance(1e-3));
  BOOST_TEST(buildings[0].dof == 21);
  BOOST_TEST(buildings[1].dof == 30);
}

BOOST_AUTO_TEST_CASE(TargetPeriodSceneSolvesThePublishedFrameFactors) {
  const auto scene = read_scene(POUNDING_EXAMPLES_DIR "/paper/paper-target-periods.toml");
  const auto buildings = pounding::analysis::summarise_buildings(scene);
  BOOST_TEST(std::abs(buildings[0].frame_factor - 0.74625) < 1e-5);
  BOOST_TEST(std::abs(buildings[1].frame_factor - 0.57268) < 1e-5);
  BOOST_TEST(buildings[0].modes[0].period_s == 0.765, tt::tolerance(1e-10));
}

BOOST_AUTO_TEST_CASE(SceneWithoutACommonLevelIsRefusedWithTheReason) {
  // B1 floors at 3 and 6 m; B2 on a 4.5 m ground storey then 3 m: floors at 4.5, 7.5, 10.5 m.
  // With slab-to-column contact off nothing could touch.
  const std::string error =
      error_of(edited("storeys = 3\nstorey_height_m = 3.0", "storeys = 3\nstorey_height_m = [4.5, 3.0, 3.0]") +
               "slab_to_column = \"off\"\n");
  BOOST_TEST(mentions(error, {"scene.toml", "building[2].storey_height_m", "[4.5, 3, 3]", "3, 6 m", "4.5, 7.5, 10.5 m",
                              "nothing could touch", "leaves out the slabs that would strike columns"}));
}

BOOST_AUTO_TEST_CASE(SlabsBetweenFloorsNeedACompliantLawAndColumns) {
  // A on 4.5 m storeys (floors 4.5, 9 m) against B's 3 m (3, 6, 9 m): A's floor 1 strikes B's
  // storey-2 columns, B's floors 1 and 2 A's storey-1 and -2 columns, and 9 m is a level.
  const std::string tall = edited("storeys = 2\nstorey_height_m = 3.0", "storeys = 2\nstorey_height_m = 4.5");
  // With columns in B too, the impulse law is refused when a run starts (after the overrides,
  // so that --contact-law can mend the file), not when the file is read.
  std::string columns = tall;
  const std::string matrix = "storey_stiffness = [[50000.0, 0.0, 0.0], [0.0, 60000.0, 0.0], [0.0, 0.0, 2.0e6]]";
  columns.replace(columns.find(matrix), matrix.size(),
                  "E_kPa = 3.0e7\nframe_factor = 1.0\ncolumns = [[0.1, 2.0, 0.4, 0.4], [0.1, 10.0, 0.4, 0.4]]");
  Case impulse(columns);
  try {
    pounding::analysis::require_compliant_law_where_needed(read_scene(impulse.file));
    BOOST_ERROR("the impulse law was not refused");
  } catch (const InputError& error) {
    BOOST_TEST(
        mentions(error.what(), {"scene.toml", "contact.law = \"impulse\"", "cannot resolve slab-to-column contact",
                                "A floor 1 (4.5 m)", "storey 2", "3 such floors", "slab_to_column = \"off\""}));
  }
  pounding::analysis::require_compliant_law_where_needed(read_scene(Case(columns + "law = \"kelvin\"\n").file));
  // B's storeys are matrices: no columns to strike.
  BOOST_TEST(mentions(error_of(tall + "law = \"kelvin\"\n"),
                      {"building[2].storey_stiffness[2]", "is a matrix", "A floor 1 (4.5 m)", "B's storey 2"}));
  BOOST_TEST(mentions(error_of(tall + "slab_to_column = \"maybe\"\n"),
                      {"contact.slab_to_column = \"maybe\"", "expected \"on\" or \"off\""}));
  // A shear capacity is a positive force, and only columns have one.
  BOOST_TEST(mentions(error_of(edited("frame_factor = 1.0\n", "frame_factor = 1.0\ncolumn_shear_capacity_kN = -5.0\n")),
                      {"building[1].column_shear_capacity_kN = -5", "kN"}));
  BOOST_TEST(mentions(error_of(edited("storey_stiffness = ", "column_shear_capacity_kN = 500.0\nstorey_stiffness = ")),
                      {"storey_stiffness", "column_shear_capacity_kN", "not both"}));
  // Left out, the scene is read and keeps its one level.
  Case off(tall + "slab_to_column = \"off\"\n");
  const pounding::analysis::Scene scene = read_scene(off.file);
  BOOST_TEST(scene.levels().size() == 1u);
  BOOST_TEST(scene.column_levels().empty());
}

BOOST_AUTO_TEST_CASE(LevelsFollowStoreyHeightsAndTheTolerance) {
  // B2's storeys 3, 3.0005, 2.9995 m: floors at 3, 6.0005, 9.0000 m. At the default 1 mm both
  // of B1's floors (3, 6 m) find a level; at 0.1 mm only floor 1 does.
  const std::string heights = "storeys = 3\nstorey_height_m = [3.0, 3.0005, 2.9995]";
  Case loose(edited("storeys = 3\nstorey_height_m = 3.0", heights));
  const auto levels = read_scene(loose.file).levels();
  BOOST_TEST_REQUIRE(levels.size() == 2u);
  BOOST_TEST((levels[1].floors == std::array<int, 2>{2, 2}));
  // At 0.1 mm B's 6.0005 m floor stands between A's: slab-to-column contact, left out here.
  Case tight(edited("storeys = 3\nstorey_height_m = 3.0", heights) +
             "level_tolerance_m = 1e-4\nslab_to_column = \"off\"\n");
  BOOST_TEST(read_scene(tight.file).levels().size() == 1u);
}

BOOST_AUTO_TEST_CASE(LevelToleranceMustStayBelowHalfAStorey) {
  BOOST_TEST(mentions(error_of(kScene + "level_tolerance_m = 0.0\n"),
                      {"scene.toml", "contact.level_tolerance_m = 0", "(0, 0.5] m"}));
  BOOST_TEST(mentions(error_of(kScene + "level_tolerance_m = 1.5\n"),
                      {"scene.toml", "contact.level_tolerance_m = 1.5", "(0, 0.5] m"}));
  // Inside its range but not below half of a 1 m storey: a floor could meet two floors.
  const std::string low_storey =
      edited("storeys = 2\nstorey_height_m = 3.0", "storeys = 2\nstorey_height_m = [1.0, 3.0]");
  BOOST_TEST(mentions(
      error_of(low_storey + "level_tolerance_m = 0.5\n"),
      {"contact.level_tolerance_m = 0.5", "half of every storey height", "building[1].storey_height_m[1] is 1 m"}));
}

BOOST_AUTO_TEST_CASE(HistoryFloorsNameLevels) {
  Case ok(kScene + "[output]\nhistory_floors = [2]\n");
  BOOST_TEST(read_scene(ok.file).output.history_floors == std::vector<int>({2}), tt::per_element());
  // Building 2 has a floor 3, but there are only two levels.
  BOOST_TEST(mentions(error_of(kScene + "[output]\nhistory_floors = [3]\n"),
                      {"output.history_floors[1]", "3", "levels", "1..2"}));
}

BOOST_AUTO_TEST_CASE(OutputSelectionDefaultsToEverythingAndRefusesUnknownGroups) {
  Case plain(kScene);
  const pounding::analysis::OutputSettings all = read_scene(plain.file).output;
  BOOST_TEST(all.history);
  BOOST_TEST(all.peaks == std::vector<std::string>({"displacements", "accelerations", "drifts"}), tt::per_element());
  const pounding::solvers::OutputSelection every = all.selection();
  BOOST_TEST((every.history && every.displacement_peaks && every.acceleration_peaks && every.drift_peaks));
  Case some(kScene + "[output]\nhistory = false\npeaks = [\"drifts\"]\n");
  const pounding::solvers::OutputSelection drifts = read_scene(some.file).output.selection();
  BOOST_TEST((!drifts.history && !drifts.displacement_peaks && !drifts.acceleration_peaks && drifts.drift_peaks));
  Case none(kScene + "[output]\npeaks = []\n");
  BOOST_TEST(!read_scene(none.file).output.selection().any_peaks());

  BOOST_TEST(mentions(error_of(kScene + "[output]\npeaks = [\"drifts\", \"velocities\"]\n"),
                      {"scene.toml", "output.peaks[2] = \"velocities\"", "displacements, accelerations, drifts"}));
  BOOST_TEST(mentions(error_of(kScene + "[output]\npeaks = [\"drifts\", \"drifts\"]\n"),
                      {"scene.toml", "output.peaks[2] = \"drifts\"", "listed twice"}));
  BOOST_TEST(mentions(error_of(kScene + "[output]\npeaks = \"drifts\"\n"),
                      {"scene.toml", "output.peaks", "expected an array"}));
  BOOST_TEST(mentions(error_of(kScene + "[output]\npeaks = [1]\n"), {"output.peaks[1] = 1", "expected a string"}));
  BOOST_TEST(mentions(error_of(kScene + "[output]\nhistory = \"off\"\n"),
                      {"scene.toml", "output.history = \"off\"", "expected true or false"}));
}

// Issue 15: inputs a hostile or careless user tried. Each is refused naming the key, the value
// and the range it must lie in (docs/scene-format.md).
BOOST_AUTO_TEST_CASE(MalformedUtf8IsRefusedBeforeTomlSeesIt) {
  // toml++ 3.3 reached an unreachable point on some malformed sequences (UBSan).
  BOOST_TEST(mentions(error_of("# caf\xff\n" + kScene), {"scene.toml:1:6", "not valid UTF-8"}));
  BOOST_TEST(mentions(error_of(kScene + "# \xc0\xaf overlong\n"), {"not valid UTF-8"}));
  BOOST_TEST(mentions(error_of(kScene + "# \xed\xa0\x80 surrogate\n"), {"not valid UTF-8"}));
  BOOST_TEST(mentions(error_of(kScene + "# cut \xe2\x82"), {"not valid UTF-8"}));
  Case valid("# café, 東京, 🏢\n" + kScene);
  BOOST_CHECK_NO_THROW(read_scene(valid.file));
}

BOOST_AUTO_TEST_CASE(ValuesInMessagesAreFormattedWithoutTheTomlFormatter) {
  // toml++'s formatter converted log10(0.05) = -1.30103 to unsigned long (UBSan).
  BOOST_TEST(mentions(error_of(edited("storeys = 2", "storeys = 0.05")),
                      {"building[1].storeys = 0.05", "expected a whole number"}));
  BOOST_TEST(mentions(error_of(edited("name = \"A\"", "name = [0.05, 1e-300, \"x\"]")),
                      {"building[1].name = [0.05, 1e-300, \"x\"]", "expected a string"}));
}

BOOST_AUTO_TEST_CASE(AbsurdBuildingValuesNameTheirRange) {
  BOOST_TEST(mentions(error_of(edited("storeys = 2", "storeys = 1000")), {"building[1].storeys = 1000", "[1, 200]"}));
  BOOST_TEST(mentions(error_of(edited("mass_t = 100.0", "mass_t = 1e-300")),
                      {"building[1].mass_t[1] = 1e-300", "[1, 10000000000] t"}));
  BOOST_TEST(mentions(error_of(edited("E_kPa = 3.0e7", "E_kPa = 1e308")), {"building[1].E_kPa = 1e+308", "kPa"}));
  BOOST_TEST(mentions(error_of(edited("frame_factor = 1.0", "target_period_s = 1e-9")),
                      {"building[1].target_period_s = 1e-09", "[0.02, 20] s"}));
  BOOST_TEST(mentions(error_of(edited("[-10.0, 0.0, 0.4, 0.4], [0.0, 0.0", "[-10.0, 0.0, 0.4, 0.4], [5.0, 0.0")),
                      {"building[1].columns[2] = [5, 0]", "outside its slab"}));
  // A grid's column is named by the grid lines that place it: the x value to change is x[3].
  const std::string grid = "column_grid = [{x = [-10.0, 0.0, 5.0], y = [0.0, 8.0], b_m = 0.4, h_m = 0.4}]";
  BOOST_TEST(mentions(
      error_of(edited(
          "columns = [[-10.0, 0.0, 0.4, 0.4], [0.0, 0.0, 0.4, 0.4], [0.0, 8.0, 0.4, 0.4], [-10.0, 8.0, 0.4, 0.4]]",
          grid)),
      {"building[1].column_grid[1] x[3] y[1] = [5, 0]", "outside its slab"}));
  // A grid line or a column given twice would count its stiffness twice: refused, naming both.
  BOOST_TEST(mentions(
      error_of(edited(
          "columns = [[-10.0, 0.0, 0.4, 0.4], [0.0, 0.0, 0.4, 0.4], [0.0, 8.0, 0.4, 0.4], [-10.0, 8.0, 0.4, 0.4]]",
          "column_grid = [{x = [-10.0, 0.0, 0.0], y = [0.0, 8.0], b_m = 0.4, h_m = 0.4}]")),
      {"building[1].column_grid[1] x[3] y[1] = [0, 0]", "stands where column_grid[1] x[2] y[1] stands"}));
  BOOST_TEST(mentions(error_of(edited("[0.0, 8.0, 0.4, 0.4]", "[0.0, 0.0, 0.5, 0.5]")),
                      {"building[1].columns[3] = [0, 0]", "stands where columns[2] stands", "stiffness twice"}));
  BOOST_TEST(mentions(error_of(edited("centre_of_mass = [-5.0, 4.0]", "centre_of_mass = [-5.0, 0.0]")),
                      {"building[1].centre_of_mass = [-5, 0]", "slab's edge", "0.001 m inside"}));
  BOOST_TEST(mentions(error_of(edited("name = \"small\"", "name = \"\"")), {"name = \"\"", "must not be empty"}));
}

BOOST_AUTO_TEST_CASE(FloorHistoryNamesABuildingAndItsFloors) {
  Case ok(kScene + "[output]\n[output.floor_history]\nB = [3, 1]\n");
  const pounding::analysis::Scene scene = read_scene(ok.file);
  BOOST_TEST(scene.history_other_floors().size() == 2u);
  BOOST_TEST((scene.history_other_floors()[0] == std::array<int, 2>{1, 3}));
  BOOST_TEST(mentions(error_of(kScene + "[output.floor_history]\nC = [1]\n"),
                      {"output.floor_history.C", "names no building", "A and B"}));
  BOOST_TEST(mentions(error_of(kScene + "[output.floor_history]\nA = [3]\n"),
                      {"output.floor_history.A[1] = 3", "floors of A, numbered 1..2"}));
  BOOST_TEST(mentions(error_of(kScene + "[output.floor_history]\nB = [2, 2]\n"),
                      {"output.floor_history.B[2] = 2", "listed twice"}));
  BOOST_TEST(mentions(error_of(kScene + "[output.floor_history]\nB = 2\n"), {"output.floor_history.B"}));
}

BOOST_AUTO_TEST_CASE(BoucWenParametersAreCheckedAndOnlyForTheirLaw) {
  // Building 1 has columns; its hysteresis table goes after them.
  const std::string columns =
      "columns = [[-10.0, 0.0, 0.4, 0.4], [0.0, 0.0, 0.4, 0.4], [0.0, 8.0, 0.4, 0.4], [-10.0, 8.0, 0.4, 0.4]]";
  const auto with_law = [&](const std::string& table) {
    return edited(columns, columns + "\n[building.hysteresis]\nyield_drift_ratio = 0.005\n" + table);
  };
  Case valid(with_law("law = \"bouc-wen\"\nbeta = 0.6\ngamma = -0.2\nn = 3\n"));
  const pounding::model::HystereticLaw law = read_scene(valid.file).buildings[0].hysteresis;
  BOOST_TEST((law.kind == pounding::model::HystereticLaw::Kind::bouc_wen));
  BOOST_TEST(law.bouc_wen_a == 1.0);  // the default
  BOOST_TEST(law.bouc_wen_beta == 0.6);
  BOOST_TEST(law.bouc_wen_gamma == -0.2);
  BOOST_TEST(law.bouc_wen_n == 3.0);
  BOOST_TEST(mentions(error_of(with_law("law = \"bouc-wen\"\ngamma = 0.7\n")),
                      {"building[1].hysteresis.gamma = 0.7", "(-beta, beta] = (-0.5, 0.5]"}));
  BOOST_TEST(mentions(error_of(with_law("law = \"bouc-wen\"\ngamma = -0.5\n")),
                      {"building[1].hysteresis.gamma = -0.5", "grows without bound"}));
  BOOST_TEST(mentions(error_of(with_law("law = \"bouc-wen\"\na = 2\n")),
                      {"building[1].hysteresis.a = 2", "must be 1", "alpha k + (1 - alpha) k A"}));
  BOOST_TEST(
      mentions(error_of(with_law("law = \"bouc-wen\"\nn = 0.5\n")), {"building[1].hysteresis.n = 0.5", "[1, 50]"}));
  BOOST_TEST(mentions(error_of(with_law("law = \"bouc-wen\"\na = 0\n")), {"building[1].hysteresis.a = 0", "(0, 10]"}));
  BOOST_TEST(mentions(error_of(with_law("law = \"bilinear\"\nbeta = 0.3\n")),
                      {"building[1].hysteresis.beta = 0.3", "applies to law = \"bouc-wen\" only"}));
  BOOST_TEST(mentions(error_of(with_law("law = \"plastic\"\n")),
                      {"building[1].hysteresis.law",
                       "\"elastic\", \"bilinear\", \"bouc-wen\", \"imk-peak-oriented\" or \"imk-pinching\""}));
}

BOOST_AUTO_TEST_CASE(AColumnGridMayGiveItsColumnsTheirOwnYieldForce) {
  const std::string columns =
      "columns = [[-10.0, 0.0, 0.4, 0.4], [0.0, 0.0, 0.4, 0.4], [0.0, 8.0, 0.4, 0.4], [-10.0, 8.0, 0.4, 0.4]]";
  const std::string grid = "[[building.column_grid]]\nx = [-10.0, 0.0]\ny = [0.0, 8.0]\nb_m = 0.4\nh_m = 0.4\n";
  const auto with = [&](const std::string& grid_lines, const std::string& law_lines) {
    return edited(columns, grid + grid_lines + "[building.hysteresis]\nlaw = \"bilinear\"\n" + law_lines);
  };
  Case spread(with("yield_force_kN = 150.0\n", ""));  // every column its own: no storey strength needed
  const auto scene = read_scene(spread.file);
  const auto& read = scene.buildings[0];
  BOOST_TEST(read.columns.size() == 4u);
  BOOST_TEST(read.columns[0].yield_force_kN == std::vector<double>({150.0, 150.0}));
  BOOST_TEST(mentions(error_of(with("yield_force_kN = [150.0]\n", "")),
                      {"building[1].column_grid[1].yield_force_kN", "needs one value per storey (2)"}));
  BOOST_TEST(mentions(error_of(with("yield_force_kN = [150.0, -1.0]\n", "")),
                      {"building[1].column_grid[1].yield_force_kN[2] = -1"}));
  BOOST_TEST(mentions(error_of(edited(columns, grid + "yield_force_kN = 150.0\n")),
                      {"building[1].column_grid[1].yield_force_kN", "needs yielding columns"}));
}

BOOST_AUTO_TEST_CASE(ImkParametersHaveOpenSeesNamesAndAreChecked) {
  const auto with_law = [](const std::string& lines) {
    const std::string columns =
        "columns = [[-10.0, 0.0, 0.4, 0.4], [0.0, 0.0, 0.4, 0.4], [0.0, 8.0, 0.4, 0.4], [-10.0, 8.0, 0.4, 0.4]]";
    return edited(columns, columns +
                               "\n[building.hysteresis]\nlaw = \"imk-peak-oriented\"\n"
                               "yield_drift_ratio = 0.005\n" +
                               lines);
  };
  const std::string required = "Up_pos = 0.05\nUpc_pos = [0.2, 0.15]\nFmaxFy_pos = 1.2\n";
  Case given(with_law(required + "Lamda_S = 2.5\nc_K = 1.5\nUp_neg = 0.04\nD_neg = 0.8\n"));
  const pounding::model::HystereticLaw law = read_scene(given.file).buildings[0].hysteresis;
  BOOST_TEST((law.kind == pounding::model::HystereticLaw::Kind::imk_peak_oriented));
  BOOST_TEST(law.imk_up_pos_m == std::vector<double>({0.05, 0.05}));  // one number: every storey
  BOOST_TEST(law.imk_upc_pos_m == std::vector<double>({0.2, 0.15}));
  BOOST_TEST(law.imk_up_neg_m == std::vector<double>({0.04, 0.04}));
  BOOST_TEST(law.imk_upc_neg_m.empty());  // the positive side's
  BOOST_TEST(*law.imk_fmax_fy_pos == 1.2);
  BOOST_TEST(!law.imk_fmax_fy_neg);
  BOOST_TEST(law.imk_fres_fy_pos == 0.0);
  BOOST_TEST(law.imk_lamda_s_m == 2.5);
  BOOST_TEST(law.imk_lamda_k_m == 0.0);  // off
  BOOST_TEST(law.imk_c_k == 1.5);
  BOOST_TEST(law.imk_d_neg == 0.8);
  BOOST_TEST(mentions(error_of(with_law("Upc_pos = 0.2\nFmaxFy_pos = 1.2\n")),
                      {"building[1].hysteresis.Up_pos", "missing", "imk-peak-oriented"}));
  BOOST_TEST(mentions(error_of(with_law(required + "hardening_ratio = 0.05\n")),
                      {"building[1].hysteresis.hardening_ratio", "applies to law = \"bilinear\" or \"bouc-wen\""}));
  BOOST_TEST(mentions(error_of(with_law(required + "FresFy_pos = 1.5\n")),
                      {"building[1].hysteresis.FresFy_pos = 1.5", "[0, 1]"}));
  BOOST_TEST(mentions(error_of(with_law(required + "Lamda_A = -1\n")), {"building[1].hysteresis.Lamda_A = -1"}));
  BOOST_TEST(mentions(error_of(with_law(required + "kappaF = 0.5\n")),
                      {"building[1].hysteresis.kappaF", "applies to law = \"imk-pinching\" only"}));
  // imk-pinching: the same keys and its two of its own, required.
  const auto pinching = [&](const std::string& lines) {
    std::string scene = with_law(required + lines);
    const std::string law = "law = \"imk-peak-oriented\"";
    scene.replace(scene.find(law), law.size(), "law = \"imk-pinching\"");
    return scene;
  };
  Case pinched(pinching("kappaF = 0.4\nkappaD = 0.6\n"));
  const pounding::model::HystereticLaw pinched_law = read_scene(pinched.file).buildings[0].hysteresis;
  BOOST_TEST((pinched_law.kind == pounding::model::HystereticLaw::Kind::imk_pinching));
  BOOST_TEST(*pinched_law.imk_kappa_f == 0.4);
  BOOST_TEST(*pinched_law.imk_kappa_d == 0.6);
  BOOST_TEST(mentions(error_of(pinching("kappaF = 0.4\n")),
                      {"building[1].hysteresis.kappaD", "missing", "law \"imk-pinching\" needs it"}));
  BOOST_TEST(mentions(error_of(pinching("kappaF = 1.4\nkappaD = 0.6\n")), {"building[1].hysteresis.kappaF = 1.4"}));
}

BOOST_AUTO_TEST_CASE(AStrengthIsOneNumberForEveryStoreyOrOneAStorey) {
  // Building 1 has two storeys of 3 m and four 0.4 m columns: k = 12 E (0.4⁴/12)/3³ each.
  const std::string columns =
      "columns = [[-10.0, 0.0, 0.4, 0.4], [0.0, 0.0, 0.4, 0.4], [0.0, 8.0, 0.4, 0.4], [-10.0, 8.0, 0.4, 0.4]]";
  const auto with_strength = [&](const std::string& lines) {
    return edited(columns, columns + "\n[building.hysteresis]\nlaw = \"bilinear\"\n" + lines);
  };
  Case spread(with_strength("yield_drift_ratio = 0.005\n"));
  BOOST_TEST(read_scene(spread.file).buildings[0].hysteresis.yield_drift_ratio == std::vector<double>({0.005, 0.005}));
  Case listed(with_strength("yield_shear_kN = [400.0, 250.0]\n"));
  const auto scene = read_scene(listed.file);
  BOOST_TEST(scene.buildings[0].hysteresis.yield_shear_kN == std::vector<double>({400.0, 250.0}));
  // The storey's yield shear over its columns' stiffness: every column of storey 2 yields at
  // 250 kN / (4 k) along x and along y.
  const pounding::model::Building building = pounding::model::make_building(scene.buildings[0]);
  const double column_k_kN_per_m = 12.0 * 3.0e7 * (0.4 * 0.4 * 0.4 * 0.4 / 12.0) / 27.0;
  BOOST_TEST(pounding::model::column_yield_drift_m(building, 2, 1) == 250.0 / (4.0 * column_k_kN_per_m),
             boost::test_tools::tolerance(1e-14));
  BOOST_TEST(pounding::model::storey_column_stiffness(building, 1, 0) == 4.0 * column_k_kN_per_m,
             boost::test_tools::tolerance(1e-14));

  BOOST_TEST(mentions(error_of(with_strength("yield_drift_m = [0.01, 0.01, 0.01]\n")),
                      {"building[1].hysteresis.yield_drift_m = 3 values", "one value per storey (2)"}));
  BOOST_TEST(mentions(error_of(with_strength("yield_shear_kN = [400.0, -1.0]\n")),
                      {"building[1].hysteresis.yield_shear_kN[2] = -1", "(0, 1000000000] kN"}));
  BOOST_TEST(mentions(error_of(with_strength("yield_shear_kN = 0.0\n")),
                      {"building[1].hysteresis.yield_shear_kN = 0", "(0, 1000000000] kN"}));
  BOOST_TEST(mentions(error_of(with_strength("yield_drift_m = [0.01, 0.2]\n")),
                      {"building[1].hysteresis.yield_drift_m[2] = 0.2", "5 % of storey 2's height (3 m)"}));
  BOOST_TEST(mentions(error_of(with_strength("yield_drift_m = 0.2\n")),
                      {"building[1].hysteresis.yield_drift_m = 0.2", "5 % of the lowest storey (3 m)"}));
  BOOST_TEST(mentions(error_of(with_strength("yield_drift_ratio = 0.005\nyield_shear_kN = 400.0\n")),
                      {"building[1].hysteresis.yield_drift_ratio = given with yield_shear_kN",
                       "one of yield_drift_ratio, yield_drift_m and yield_shear_kN"}));
  BOOST_TEST(mentions(error_of(with_strength("")), {"building[1].hysteresis.yield_drift_ratio = missing"}));
  BOOST_TEST(
      mentions(error_of(with_strength("yield_shear_kN = [\"a\", 1.0]\n")), {"building[1].hysteresis.yield_shear_kN"}));
  // A shear that the columns reach only beyond 5 % of the storey's drift is refused once the
  // frame factor is known (here 4 k · 0.15 m = 1.7e4 kN at storey 1).
  Case too_strong(with_strength("yield_shear_kN = [2.0e4, 400.0]\n"));
  const auto strong = read_scene(too_strong.file);
  try {
    pounding::analysis::summarise_buildings(strong);
    BOOST_FAIL("a yield shear beyond 5 % drift was accepted");
  } catch (const InputError& error) {
    BOOST_TEST(mentions(error.what(), {"building[1].hysteresis.yield_shear_kN[1] = 20000",
                                       "yield drift of 0.1758 m along x, over 5 % of its height (3 m)"}));
  }
}

BOOST_AUTO_TEST_CASE(AColumnShearCapacityIsOneNumberForEveryStoreyOrOneAStoreyOrFromTheSection) {
  const std::string columns =
      "columns = [[-10.0, 0.0, 0.4, 0.4], [0.0, 0.0, 0.4, 0.4], [0.0, 8.0, 0.4, 0.4], [-10.0, 8.0, 0.4, 0.4]]";
  const auto with = [&](const std::string& lines) { return edited(columns, columns + "\n" + lines); };
  Case spread(with("column_shear_capacity_kN = 300.0\n"));
  BOOST_TEST(read_scene(spread.file).buildings[0].column_shear_capacity_kN == std::vector<double>({300.0, 300.0}));
  Case listed(with("column_shear_capacity_kN = [300.0, 200.0]\n"));
  BOOST_TEST(read_scene(listed.file).buildings[0].column_shear_capacity_kN == std::vector<double>({300.0, 200.0}));
  BOOST_TEST(mentions(error_of(with("column_shear_capacity_kN = [300.0, -1.0]\n")),
                      {"building[1].column_shear_capacity_kN[2] = -1", "(0, 1000000] kN"}));
  BOOST_TEST(mentions(error_of(with("column_shear_capacity_kN = [300.0]\n")),
                      {"building[1].column_shear_capacity_kN = 1 values", "one value per storey (2)"}));
  // From the section: the keys are read as their rows say, checked against their ranges, and the
  // required ones must be there.
  const std::string section =
      "[building.shear_capacity]\nconcrete_strength_MPa = 25.0\ntransverse_yield_strength_MPa = 420.0\n"
      "transverse_area_mm2 = 157.0\ntransverse_spacing_mm = 200.0\n";
  Case formula(with(section));
  const auto capacity = read_scene(formula.file).buildings[0].shear_capacity;
  BOOST_TEST_REQUIRE(capacity.has_value());
  BOOST_TEST(capacity->concrete_strength_MPa == 25.0);
  BOOST_TEST(capacity->effective_depth_ratio == 0.8);  // the default
  BOOST_TEST(!capacity->axial_load_kN.has_value());    // unset: the gravity share
  BOOST_TEST(mentions(error_of(with(section + "ductility_factor = 0.5\n")),
                      {"building[1].shear_capacity.ductility_factor = 0.5", "[0.7, 1]"}));
  BOOST_TEST(mentions(error_of(with("[building.shear_capacity]\nconcrete_strength_MPa = 25.0\n")),
                      {"building[1].shear_capacity.transverse_yield_strength_MPa"}));
  BOOST_TEST(mentions(error_of(with("column_shear_capacity_kN = 300.0\n" + section)),
                      {"building[1].shear_capacity", "one way"}));
  // Losing the stiffness at the failure needs bilinear columns and a capacity.
  BOOST_TEST(mentions(error_of(with("column_shear_failure = \"crumble\"\n")),
                      {"building[1].column_shear_failure = \"crumble\"", "\"report\" or \"lose-stiffness\""}));
  BOOST_TEST(
      mentions(error_of(with("column_shear_capacity_kN = 300.0\ncolumn_shear_failure = \"lose-stiffness\"\n")),
               {"building[1].column_shear_failure", "needs bilinear, imk-peak-oriented or imk-pinching columns"}));
  BOOST_TEST(mentions(error_of(with("column_shear_failure = \"lose-stiffness\"\n[building.hysteresis]\nlaw = "
                                    "\"bilinear\"\nyield_drift_ratio = 0.005\n")),
                      {"building[1].column_shear_failure", "needs a shear capacity"}));
}

BOOST_AUTO_TEST_CASE(DriftLimitStatesAreReadFromTheirTableAndChecked) {
  const std::string columns =
      "columns = [[-10.0, 0.0, 0.4, 0.4], [0.0, 0.0, 0.4, 0.4], [0.0, 8.0, 0.4, 0.4], [-10.0, 8.0, 0.4, 0.4]]";
  const auto with_limits = [&](const std::string& lines) {
    return edited(columns, columns + "\n[building.limit_states]\n" + lines);
  };
  Case empty(with_limits(""));
  const auto defaults = read_scene(empty.file).buildings[0].drift_limits;
  BOOST_TEST_REQUIRE(defaults.has_value());
  BOOST_TEST(defaults->structural_type == "concrete-frame");
  BOOST_TEST((pounding::analysis::resolved_drift_limits(*defaults) == std::array<double, 3>{0.01, 0.02, 0.04}));
  Case given(with_limits("structural_type = \"concrete-wall\"\nlife_safety = 0.015\n"));
  const auto limits = *read_scene(given.file).buildings[0].drift_limits;
  BOOST_TEST((pounding::analysis::resolved_drift_limits(limits) == std::array<double, 3>{0.005, 0.015, 0.02}));
  BOOST_TEST(!read_scene(Case(kScene).file).buildings[0].drift_limits.has_value());

  BOOST_TEST(mentions(error_of(with_limits("structural_type = \"adobe\"\n")),
                      {"building[1].limit_states.structural_type = \"adobe\"", "\"concrete-frame\" or"}));
  BOOST_TEST(mentions(error_of(with_limits("life_safety = 0.5\n")),
                      {"building[1].limit_states.life_safety = 0.5", "(0, 0.2]"}));
  BOOST_TEST(mentions(error_of(with_limits("collapse_prevention = 0.015\n")),
                      {"building[1].limit_states.collapse_prevention = 0.015",
                       "must exceed the LS limit (0.02, the "
                       "concrete-frame default)"}));
  BOOST_TEST(mentions(error_of(with_limits("life_safty = 0.02\n")), {"limit_states.life_safty", "life_safety"}));
  BOOST_TEST(mentions(error_of(with_limits("") + "[output]\npeaks = [\"displacements\"]\n"),
                      {"output.peaks = [\"displacements\"]", "must include \"drifts\"", "building 'A'"}));
}

BOOST_AUTO_TEST_CASE(AbsurdContactSolverAndOutputValuesNameTheirRange) {
  BOOST_TEST(mentions(error_of(kScene, {.gap_m = 1e17}), {"--gap = 1e+17", "[0, 10] m"}));
  BOOST_TEST(mentions(error_of(edited("restitution = 0.5", "restitution = 0.5\nhold_velocity_mps = 1e6")),
                      {"contact.hold_velocity_mps = 1000000", "(0, 0.1] m/s"}));
  const auto with_solver = [](const std::string& table) { return kScene + table; };
  BOOST_TEST(mentions(error_of(with_solver("[solver]\nrtol = 1e-300\n")), {"solver.rtol = 1e-300", "[1e-14, 0.1]"}));
  BOOST_TEST(mentions(error_of(with_solver("[solver]\natol = 1e300\n")), {"solver.atol = 1e+300", "[1e-16, 0.001]"}));
  BOOST_TEST(mentions(error_of(with_solver("[solver]\nmethod = \"hht\"\ndt_s = 100.0\n")),
                      {"solver.dt_s = 100", "(0, 0.1] s"}));
  BOOST_TEST(mentions(error_of(with_solver("[solver]\nmethod = \"hht\"\ncontact_tolerance_m = 10.0\n")),
                      {"solver.contact_tolerance_m = 10", "(0, 0.01] m"}));
  BOOST_TEST(mentions(error_of(with_solver("[output]\nhistory_interval_s = 1e-9\n")),
                      {"output.history_interval_s = 1e-09", "[0.0001, 10] s"}));
  BOOST_TEST(mentions(error_of(with_solver("[output]\nhistory_floors = [1, 2, 1]\n")),
                      {"output.history_floors[3] = 1", "listed twice"}));
}

BOOST_AUTO_TEST_CASE(ASolverKeyTheFilesMethodDoesNotUseIsRefused) {
  BOOST_TEST(mentions(error_of(kScene + "[solver]\nmethod = \"hht\"\nrtol = 1e-10\n"),
                      {"scene.toml", "solver.rtol = 1e-10", "does not apply to method hht"}));
  BOOST_TEST(mentions(error_of(kScene + "[solver]\ndt_s = 0.01\n"), {"solver.dt_s = 0.01", "method cvode-bdf"}));
  BOOST_TEST(mentions(error_of(kScene + "[solver]\nmethod = \"arkode-erk\"\nnewton = \"dense\"\n"),
                      {"solver.newton = \"dense\"", "does not apply to method arkode-erk"}));
  Case ok(kScene + "[solver]\nmethod = \"hht\"\ndt_s = 0.01\n");
  BOOST_TEST(read_scene(ok.file).solver.dt_s.value_or(0.0) == 0.01);
}

BOOST_AUTO_TEST_CASE(HoldRtolOfTheExactPathNamesItsRange) {
  Case ok(kScene + "[solver]\nmethod = \"exact\"\nhold_rtol = 1e-10\n");
  BOOST_TEST(read_scene(ok.file).solver.hold_rtol.value_or(0.0) == 1e-10);
  BOOST_TEST(mentions(error_of(kScene + "[solver]\nmethod = \"exact\"\nhold_rtol = 1e-3\n"),
                      {"scene.toml", "solver.hold_rtol = 0.001", "[1e-14, 1e-06]"}));
  BOOST_TEST(mentions(error_of(kScene + "[solver]\nmethod = \"exact\"\nhold_rtol = 1e-300\n"),
                      {"solver.hold_rtol = 1e-300", "[1e-14, 1e-06]"}));
  BOOST_TEST(mentions(error_of(kScene + "[solver]\nmethod = \"exact\"\nhold_rtol = nan\n"),
                      {"solver.hold_rtol = nan", "[1e-14, 1e-06]"}));
}

BOOST_AUTO_TEST_CASE(AbsurdExcitationValuesNameTheirRange) {
  const auto with = [](const std::string& line) { return edited("units = \"m/s2\"", "units = \"m/s2\"\n" + line); };
  BOOST_TEST(mentions(error_of(with("g_mps2 = 1e308")), {"excitation.g_mps2 = 1e+308", "[9, 10.5] m/s2"}));
  BOOST_TEST(mentions(error_of(with("direction_deg = 1e300")), {"excitation.direction_deg = 1e+300", "[-360, 360]"}));
  BOOST_TEST(mentions(error_of(with("dt_s = 1e306")), {"excitation.dt_s = 1e+306", "[1e-05, 1] s"}));
}

BOOST_AUTO_TEST_CASE(OversizedSceneFileIsRefusedUnread) {
  BOOST_TEST(mentions(error_of(kScene + "# " + std::string(pounding::io::kMaxSceneBytes, 'x') + "\n"),
                      {"scene.toml", "bytes", "at most 1048576 bytes"}));
}

BOOST_AUTO_TEST_CASE(AbsurdStoreyStiffnessIsRefusedBeforeTheEigensolver) {
  BOOST_TEST(mentions(error_of(edited("[[50000.0, 0.0, 0.0]", "[[1e300, 0.0, 0.0]")),
                      {"building[2].storey_stiffness[1] = 1e+300", "[-1e+16, 1e+16]"}));
}

BOOST_AUTO_TEST_CASE(TableHeaderStartingWithoutAKeyIsRefused) {
  // Found by fuzzing: toml++ 3.3's internal check in parse_key fails on "[+a]" (undefined
  // behaviour when that check is compiled as an assumption).
  BOOST_TEST(mentions(error_of("[+a]\n" + kScene), {"scene.toml"}));
  BOOST_TEST(mentions(error_of(kScene + "[[+building]]\n"), {"scene.toml"}));
}

BOOST_AUTO_TEST_CASE(NonAsciiTextReachesTomlOnlyAsEscapes) {
  // Found by fuzzing: toml++ 3.3 reaches TOML_UNREACHABLE (unicode_autogenerated.h:44) when it
  // asks whether a character in U+00A1…U+0499 is whitespace, e.g. right after a value.
  BOOST_TEST(
      mentions(error_of(edited("storey_height_m = 3.0\nslab = [[-10.0", "storey_height_m = 3.0²\nslab = [[-10.0")),
               {"scene.toml:5:22", "non-ASCII character outside a string or comment"}));
  Case basic(edited("name = \"small\"", "name = \"Gebäude ²µ 東京 🏢\" # é"));
  BOOST_TEST(read_scene(basic.file).name == "Gebäude ²µ 東京 🏢");
  Case literal(edited("name = \"small\"", "name = 'C:\\dir \"é\"'"));
  BOOST_TEST(read_scene(literal.file).name == "C:\\dir \"é\"");
  Case multi(edited("name = \"small\"", "description = '''\nä ''b'''\nname = \"\"\"x\\\n   ö\"\"\""));
  BOOST_TEST(read_scene(multi.file).name == "xö");
  BOOST_TEST(mentions(error_of(edited("name = \"small\"", "\"ñame\" = \"small\"")), {"unknown key"}));
}

BOOST_AUTO_TEST_CASE(RecordPathTooLongForTheSystemIsRefusedAsMissing) {
  // Found by fuzzing: is_regular_file threw filesystem_error (name too long) past InputError.
  BOOST_TEST(mentions(error_of(edited("file = \"record.txt\"", "file = \"" + std::string(5000, 'x') + "\"")),
                      {"excitation.file", "no such record file"}));
}
