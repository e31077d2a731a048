// The finite-element table in the tick's place (models/fe_stress_table.hpp): the cost of one
// lookup and of one function-scene sample with and without the table (Google Benchmark), and,
// with --figure DIR, the figure of docs/finite-element.md: the target pressure finger 1 asks for
// along a pass across the same tumor 5 and 15 mm deep (data/scenes/fe_depths.json), pressing
// 2 N, rendered from the shipped table and by the felt-stiffness rule.
//   build/bin/bench_fe_table                       the benchmarks
//   build/bin/bench_fe_table --figure docs         docs/fe_depths.png and .svg
// The tick's own p99 with the table is bench_tick's BM_TickFunctionSceneFeTable.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

#include "charts/chart_png.hpp"
#include "charts/chart_svg.hpp"
#include "controller/tick.hpp"
#include "controller/tick_setup.hpp"
#include "formats/rig_file.hpp"
#include "formats/scene_file.hpp"
#include "models/tissue_scene.hpp"

using namespace palprig;

namespace {

const std::filesystem::path kData = std::filesystem::path(PALPRIG_SOURCE_DIR) / "data";

SceneFile& depths_scene() {
  static SceneFile scene = load_scene_file(kData / "scenes" / "fe_depths.json");
  return scene;
}

void BM_TableLookup(benchmark::State& state) {
  const FeStressTable& t = *dynamic_cast<FunctionScene&>(*depths_scene().scene).fe_table();
  double x = 0;
  for (auto _ : state) {
    x += 0.37;
    if (x > 20) x = 0;
    benchmark::DoNotOptimize(t.rise_kPa(7.0, 5.0 + x / 4, 10.0, 6.8, x));
  }
}
BENCHMARK(BM_TableLookup);

void sample_cost(benchmark::State& state, bool table) {
  auto& scene = dynamic_cast<FunctionScene&>(*depths_scene().scene);
  static const FeStressTable kept = *scene.fe_table();
  scene.use_fe_table(table ? std::make_shared<const FeStressTable>(kept) : nullptr);
  double x = 20;
  for (auto _ : state) {
    x += 0.06;  // hand speed at 1 kHz
    if (x > 140) x = 20;
    benchmark::DoNotOptimize(scene.sample({x, 40}, 2.0, 0.0));
  }
  scene.use_fe_table(std::make_shared<const FeStressTable>(kept));
}
void BM_SampleWithTable(benchmark::State& s) { sample_cost(s, true); }
void BM_SampleStiffnessRule(benchmark::State& s) { sample_cost(s, false); }
BENCHMARK(BM_SampleWithTable);
BENCHMARK(BM_SampleStiffnessRule);

// What the tick asks of finger 1 held at x (steady: past the slew limit's ramp).
double held_target_kPa(const Scene& scene, const TickConfig& cfg, double x) {
  TickState st = make_tick_state(cfg);
  TouchSample s;
  s.x_mm = x;
  s.y_mm = 40;
  s.force_N = 2.0;
  s.in_contact = true;
  double p = 0;
  for (int k = 0; k < 400; ++k) {
    s.t_s = k * 1e-3;
    p = tick(st, cfg, scene, s, s.t_s).record.target_kPa[0];
  }
  return p;
}

int write_figure(const std::filesystem::path& dir) {
  auto& scene = dynamic_cast<FunctionScene&>(*depths_scene().scene);
  const auto table = std::make_shared<const FeStressTable>(*scene.fe_table());
  const TickConfig cfg = make_tick_config(load_rig_file(kData / "rigs" / "simulated.json"), CalibrationModels{});
  charts::Chart c;
  c.title = "The same tumor 5 and 15 mm deep, pressing 2 N: target pressure of finger 1";
  c.x_label = "finger 1 across the scene (mm); tumors at 50 (top 5 mm down) and 110 (15 mm)";
  c.y_label = "target air pressure (kPa)";
  for (bool with_table : {true, false}) {
    scene.use_fe_table(with_table ? table : nullptr);
    charts::ChartSeries s;
    s.label = with_table ? "finite-element table" : "felt-stiffness rule";
    for (double x = 20; x <= 140.01; x += 1) {
      s.x.push_back(x);
      s.y.push_back(held_target_kPa(scene, cfg, x));
    }
    std::printf("%s: shallow %.2f kPa, deep %.2f kPa, between %.2f kPa\n", s.label.c_str(), s.y[30], s.y[90], s.y[60]);
    c.series.push_back(s);
  }
  scene.use_fe_table(table);
  c.y_min = 0;
  charts::write_chart_png(c, dir / "fe_depths.png");
  charts::write_chart_svg(c, dir / "fe_depths.svg");
  std::printf("wrote %s and %s\n", (dir / "fe_depths.png").c_str(), (dir / "fe_depths.svg").c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 3 && std::strcmp(argv[1], "--figure") == 0) return write_figure(argv[2]);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
