// Loading a function scene whose one inclusion is a union of N spheres (a grid at a 2.5 mm
// pitch), and sampling it: both should grow about linearly with N (the union's part grid), where
// a plain scan of the parts made loading quadratic (5,000 spheres 16 s, 20,000 spheres 254 s).
//   build/bin/bench_scene_load
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "formats/scene_file.hpp"

using namespace palprig;

namespace {

std::filesystem::path sphere_union_scene(int n) {
  nlohmann::json parts = nlohmann::json::array();
  const int side = static_cast<int>(std::ceil(std::sqrt(double(n))));
  for (int i = 0; i < n; ++i) {
    const int column = i % side, row = i / side;  // the spheres on a square grid, 2.5 mm apart
    parts.push_back({{"type", "sphere"}, {"centre_mm", {10 + 2.5 * column, 10 + 2.5 * row, 5}}, {"radius_mm", 1.0}});
  }
  const nlohmann::json doc = {
      {"version", 1},
      {"kind", "function"},
      {"body", {{"centre_mm", {100, 100}}, {"half_size_mm", {100, 100}}}},
      {"layers", {{{"name", "skin"}, {"thickness_mm", 40}, {"stiffness_kPa", 10}}}},
      {"felt_range_kPa", {{"soft", 10}, {"hard", 100}}},
      {"inclusions", {{{"name", "many"}, {"stiffness_kPa", 100}, {"shape", {{"type", "union"}, {"of", parts}}}}}}};
  auto path = std::filesystem::temp_directory_path() /
              ("palprig-bench-union-" + std::to_string(::getpid()) + "-" + std::to_string(n) + ".json");
  std::ofstream(path) << doc.dump();
  return path;
}

void BM_LoadSphereUnion(benchmark::State& state) {
  const auto path = sphere_union_scene(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(load_scene_file(path));
  std::filesystem::remove(path);
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_LoadSphereUnion)->Arg(500)->Arg(1000)->Arg(2000)->Arg(4000)->Unit(benchmark::kMillisecond)->Complexity();

void BM_SampleSphereUnion(benchmark::State& state) {
  const auto path = sphere_union_scene(static_cast<int>(state.range(0)));
  const SceneFile s = load_scene_file(path);
  std::filesystem::remove(path);
  double x = 10;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.scene->sample({x, 60}, 2.0, 0.0));
    x = x > 160 ? 10 : x + 0.37;
  }
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_SampleSphereUnion)->Arg(500)->Arg(1000)->Arg(2000)->Arg(4000)->Complexity();

}  // namespace

BENCHMARK_MAIN();
