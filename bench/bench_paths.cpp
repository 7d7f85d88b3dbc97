// Times one run of the paper scene per solution path at its default settings, for tracking speed
// over time (not part of CI's pass/fail):  ./build/bench/bench_paths [--benchmark_repetitions=5]

#include <benchmark/benchmark.h>

#include "pounding/analysis/run_scene.hpp"
#include "pounding/io/scene_reader.hpp"

namespace {

void run_paper(benchmark::State& state, const char* method) {
  pounding::analysis::Scene scene = pounding::io::read_scene(POUNDING_EXAMPLES_DIR "/paper/paper.toml");
  scene.solver.method = method;
  std::size_t impacts = 0;
  for (auto _ : state) {
    const auto report = pounding::analysis::run_scene(scene);
    impacts = report.result.impacts.size();
    benchmark::DoNotOptimize(impacts);
  }
  state.counters["impacts"] = static_cast<double>(impacts);
}

BENCHMARK_CAPTURE(run_paper, cvode_bdf, "cvode-bdf")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(run_paper, cvode_adams, "cvode-adams")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(run_paper, arkode_erk, "arkode-erk")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(run_paper, arkode_dirk, "arkode-dirk")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(run_paper, hht, "hht")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(run_paper, exact, "exact")->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
