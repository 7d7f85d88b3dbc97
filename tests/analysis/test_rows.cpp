#include <boost/test/unit_test.hpp>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "pounding/analysis/run_scene.hpp"
#include "pounding/input_error.hpp"
#include "pounding/io/scene_reader.hpp"

using namespace pounding;

namespace {

const std::string kRowOfThree = POUNDING_EXAMPLES_DIR "/rows/row-of-three.toml";
const std::string kCornerBlock = POUNDING_EXAMPLES_DIR "/rows/corner-block.toml";

std::string text_of(const std::string& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// `text` with `from` replaced by `to` once. @pre `from` occurs in it.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  BOOST_REQUIRE_MESSAGE(at != std::string::npos, "no '" << from << "' in the scene");
  return text.replace(at, from.size(), to);
}

/// The InputError's key that reading `text` (as if it were the row-of-three's file) raises; empty: none.
std::string refused_key(const std::string& text, std::string* reason = nullptr) {
  try {
    io::parse_scene(text, kRowOfThree);
  } catch (const InputError& error) {
    if (reason != nullptr) *reason = error.reason();
    return error.key();
  }
  return {};
}

model::Polygon rectangle(double x0, double y0, double x1, double y1) {
  return model::Polygon({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}});
}

}  // namespace

BOOST_AUTO_TEST_CASE(ClearanceIsTheShortestDistanceAndTheDirectionThatWidensIt) {
  const model::Polygon a = rectangle(0, 0, 10, 8);
  // Facing across x (the nearest points along a whole edge), across y, and corner to corner.
  const model::Clearance east = model::clearance(a, rectangle(10.3, 2, 20, 12));
  BOOST_TEST(east.distance_m == 0.3, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(east.direction.x() == 1.0);
  BOOST_TEST(east.direction.y() == 0.0);
  const model::Clearance north = model::clearance(a, rectangle(-3, 8.05, 4, 15));
  BOOST_TEST(north.distance_m == 0.05, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(north.direction.y() == 1.0);
  const model::Clearance south = model::clearance(rectangle(-3, -9, 4, -0.2), a);  // a is the second
  BOOST_TEST(south.distance_m == 0.2, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(south.direction.y() == 1.0);
  // Facades in line (the same y range): the nearest corners lie on two edges each; the pair
  // still faces along x.
  for (const double gap : {0.25, 0.0}) {
    const model::Clearance aligned = model::clearance(a, rectangle(10 + gap, 0, 20, 8));
    BOOST_TEST(aligned.distance_m == gap, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(aligned.direction.x() == 1.0);
    BOOST_TEST(aligned.direction.y() == 0.0);
  }
  const model::Clearance diagonal = model::clearance(a, rectangle(13, 12, 20, 20));
  BOOST_TEST(diagonal.distance_m == 5.0, boost::test_tools::tolerance(1e-12));  // 3-4-5 between the corners
}

BOOST_AUTO_TEST_CASE(ARowFindsEachPairsLevelsAndCandidatesByTheTwoBuildingRules) {
  const analysis::Scene row = io::read_scene(kRowOfThree);
  const std::vector<analysis::BuildingPair> pairs = row.pairs();
  BOOST_REQUIRE_EQUAL(pairs.size(), 2u);  // B1 and B3 stand 28 m apart
  BOOST_TEST(pairs[0].first == 0);
  BOOST_TEST(pairs[0].second == 1);
  BOOST_TEST(pairs[1].first == 1);
  BOOST_TEST(pairs[1].second == 2);
  BOOST_TEST(pairs[0].gap_m == 0.2, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(pairs[1].gap_m == 0.2, boost::test_tools::tolerance(1e-12));

  // Each pair's levels and candidates are its two-building scene's, moved onto its buildings and
  // numbered on: B1:B2 has levels 1-7 (the paper's 14 candidates), B2:B3 levels 8-13.
  const std::vector<contact::Level> levels = row.levels();
  const std::vector<contact::Candidate> candidates = analysis::scene_candidates(row);
  BOOST_REQUIRE_EQUAL(levels.size(), 13u);
  int level_offset = 0;
  std::size_t next = 0;
  for (const analysis::BuildingPair& pair : pairs) {
    const analysis::Scene two = row.pair_scene(pair);
    const std::vector<contact::Level> own_levels = two.levels();
    const std::vector<contact::Candidate> own = analysis::scene_candidates(two);
    for (const contact::Level& level : own_levels) {
      const contact::Level& in_row = levels.at(static_cast<std::size_t>(level.index + level_offset - 1));
      BOOST_TEST(in_row.index == level.index + level_offset);
      BOOST_TEST(in_row.floors == level.floors);
      BOOST_TEST((in_row.pair == std::array{pair.first, pair.second}));
    }
    for (const contact::Candidate& c : own) {
      const contact::Candidate& in_row = candidates.at(next++);
      BOOST_TEST(in_row.level == c.level + level_offset);
      BOOST_TEST((in_row.pair == std::array{pair.first, pair.second}));
      BOOST_TEST(in_row.striking_building == in_row.pair[static_cast<std::size_t>(c.striking_building)]);
      BOOST_TEST(in_row.struck_building == in_row.pair[static_cast<std::size_t>(c.struck_building)]);
      BOOST_TEST(in_row.floors == c.floors);
      BOOST_TEST((in_row.vertex_rest == c.vertex_rest));
      BOOST_TEST((in_row.edge_start_rest == c.edge_start_rest));
    }
    level_offset += static_cast<int>(own_levels.size());
  }
  BOOST_TEST(next == candidates.size());
}

BOOST_AUTO_TEST_CASE(APairsGapMovesItsSecondBuildingWithEveryBuildingBeyond) {
  const analysis::Scene row = io::read_scene(kRowOfThree);
  analysis::Scene wider = row;
  wider.set_pair_gap("B2", "B1", 0.35);  // either order
  const double shift = 0.35 - row.pairs()[0].gap_m;
  BOOST_TEST(wider.buildings[0].slab.vertex(0).x() == row.buildings[0].slab.vertex(0).x());
  for (std::size_t b : {1u, 2u}) {  // B2 and B3 beyond it move together
    BOOST_TEST(wider.buildings[b].slab.vertex(0).x() == row.buildings[b].slab.vertex(0).x() + shift,
               boost::test_tools::tolerance(1e-12));
    BOOST_TEST(wider.buildings[b].centre_of_mass.x() == row.buildings[b].centre_of_mass.x() + shift,
               boost::test_tools::tolerance(1e-12));
    BOOST_TEST(
        wider.buildings[b].columns.front().position_m.x() == row.buildings[b].columns.front().position_m.x() + shift,
        boost::test_tools::tolerance(1e-12));
  }
  BOOST_TEST(wider.pairs()[0].gap_m == 0.35, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(wider.pairs()[1].gap_m == row.pairs()[1].gap_m, boost::test_tools::tolerance(1e-9));
  wider.validate();  // [contact.gaps] follows the move

  analysis::Scene closer = row;
  closer.set_pair_gap("B2", "B3", 0.05);  // only B3 moves
  BOOST_TEST(closer.buildings[1].slab.vertex(0).x() == row.buildings[1].slab.vertex(0).x());
  BOOST_TEST(closer.pairs()[1].gap_m == 0.05, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(closer.pairs()[0].gap_m == row.pairs()[0].gap_m);

  BOOST_CHECK_THROW(closer.set_pair_gap("B1", "B3", 0.1), InputError);  // not neighbours
  BOOST_CHECK_THROW(closer.set_pair_gap("B1", "B9", 0.1), InputError);  // no such building
  BOOST_CHECK_THROW(closer.set_gap(0.1), InputError);                   // one gap for a row
}

BOOST_AUTO_TEST_CASE(APairOnARingOfNeighboursIsNotMovedAlone) {
  // B3 stands in the corner above B1 and beside B2, 0.3 m and 0.2 m from them.
  std::string text = text_of(kRowOfThree);
  text = replaced(text, "slab = [[28.4, 10.0], [46.4, 10.0], [46.4, 30.0], [28.4, 30.0]]",
                  "slab = [[-10.0, 20.3], [0.0, 20.3], [0.0, 40.3], [-10.0, 40.3]]");
  text = replaced(text, "centre_of_mass = [38.2, 20.8]", "centre_of_mass = [-4.8, 30.8]");
  text = replaced(text, "x = [28.4, 34.4, 40.4, 46.4]", "x = [-10.0, -6.0, -3.0, 0.0]");
  text = replaced(text, "y = [10.0, 15.0, 20.0, 25.0, 30.0]", "y = [20.3, 25.3, 30.3, 35.3, 40.3]");
  text = replaced(text, "\"B2:B3\" = 0.20\n", "");
  analysis::Scene ring = io::parse_scene(text, kRowOfThree);
  BOOST_REQUIRE_EQUAL(ring.pairs().size(), 3u);
  try {
    ring.set_pair_gap("B1", "B2", 0.3);
    BOOST_FAIL("a pair on a ring was moved");
  } catch (const InputError& error) {
    BOOST_TEST(error.reason().find("ring") != std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(APairFacingAlongYIsTurnedAQuarterForTheNeededGap) {
  const analysis::Scene corner = io::read_scene(kCornerBlock);
  const analysis::BuildingPair north = corner.pairs().at(1);  // Corner:North, North on +y
  BOOST_TEST(north.direction.y() == 1.0);
  double turned_deg = 0.0;
  const analysis::Scene two = corner.pair_scene_facing_x(north, turned_deg);
  BOOST_TEST(turned_deg == 270.0);
  two.validate();  // now the second building stands on the +x side, contact.gap_m the clearance
  BOOST_TEST(*model::horizontal_clearance(two.buildings[0].slab, two.buildings[1].slab) == north.gap_m,
             boost::test_tools::tolerance(1e-12));
  BOOST_TEST(two.excitation.direction_deg == std::fmod(corner.excitation.direction_deg + 270.0, 360.0));
  // A column's b lies along x: a quarter turn exchanges b and h (the storey stiffness turns with it).
  const model::Column& before = corner.buildings[2].columns.front();
  const model::Column& after = two.buildings[1].columns.front();
  BOOST_TEST(after.position_m.x() == before.position_m.y(), boost::test_tools::tolerance(1e-12));
  BOOST_TEST(after.position_m.y() == -before.position_m.x(), boost::test_tools::tolerance(1e-12));
  // The periods do not depend on the turn.
  const model::Building turned = model::make_building(two.buildings[1]);
  const model::Building original = model::make_building(corner.buildings[2]);
  for (std::size_t k = 0; k < 3; ++k)
    BOOST_TEST(turned.modes[k].period_s == original.modes[k].period_s, boost::test_tools::tolerance(1e-9));
}

BOOST_AUTO_TEST_CASE(ARowsImpactsNameTheirPairAndItsFloorsAndTheEnergyCloses) {
  const analysis::Scene row = io::read_scene(kRowOfThree);
  const analysis::RunReport report = analysis::run_scene(row);
  BOOST_REQUIRE(report.result.status == solvers::RunStatus::completed);
  int between_b2_b3 = 0;
  for (const solvers::ImpactRecord& impact : report.result.impacts) {
    const contact::Candidate& c = report.candidates.at(impact.candidate);
    BOOST_TEST((impact.buildings == std::array{c.pair[0] + 1, c.pair[1] + 1}));
    BOOST_TEST(impact.striking_building == c.striking_building + 1);
    BOOST_TEST(impact.struck_building == c.struck_building + 1);
    BOOST_TEST(impact.floors == c.floors);
    between_b2_b3 += impact.buildings == std::array{2, 3};
  }
  BOOST_TEST(between_b2_b3 > 0);  // B2 is struck from both sides
  BOOST_TEST(between_b2_b3 < static_cast<int>(report.result.impacts.size()));
  const auto& e = report.result.energy;
  BOOST_TEST(std::abs(e.residual_kJ()) < 1e-6 * e.input_kJ);
}

BOOST_AUTO_TEST_CASE(ARowsFileIsCheckedNamingTheKey) {
  const std::string row = text_of(kRowOfThree);
  std::string reason;
  BOOST_TEST(refused_key(replaced(row, "[contact]\n", "[contact]\ngap_m = 0.2\n"), &reason) == "contact.gap_m");
  BOOST_TEST(refused_key(replaced(row, "\"B2:B3\" = 0.20", "\"B2:B3\" = 0.25")) == "contact.gaps.\"B2:B3\"");
  BOOST_TEST(refused_key(replaced(row, "\"B2:B3\" = 0.20", "\"B2:B9\" = 0.20")) == "contact.gaps.\"B2:B9\"");
  BOOST_TEST(refused_key(replaced(row, "\"B2:B3\" = 0.20", "\"B1:B3\" = 0.20"), &reason) == "contact.gaps.\"B1:B3\"");
  BOOST_TEST(reason.find("no neighbouring pair") != std::string::npos);
  BOOST_TEST(refused_key(replaced(row, "\"B2:B3\" = 0.20", "\"B2-B3\" = 0.20")) == "contact.gaps.\"B2-B3\"");
  BOOST_TEST(refused_key(replaced(row, "name = \"B3\"", "name = \"B1\"")) == "building[3].name");
  // Slabs that overlap at rest.
  BOOST_TEST(refused_key(replaced(row, "slab = [[28.4, 10.0]", "slab = [[28.0, 10.0]")) == "building[3].slab");
  // Two buildings take contact.gap_m, not [contact.gaps].
  const std::string paper = text_of(POUNDING_EXAMPLES_DIR "/paper/paper.toml");
  try {
    io::parse_scene(paper + "[contact.gaps]\n\"B1:B2\" = 0.2\n", POUNDING_EXAMPLES_DIR "/paper/paper.toml");
    BOOST_FAIL("[contact.gaps] accepted for two buildings");
  } catch (const InputError& error) {
    BOOST_TEST(error.key() == "contact.gaps");
  }
}
