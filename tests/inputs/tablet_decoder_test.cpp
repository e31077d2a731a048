// Pen tablet decoding over the evemu recordings the project ships (read with libevemu): mm from
// the device resolution, newtons from the pressure curve, lift-off, proximity out, and the
// SYN_DROPPED resynchronisation.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "formats/json_file.hpp"
#include "inputs/tablet_decoder.hpp"
#include "inputs/tablet_source.hpp"
#include "core/input_error.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/text_and_paths.hpp"

using namespace palprig;

namespace {

const PenFrame& frame_at(const std::vector<PenFrame>& frames, double t_s) {
  for (const auto& f : frames)
    if (std::fabs(f.t_s - t_s) < 1e-6) return f;
  throw std::runtime_error("no frame at t=" + std::to_string(t_s));
}

input_event ev(double t, int type, int code, int value) {
  input_event e{};
  e.input_event_sec = static_cast<decltype(e.input_event_sec)>(t);
  e.input_event_usec = static_cast<decltype(e.input_event_usec)>(std::lround((t - std::floor(t)) * 1e6));
  e.type = static_cast<__u16>(type);
  e.code = static_cast<__u16>(code);
  e.value = value;
  return e;
}

}  // namespace

TEST(TabletRecording, ReadsTheDeviceDescription) {
  const PenRecording r = read_pen_recording(palprig::testing::evemu_fixture("pen_stroke.evemu"));
  EXPECT_EQ(r.device_name, "Wacom Intuos S Pen");
  EXPECT_EQ(r.axes.x_max, 15200);
  EXPECT_EQ(r.axes.x_resolution, 100);
  EXPECT_EQ(r.axes.y_max, 9500);
  EXPECT_EQ(r.axes.pressure_max, 4095);
  EXPECT_TRUE(r.axes.has_touch_key);
  EXPECT_GT(r.events.size(), 400u);
}

TEST(TabletRecording, RefusesFilesThatAreNotPenRecordings) {
  palprig::test_support::TempDir dir;
  EXPECT_THROW(read_pen_recording(dir.write("x.evemu", "hello\n")), InputError);
  EXPECT_THROW(read_pen_recording(dir.path() / "absent.evemu"), InputError);
  // A device description without ABS_PRESSURE (a mouse, say).
  std::string text = palprig::test_support::read_file(palprig::testing::evemu_fixture("pen_stroke.evemu"));
  const auto at = text.find("A: 18 0 4095");
  text.replace(text.find("B: 03 03 00 00 0f"), 17, "B: 03 03 00 00 00");
  text.erase(at, text.find('\n', at) - at + 1);
  EXPECT_THROW(read_pen_recording(dir.write("mouse.evemu", text)), InputError);
}

TEST(TabletDecoder, StrokeInMillimetresAndNewtons) {
  const PenRecording r = read_pen_recording(palprig::testing::evemu_fixture("pen_stroke.evemu"));
  const auto frames = decode_pen_events(r.axes, TabletConfig{}, r.events);
  // Hovering: in proximity, no contact, no force; 5000 units at 100 units/mm = 50 mm.
  const PenFrame& hover = frame_at(frames, 0.0);
  EXPECT_TRUE(hover.in_proximity);
  EXPECT_FALSE(hover.in_contact);
  EXPECT_EQ(hover.force_N, 0.0);
  EXPECT_DOUBLE_EQ(hover.x_mm, 50.0);
  EXPECT_DOUBLE_EQ(hover.y_mm, 90.0);
  // Pressing at 3072/4095 of full pressure; default curve 4 N at full pressure.
  const PenFrame& press = frame_at(frames, 0.4);
  EXPECT_TRUE(press.in_contact);
  EXPECT_NEAR(press.force_N, 3072.0 / 4095.0 * 4.0, 1e-12);
  EXPECT_DOUBLE_EQ(press.x_mm, 74.0);               // 5000 + 4000 * 0.3/0.5 = 7400 units
  EXPECT_TRUE(frame_at(frames, 0.105).in_contact);  // first report with BTN_TOUCH down
}

TEST(TabletDecoder, LiftOffAndProximityOutPressWithZeroNewtons) {
  const PenRecording r = read_pen_recording(palprig::testing::evemu_fixture("pen_stroke.evemu"));
  const auto frames = decode_pen_events(r.axes, TabletConfig{}, r.events);
  const PenFrame& lift = frame_at(frames, 0.65);
  EXPECT_FALSE(lift.in_contact);
  EXPECT_TRUE(lift.in_proximity);
  EXPECT_EQ(lift.force_N, 0.0);
  const PenFrame& out = frame_at(frames, 0.75);
  EXPECT_FALSE(out.in_proximity);
  EXPECT_FALSE(out.in_contact);
  EXPECT_EQ(out.force_N, 0.0);
  for (const auto& f : frames) {
    if (f.t_s >= 0.65) {
      EXPECT_FALSE(f.in_contact) << "contact after lift-off at t=" << f.t_s;
    }
  }
  const PenFrame& back = frame_at(frames, 0.95);
  EXPECT_TRUE(back.in_proximity);
  EXPECT_FALSE(back.in_contact);
}

TEST(TabletDecoder, OriginAndPressureCurveFromTheRigFile) {
  const PenRecording r = read_pen_recording(palprig::testing::evemu_fixture("pen_stroke.evemu"));
  TabletConfig cfg;
  cfg.origin_mm = {10.0, 5.0};
  cfg.pressure.points = {{0.0, 0.0}, {0.5, 1.0}, {1.0, 5.0}};
  const std::vector<PenFrame> frames = decode_pen_events(r.axes, cfg, r.events);  // keep them alive
  const PenFrame& press = frame_at(frames, 0.4);
  EXPECT_DOUBLE_EQ(press.x_mm, 64.0);
  EXPECT_DOUBLE_EQ(press.y_mm, 85.0);
  const double p = 3072.0 / 4095.0;  // on the second segment: 1 N at 0.5, 5 N at 1
  EXPECT_NEAR(press.force_N, 1.0 + (p - 0.5) / 0.5 * 4.0, 1e-12);
}

TEST(TabletDecoder, SynDroppedDiscardsTheLostReportAndReportsLiftedUntilResynced) {
  const PenRecording r = read_pen_recording(palprig::testing::evemu_fixture("pen_syn_dropped.evemu"));
  const auto frames = decode_pen_events(r.axes, TabletConfig{}, r.events);
  const PenFrame& before = frame_at(frames, 0.295);
  EXPECT_TRUE(before.in_contact);
  EXPECT_NEAR(before.force_N, 2048.0 / 4095.0 * 4.0, 1e-12);
  // The frame that closes the lost report, and the reports where Y and pressure are still
  // unknown: lifted, not synced, no force; never the lost 4000.
  for (double t : {0.300, 0.305, 0.310, 0.315, 0.320}) {
    const PenFrame& f = frame_at(frames, t);
    EXPECT_FALSE(f.synced) << t;
    EXPECT_FALSE(f.in_contact) << t;
    EXPECT_EQ(f.force_N, 0.0) << t;
  }
  // X, Y and pressure all re-reported by 0.325 s: the press resumes with what was reported.
  const PenFrame& after = frame_at(frames, 0.325);
  EXPECT_TRUE(after.synced);
  EXPECT_TRUE(after.in_contact);
  EXPECT_NEAR(after.force_N, 2986.0 / 4095.0 * 4.0, 1e-12);
  EXPECT_DOUBLE_EQ(after.x_mm, 63.19);
  EXPECT_DOUBLE_EQ(after.y_mm, 40.03);
  for (const auto& f : frames) EXPECT_LT(f.force_N, 3.0) << "the lost pressure surfaced at t=" << f.t_s;
}

TEST(TabletDecoder, ResyncFromTheDeviceStateEndsTheUnknownAtOnce) {
  const PenRecording r = read_pen_recording(palprig::testing::evemu_fixture("pen_syn_dropped.evemu"));
  TabletDecoder d(r.axes, TabletConfig{});
  d.feed(ev(0.0, EV_SYN, SYN_DROPPED, 0));
  d.feed(ev(0.0, EV_ABS, ABS_PRESSURE, 4000));
  EXPECT_TRUE(d.feed(ev(0.0, EV_SYN, SYN_REPORT, 0)));
  EXPECT_FALSE(d.synced());
  // What libevdev reports after its own resynchronisation (EVIOCGABS/EVIOCGKEY).
  d.resync(PenState{7000, 4100, 1024, true, true}, 0.01);
  EXPECT_TRUE(d.synced());
  EXPECT_TRUE(d.frame().in_contact);
  EXPECT_DOUBLE_EQ(d.frame().x_mm, 70.0);
  EXPECT_NEAR(d.frame().force_N, 1024.0 / 4095.0 * 4.0, 1e-12);
}

TEST(TabletDecoder, DeviceWithoutTouchKeyTouchesOnPressure) {
  TabletAxes axes{0, 1000, 10, 0, 1000, 10, 0, 255, false};
  TabletDecoder d(axes, TabletConfig{});
  d.feed(ev(0, EV_KEY, BTN_TOOL_PEN, 1));
  d.feed(ev(0, EV_ABS, ABS_PRESSURE, 0));
  d.feed(ev(0, EV_SYN, SYN_REPORT, 0));
  EXPECT_FALSE(d.frame().in_contact);
  d.feed(ev(0.01, EV_ABS, ABS_PRESSURE, 51));
  d.feed(ev(0.01, EV_SYN, SYN_REPORT, 0));
  EXPECT_TRUE(d.frame().in_contact);
  EXPECT_NEAR(d.frame().force_N, 51.0 / 255.0 * 4.0, 1e-12);
}

TEST(TabletDecoder, NeedsAResolutionOrASizeInMillimetres) {
  TabletAxes axes{0, 1000, 0, 0, 800, 0, 0, 255, true};
  EXPECT_THROW(TabletDecoder(axes, TabletConfig{}), palprig::BadInput);
  TabletConfig cfg;
  cfg.size_mm = {100.0, 80.0};
  TabletDecoder d(axes, cfg);
  d.feed(ev(0, EV_KEY, BTN_TOOL_PEN, 1));
  d.feed(ev(0, EV_ABS, ABS_X, 500));
  d.feed(ev(0, EV_ABS, ABS_Y, 400));
  d.feed(ev(0, EV_SYN, SYN_REPORT, 0));
  EXPECT_DOUBLE_EQ(d.frame().x_mm, 50.0);
  EXPECT_DOUBLE_EQ(d.frame().y_mm, 40.0);
}

TEST(TabletConfigFile, PressureCurveMustRiseFromZeroToOne) {
  palprig::test_support::TempDir dir;
  auto parse = [&](const std::string& curve) {
    const nlohmann::json doc = nlohmann::json::parse("{\"pressure_curve_N\": " + curve + "}");
    return parse_tablet_config(JsonObject(doc, "rig.json", "tablet"));
  };
  EXPECT_NEAR(parse("[[0, 0], [0.25, 0.5], [1, 4]]").pressure.force_N(0.625), 0.5 + 0.375 / 0.75 * 3.5, 1e-12);
  EXPECT_THROW(parse("[[0.1, 0], [1, 4]]"), InputError);
  EXPECT_THROW(parse("[[0, 0], [0.5, 2], [0.5, 3], [1, 4]]"), InputError);
  EXPECT_THROW(parse("[[0, 2], [1, 1]]"), InputError);
  EXPECT_THROW(parse("[[0, 0]]"), InputError);
}

TEST(TabletConfigFile, ReaderPriorityDefaultsBelowTheLoopAndIsChecked) {
  auto parse = [&](const std::string& body) {
    const nlohmann::json doc = nlohmann::json::parse(body);
    return parse_tablet_config(JsonObject(doc, "rig.json", "tablet"));
  };
  EXPECT_EQ(parse("{}").reader_fifo_priority, 60);  // loop 80 > bus thread 70 > reader 60
  EXPECT_EQ(parse("{\"reader_fifo_priority\": 0}").reader_fifo_priority, 0);
  try {
    parse("{\"reader_fifo_priority\": 99}");
    FAIL() << "99 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("reader_fifo_priority"), std::string::npos) << e.what();
  }
}
