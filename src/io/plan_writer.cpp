#include "pounding/io/plan_writer.hpp"

#include "pounding/io/json_report.hpp"

namespace pounding::io {

namespace {

using json = nlohmann::ordered_json;

json point(const model::Point2& p) { return json::array({p.x(), p.y()}); }

json building_json(const analysis::BuildingPlan& b) {
  json slab = json::array(), columns = json::array(), centres = json::array();
  for (const model::Point2& v : b.slab.vertices()) slab.push_back(point(v));
  for (const model::Column& c : b.columns) {
    columns.push_back({{"x_m", c.position_m.x()}, {"y_m", c.position_m.y()}, {"b_m", c.b_m}, {"h_m", c.h_m}});
  }
  for (const model::Point2& c : b.centres_of_stiffness) centres.push_back(point(c));
  return {{"name", b.name},
          {"slab", slab},
          {"centre_of_mass", point(b.centre_of_mass)},
          {"columns", columns},
          {"floor_elevations_m", b.floor_elevations_m},
          {"centres_of_stiffness", centres},
          {"periods_s", b.periods_s}};
}

}  // namespace

json plan_json(const analysis::ScenePlan& plan) {
  json levels = json::array(), candidates = json::array();
  const bool row = !plan.pairs.empty();  // a row's levels and candidates name their pair (1-based)
  for (const contact::Level& l : plan.levels) {
    levels.push_back({{"level", l.index}, {"floors", {l.floors[0], l.floors[1]}}, {"elevation_m", l.elevation_m}});
    if (row) levels.back()["buildings"] = {l.pair[0] + 1, l.pair[1] + 1};
  }
  for (const contact::Candidate& c : plan.candidates) {
    candidates.push_back({{"level", c.level},
                          {"striking_building", c.striking_building + 1},
                          {"vertex", point(c.vertex_rest)},
                          {"edge", {point(c.edge_start_rest), point(c.edge_end_rest)}}});
    if (row) candidates.back()["struck_building"] = c.struck_building + 1;
  }
  json buildings = json::array();
  for (const analysis::BuildingPlan& b : plan.buildings) buildings.push_back(building_json(b));
  json document = {{"scene", plan.scene},
                   {"gap_m", row ? json(nullptr) : json(plan.gap_m)},
                   {"buildings", buildings},
                   {"levels", levels},
                   {"candidates", candidates}};
  if (row) {
    json pairs = json::array();
    for (const analysis::BuildingPair& p : plan.pairs)
      pairs.push_back({{"buildings", {p.first + 1, p.second + 1}}, {"gap_m", p.gap_m}});
    document["pairs"] = pairs;
  }
  return document;
}

void write_plan(const analysis::ScenePlan& plan, const Provenance& provenance, const std::filesystem::path& folder) {
  std::filesystem::create_directories(folder);
  json document = plan_json(plan);
  document["provenance"] = provenance_json(provenance);
  write_json(document, folder / "plan.json");
}

}  // namespace pounding::io
