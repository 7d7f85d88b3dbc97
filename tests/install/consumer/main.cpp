// Reads a scene, prints both buildings' first period and the impacts of its run:
// consumer SCENE -> "T1 T2 IMPACTS" (periods in s, 17 significant digits).
#include <cstdio>
#include "pounding/analysis/modal_summary.hpp"
#include "pounding/analysis/run_scene.hpp"
#include "pounding/io/scene_reader.hpp"

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const pounding::analysis::Scene scene = pounding::io::read_scene(argv[1]);
  const auto buildings = pounding::analysis::summarise_buildings(scene);
  const auto report = pounding::analysis::run_scene(scene);
  std::printf("%.17g %.17g %zu\n", buildings[0].modes[0].period_s, buildings[1].modes[0].period_s,
              report.result.impacts.size());
}
