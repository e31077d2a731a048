// Recorded inputs that would replay for ever or lie about the pen: traces with epoch or huge
// times, long gaps, hex floats; evemu recordings with a bad event line, long gaps, or no
// pressure axis. Each is refused with one line of palprig's own (exit 2 from the command line),
// or runs when the run's length is given explicitly.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "inputs/input_source.hpp"
#include "inputs/tablet_source.hpp"
#include "core/input_error.hpp"
#include "tests/support/run_process.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/text_and_paths.hpp"

using namespace palprig;
using palprig::test_support::palprig_bin;
using palprig::test_support::run_process;
using palprig::test_support::TempDir;

namespace {

template <class F>
std::string refusal(F&& load) {
  try {
    load();
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

std::string data(const std::string& rel) { return std::string(PALPRIG_SOURCE_DIR) + "/data/" + rel; }

// The shipped stroke recording with its event lines passed through `edit`.
std::string edited_recording(const std::function<std::string(const std::string&, int)>& edit) {
  std::ifstream in(palprig::testing::evemu_fixture("pen_stroke.evemu"));
  std::string line, out;
  int event = 0;
  while (std::getline(in, line)) out += (line.rfind("E:", 0) == 0 ? edit(line, event++) : line) + "\n";
  return out;
}

std::string run_scene_cmd() { return palprig_bin() + " run --scene " + data("scenes/phantom_abc.json"); }

}  // namespace

TEST(TraceBounds, TimesAreRelativeToTheFirstRow) {
  TempDir dir;
  const auto f = dir.write("epoch.csv",
                           "t_s,x_mm,y_mm,force_N\n1763900000.000,10,10,1\n1763900000.010,11,10,1\n"
                           "1763900000.020,12,10,1\n");
  const auto t = load_trace_csv(f);
  ASSERT_EQ(t.size(), 3u);
  EXPECT_EQ(t[0].t_s, 0.0);
  EXPECT_NEAR(t[2].t_s, 0.02, 1e-6);
  EXPECT_NEAR(TraceInput(t, "epoch").duration_s(), 0.02, 1e-6);
}

TEST(TraceBounds, HugeTimesAndLongGapsAreRefused) {
  TempDir dir;
  const auto huge = dir.write("huge.csv", "t_s,x_mm,y_mm,force_N\n0,10,10,1\n0.01,11,10,1\n1e300,12,10,1\n");
  EXPECT_EQ(
      refusal([&] {
        load_trace_csv(huge, 0.05, TraceLimits{3600, 1e308});
      }),
      huge.string() + ": line 4, t_s: a trace at most 3600 s long (times count from the first row, 0 s), got 1e+300 s");
  EXPECT_EQ(refusal([&] { load_trace_csv(huge); }),
            huge.string() + ": line 4, t_s: rows at most 0.1 s apart (the stale-input limit), got a gap of 1e+300 s");
  const auto gap = dir.write("gap.csv", "t_s,x_mm,y_mm,force_N\n0,10,10,1\n0.05,11,10,1\n5.05,12,10,1\n");
  EXPECT_EQ(refusal([&] { load_trace_csv(gap); }),
            gap.string() + ": line 4, t_s: rows at most 0.1 s apart (the stale-input limit), got a gap of 5 s");
  EXPECT_NO_THROW(load_trace_csv(gap, 0.05, TraceLimits::unbounded()));
}

TEST(TraceBounds, HexAndOtherNonDecimalNumbersAreRefused) {
  TempDir dir;
  const auto hex = dir.write("hex.csv", "t_s,x_mm,y_mm,force_N\n0,10,10,1\n0.01,0x1p-2,10,1\n");
  EXPECT_EQ(refusal([&] { load_trace_csv(hex); }), hex.string() + ": line 3, x_mm: a finite number, got '0x1p-2'");
  const auto inf = dir.write("inf.csv", "t_s,x_mm,y_mm,force_N\n0,10,10,1\n0.01,10,infinity,1\n");
  EXPECT_EQ(refusal([&] { load_trace_csv(inf); }), inf.string() + ": line 3, y_mm: a finite number, got 'infinity'");
}

TEST(TraceBounds, CommandLineRefusesARunawayTraceAndRunsItWithAnExplicitDuration) {
  TempDir dir;
  const auto trace = dir.write("long.csv", "t_s,x_mm,y_mm,force_N\n0,110,50,1\n0.01,110,50,1\n1e9,110,50,1\n");
  const auto tel = dir.path() / "tel.bin";
  auto r = run_process(run_scene_cmd() + " --input trace:" + trace.string() + " --telemetry " + tel.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "palprig: " + trace.string() +
                       ": line 4, t_s: rows at most 0.1 s apart (the stale-input limit), got a gap of 1e+09 s; give "
                       "--duration-s to run it anyway\n");
  EXPECT_FALSE(std::filesystem::exists(tel));  // nothing started
  r = run_process(run_scene_cmd() + " --input trace:" + trace.string() + " --duration-s 0.5 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["ticks"], 500);
}

TEST(RecordingBounds, AMalformedEventLineIsRefusedWithItsLineNotEndedSilently) {
  TempDir dir;
  const auto f = dir.write("bad.evemu", edited_recording([](const std::string& l, int i) {
                             return i == 40 ? std::string("E: 0.2x0000 0003 0000 5100") : l;
                           }));
  const std::string why = refusal([&] { read_pen_recording(f); });
  EXPECT_NE(why.find(f.string() + ": line "), std::string::npos) << why;
  EXPECT_NE(why.find("an event line 'E: <sec>.<usec> <type hex> <code hex> <value>', got 'E: 0.2x0000"),
            std::string::npos)
      << why;
  // From the command line: exit 2 and exactly one line, palprig's own (libevemu prints nothing).
  const auto r = run_process(run_scene_cmd() + " --input tablet:" + f.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("palprig: " + f.string() + ": line ", 0), 0u) << r.err;
}

TEST(RecordingBounds, ABadDescriptionIsOneLineOfPalprigsOwn) {
  TempDir dir;
  const auto f = dir.write("junk.evemu", "N: pen\nI: zz\nB: 03 03\nE: 0.000000 0003 0000 5000\n");
  const auto r = run_process(run_scene_cmd() + " --input tablet:" + f.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("palprig: " + f.string() + ": ", 0), 0u) << r.err;
}

TEST(RecordingBounds, ARecordingWithoutPressureIsRefused) {
  TempDir dir;
  // No A: line for ABS_PRESSURE (0x18) and its bit cleared: every touch would read as full force.
  std::string text = edited_recording([](const std::string& l, int) { return l; });
  text.replace(text.find("A: 18 0 4095 0 0 0\n"), 19, "");
  text.replace(text.find("B: 03 03 00 00 0f"), 17, "B: 03 03 00 00 0e");
  const auto f = dir.write("nopressure.evemu", text);
  EXPECT_NE(refusal([&] { read_pen_recording(f); }).find("device description: a pen tablet with a pressure axis"),
            std::string::npos);
  // Axis declared, but the touches never report a pressure.
  const auto g = dir.write("silent.evemu", edited_recording([](const std::string& l, int) {
                             return l.find(" 0003 0018 ") != std::string::npos ? std::string("# dropped") : l;
                           }));
  EXPECT_EQ(refusal([&] { read_pen_recording(g); }),
            g.string() + ": events: touches that report their pressure (ABS_PRESSURE events), got none");
}

TEST(RecordingBounds, LongGapsAreRefusedUnlessTheRunLengthIsGiven) {
  TempDir dir;
  // The last events jump 2 days ahead (a clock jump): replayed, the run would last two days.
  const auto f = dir.write("jump.evemu", edited_recording([](const std::string& l, int i) {
                             if (i < 150) return l;
                             std::istringstream s(l.substr(2));
                             double t;
                             std::string rest;
                             s >> t;
                             std::getline(s, rest);
                             char buf[64];
                             std::snprintf(buf, sizeof buf, "E: %.6f", t + 172800.0);
                             return std::string(buf) + rest;
                           }));
  const std::string why = refusal([&] { read_pen_recording(f); });
  EXPECT_NE(why.find("events at most 30 s apart, got a gap of 172800"), std::string::npos) << why;
  EXPECT_NO_THROW(read_pen_recording(f, PenRecordingLimits::unbounded()));
  const auto r = run_process(run_scene_cmd() + " --input tablet:" + f.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("; give --duration-s to run it anyway"), std::string::npos) << r.err;
}

TEST(RecordingBounds, TheShippedRecordingsStillLoad) {
  EXPECT_EQ(read_pen_recording(palprig::testing::evemu_fixture("pen_stroke.evemu")).events.size() > 100, true);
  EXPECT_NO_THROW(read_pen_recording(palprig::testing::evemu_fixture("pen_syn_dropped.evemu")));
}
