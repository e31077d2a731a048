// Frame time of the window's two busy views, drawn with the same code as on screen
// (StripChart::render_to, SceneView::render_to) into a QImage with Qt's raster engine, the
// engine behind a widget's backing store on xcb and offscreen alike. Goal: under 8 ms at 60 Hz
// with 10 s windows (9 traces of 10,000 points each).
//   build/bin/bench_gui_frames        (sets QT_QPA_PLATFORM=offscreen unless already set)
#include <benchmark/benchmark.h>

#include <QApplication>
#include <QImage>
#include <QPainter>
#include <cmath>
#include <cstdlib>
#include <random>

#include "formats/scene_file.hpp"
#include "gui/scene_image.hpp"
#include "gui/scene_view.hpp"
#include "gui/strip_chart.hpp"
#include "gui/trace_history.hpp"
#include "models/finger_layout.hpp"

using namespace palprig;
using namespace palprig::gui;

namespace {

// window_s seconds at 1 kHz of pressures that look like a pass over the phantom: slow steps
// between soft tissue and tumors, the regulator's lag, and monitor noise.
TraceHistory make_history(double window_s) {
  TraceHistory h(std::size_t(window_s * 1000) + 10);
  std::mt19937 rng(1);
  std::normal_distribution<float> noise(0.0f, 0.1f);
  float monitor[kFingerCount] = {};
  for (int k = 0; k < int(window_s * 1000); ++k) {
    TraceSample s;
    s.t_s = k * 1e-3;
    for (int f = 0; f < kFingerCount; ++f) {
      const float target = std::fmod(s.t_s + f * 0.7, 3.0) < 1.0 ? 11.75f : 0.6f;
      monitor[f] += (target - monitor[f]) * (1.0f - std::exp(-1e-3f / 0.05f));
      s.kPa[int(TraceKind::target)][f] = target;
      s.kPa[int(TraceKind::setpoint)][f] = target;
      s.kPa[int(TraceKind::monitor)][f] = monitor[f] + noise(rng);
    }
    h.push(s);
  }
  return h;
}

void BM_StripChartFrame(benchmark::State& state) {
  const double window_s = double(state.range(0));
  const TraceHistory history = make_history(window_s);
  StripChart chart(&history);
  chart.set_window_s(window_s);
  chart.resize(1240, 330);  // as in the 1280 x 860 window
  QImage frame(chart.size(), QImage::Format_ARGB32_Premultiplied);
  for (auto _ : state) {
    QPainter p(&frame);
    chart.render_to(p, frame.rect());
    p.end();
    benchmark::DoNotOptimize(frame.constBits());
  }
  state.counters["points_per_trace"] = double(history.size());
  state.counters["traces"] = 9;
}
BENCHMARK(BM_StripChartFrame)->Arg(10)->Arg(60)->Unit(benchmark::kMillisecond);

void BM_SceneViewFrame(benchmark::State& state, const char* scene_file) {
  const SceneFile scene = load_scene_file(std::string(PALPRIG_SOURCE_DIR) + "/data/scenes/" + scene_file);
  SceneView view(scene, FingerLayout{}, 60.0);
  view.resize(760, 470);
  // Pressing over the middle of the scene: indentation grids and coloured fingers drawn.
  const SceneBounds b = scene.scene->bounds();
  TelemetryRecord r;
  r.x_mm = float((b.x0_mm + b.x1_mm) / 2);
  r.y_mm = float((b.y0_mm + b.y1_mm) / 2);
  r.force_N = 2.0f;
  r.flags = kInContact;
  for (int f = 0; f < kFingerCount; ++f) {
    r.stiffness[f] = 0.3f * float(f);
    r.setpoint_kPa[f] = 4.0f * float(f);
  }
  view.show_record(r);
  QImage frame(view.size(), QImage::Format_ARGB32_Premultiplied);
  for (auto _ : state) {
    QPainter p(&frame);
    view.render_to(p);
    p.end();
    benchmark::DoNotOptimize(frame.constBits());
  }
}
BENCHMARK_CAPTURE(BM_SceneViewFrame, phantom_map, "phantom_abc.json")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SceneViewFrame, brachial_function_scene, "brachial_pulse.json")->Unit(benchmark::kMillisecond);

// What a breathing function scene costs to re-render (SceneView does it at 120 px on a worker
// thread once a second).
void BM_FunctionSceneRender(benchmark::State& state) {
  const SceneFile scene = load_scene_file(std::string(PALPRIG_SOURCE_DIR) + "/data/scenes/liver_edge.json");
  double t = 0;
  for (auto _ : state) {
    QImage img = render_scene_image(*scene.scene, 2.0, t, 120, 120);
    benchmark::DoNotOptimize(img.constBits());
    t += 0.5;
  }
}
BENCHMARK(BM_FunctionSceneRender)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  setenv("QT_QPA_PLATFORM", "offscreen", 0);
  QApplication app(argc, argv);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
