// Recordings that cannot say how hard or when the pen touches: a pressure axis without its range
// line (libevemu then gives it 0..1, so every touch read as the full 4 N) and a device without
// the pen tool and touch keys. Both are refused with one line naming the file and what was
// expected; the shipped recordings still load.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "inputs/tablet_source.hpp"
#include "core/input_error.hpp"
#include "tests/support/run_process.hpp"
#include "tests/support/text_and_paths.hpp"

using namespace palprig;
using palprig::test_support::palprig_bin;
using palprig::test_support::run_process;

namespace {

std::string refusal(const std::string& file) {
  try {
    (void)read_pen_recording(file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

void expect_one_line_exit_two(const std::string& file, const std::string& expected) {
  const auto r = run_process(palprig_bin() + " run --scene " + std::string(PALPRIG_SOURCE_DIR) +
                             "/data/scenes/phantom_abc.json --input tablet:" + file);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("palprig: " + expected, 0), 0u) << r.err;
}

}  // namespace

TEST(TabletRecordingRefusals, APressureAxisWithoutItsRangeLineIsRefused) {
  const std::string f = palprig::testing::evemu_fixture("refused_pressure_without_range.evemu");
  const std::string expected =
      f +
      ": device description: a range line for every pen axis ('A: 18 <min> <max> <fuzz> <flat> "
      "<resolution>'), got none for ABS_PRESSURE";
  EXPECT_EQ(refusal(f), expected);
  expect_one_line_exit_two(f, expected);
}

TEST(TabletRecordingRefusals, ARecordingWithoutPenToolAndTouchKeysIsRefused) {
  const std::string f = palprig::testing::evemu_fixture("refused_no_pen_keys.evemu");
  const std::string expected = f +
                               ": device description: a pen tablet with a pen tool key (BTN_TOOL_PEN, RUBBER, BRUSH, "
                               "PENCIL or AIRBRUSH) and BTN_TOUCH in its 'B: 01' lines, got neither";
  EXPECT_EQ(refusal(f), expected);
  expect_one_line_exit_two(f, expected);
}

TEST(TabletRecordingRefusals, TheShippedRecordingsStillLoadWithTheirPressureRange) {
  const PenRecording r = read_pen_recording(palprig::testing::evemu_fixture("pen_stroke.evemu"));
  EXPECT_EQ(r.axes.pressure_min, 0);
  EXPECT_EQ(r.axes.pressure_max, 4095);
  EXPECT_NO_THROW(read_pen_recording(palprig::testing::evemu_fixture("pen_syn_dropped.evemu")));
}
