// The tick allocates nothing (docs/architecture.md, "The tick"), the lag
// compensation stage, the pulse stage and tissue drag included: every operator new of this
// program is counted on the thread that makes it, and a tick's thread must count none.
//
// Its own program (palprig_tests_tick_allocations): replacing operator new is program-wide, and
// the other suites keep the sanitizer's own new/delete pairing checks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>
#include <filesystem>
#include <new>
#include <vector>

#include "controller/tick.hpp"
#include "controller/tick_setup.hpp"
#include "formats/calibration_file.hpp"
#include "formats/rig_file.hpp"
#include "formats/scene_file.hpp"
#include "inputs/input_source.hpp"

// new is malloc here, so GCC's pairing warning (new with std::free once inlined) is wrong.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
namespace {
thread_local long t_allocations = 0;
}
void* operator new(std::size_t n) {
  ++t_allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

using namespace palprig;

namespace {

const std::filesystem::path kData = std::filesystem::path(PALPRIG_SOURCE_DIR) / "data";

CalibrationModels calibration(bool lag_compensated) {
  CalibrationModels cal = load_calibration_file(kData / "calibration" / "sim-default.json");
  cal.lag_compensation.enabled = lag_compensated;
  return cal;
}

struct Pass {
  long allocations = 0;
  std::vector<ChannelPressures> setpoints_kPa;
};

// Ticks through `samples` (made beforehand: making them allocates) with the shipped simulated
// rig and calibration, lag compensation on or off; counts the allocations the ticks made.
Pass tick_through(const Scene& scene, const std::vector<TouchSample>& samples, bool lag_compensated) {
  const TickConfig cfg =
      make_tick_config(load_rig_file(kData / "rigs" / "simulated.json"), calibration(lag_compensated));
  TickState st = make_tick_state(cfg);
  Pass pass;
  pass.setpoints_kPa.reserve(samples.size());  // within its capacity, push_back allocates nothing
  const long before = t_allocations;
  double t = 0;
  for (const TouchSample& s : samples) {
    pass.setpoints_kPa.push_back(tick(st, cfg, scene, s, t).setpoint_kPa);
    t += 1e-3;
  }
  pass.allocations = t_allocations - before;
  return pass;
}

// How many ticks commanded another setpoint with compensation than without: a pass that never
// exercised the compensator cannot pass for one that did.
int ticks_that_differ(const Pass& a, const Pass& b) {
  int n = 0;
  for (std::size_t i = 0; i < a.setpoints_kPa.size(); ++i)
    for (std::size_t f = 0; f < kFingerCount; ++f)
      if (std::abs(a.setpoints_kPa[i][f] - b.setpoints_kPa[i][f]) > 0.05) {
        ++n;
        break;
      }
  return n;
}

TEST(TickAllocations, TheDemoPassWithLagCompensationAllocatesNothing) {
  const SceneFile scene = load_scene_file(kData / "scenes" / "phantom_abc.json");
  const double contact_force_N =
      make_tick_config(load_rig_file(kData / "rigs" / "simulated.json"), calibration(true)).contact_force_N;
  TraceInput trace(load_trace_csv(kData / "traces" / "phantom_abc_pass.csv", contact_force_N), "pass", contact_force_N);
  std::vector<TouchSample> samples(static_cast<std::size_t>(trace.duration_s() * 1000));
  for (std::size_t i = 0; i < samples.size(); ++i) samples[i] = trace.latest(double(i) * 1e-3);
  const Pass on = tick_through(*scene.scene, samples, true);
  const Pass off = tick_through(*scene.scene, samples, false);
  EXPECT_EQ(on.allocations, 0);
  EXPECT_EQ(off.allocations, 0);
  EXPECT_GT(ticks_that_differ(on, off), 100)
      << "the pass crosses three tumors: the compensator should lead their edges";
}

// Function scenes: a pulsing artery (the pulse stage), a skin that drags (tissue drag) and two
// tumors rendered from the finite-element table, swept by a pressing pen back and forth.
TEST(TickAllocations, PulseAndDraggingScenesWithLagCompensationAllocateNothing) {
  for (const char* name : {"brachial_pulse", "liver_edge", "fe_depths"}) {
    SCOPED_TRACE(name);
    const SceneFile scene = load_scene_file(kData / "scenes" / (std::string(name) + ".json"));
    const SceneBounds b = scene.scene->bounds();
    std::vector<TouchSample> samples(6000);
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const double u = double(i % 2000) / 2000.0;  // 2 s per sweep, three sweeps
      TouchSample& s = samples[i];
      s.t_s = double(i) * 1e-3;
      s.x_mm = b.x0_mm + (b.x1_mm - b.x0_mm) * (u < 0.5 ? 2 * u : 2 - 2 * u);
      s.y_mm = 0.5 * (b.y0_mm + b.y1_mm);
      s.force_N = 2.5;
      s.in_contact = (i % 2000) < 1900;  // lifted for the last 0.1 s of each sweep
    }
    const Pass on = tick_through(*scene.scene, samples, true);
    const Pass off = tick_through(*scene.scene, samples, false);
    EXPECT_EQ(on.allocations, 0);
    EXPECT_EQ(off.allocations, 0);
    EXPECT_GT(ticks_that_differ(on, off), 0);
  }
}

// The counter itself counts (a test of the test: an allocation on this thread is seen).
TEST(TickAllocations, TheCounterSeesAnAllocation) {
  const long before = t_allocations;
  auto* v = new std::vector<int>(16);
  EXPECT_GE(t_allocations - before, 1);
  delete v;
}

}  // namespace
