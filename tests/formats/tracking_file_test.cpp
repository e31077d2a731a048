// The tracking file and the rig file's load cells: what they hold, and every bad
// field refused with one line naming the file, the field and what was expected.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "formats/rig_file.hpp"
#include "formats/tracking_file.hpp"
#include "core/input_error.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig;
using palprig::test_support::TempDir;

namespace {

const std::filesystem::path kTrackingData = std::filesystem::path(PALPRIG_SOURCE_DIR) / "data";

std::string refusal(const std::string& json, const std::string& name = "t.json") {
  TempDir dir;
  const auto p = dir.write(name, json);
  try {
    (void)load_tracking_file(p);
  } catch (const InputError& e) {
    std::string what = e.what();
    const auto at = what.find(name);
    return at == std::string::npos ? what : what.substr(at);
  }
  return "accepted";
}

std::string rig_refusal(const std::string& json) {
  TempDir dir;
  const auto p = dir.write("r.json", json);
  try {
    (void)load_rig_file(p);
  } catch (const InputError& e) {
    std::string what = e.what();
    return what.substr(what.find("r.json"));
  }
  return "accepted";
}

const std::string kTools =
    R"("tools": [{"name": "Finger1ToTracker", "finger": 1}, {"name": "Finger2ToTracker", "finger": 2}])";

}  // namespace

TEST(TrackingFile, ShippedFilesLoad) {
  const TrackingConfig t = load_tracking_file(kTrackingData / "tracking" / "tracking_three_fingers.json");
  EXPECT_EQ(t.placement, TrackedPlacement::per_finger);
  ASSERT_EQ(t.tools.size(), 3u);
  EXPECT_EQ(t.tools[2].name, "Finger3ToTracker");
  EXPECT_EQ(t.tools[2].finger, 2);
  EXPECT_DOUBLE_EQ(t.tools[0].tip.offset_mm[2], -12);
  EXPECT_EQ(t.tools[0].tip.method, "pivot");
  EXPECT_NEAR(t.registration.tracker_to_scene.rotation[2][2], -1, 1e-12);
  EXPECT_EQ(t.tool_for_finger(1)->name, "Finger2ToTracker");
  const TrackingConfig s = load_tracking_file(kTrackingData / "tracking" / "tracking_stylus.json");
  EXPECT_EQ(s.placement, TrackedPlacement::triangle);
  EXPECT_EQ(s.tools[0].finger, 0);
  EXPECT_EQ(s.registration.fiducials, 0);
  const RigConfig rig = load_rig_file(kTrackingData / "rigs" / "simulated_load_cells.json");
  ASSERT_TRUE(rig.load_cells.has_value());
  EXPECT_TRUE(rig.load_cells->per_finger);
  EXPECT_EQ(rig.load_cells->channels.size(), 3u);
  EXPECT_DOUBLE_EQ(rig.load_cells->simulated.stiffness_N_per_mm, 0.5);
}

TEST(TrackingFile, WrittenFilesReadBackTheSame) {
  TempDir dir;
  TrackingConfig t = load_tracking_file(kTrackingData / "tracking" / "tracking_three_fingers.json");
  t.tools[1].tip = {{1.25, -2.5, -11.75}, "digitized", std::nan("")};
  t.tools[0].tip.rms_mm = 0.31;
  t.registration.fre_mm = 0.42;
  t.registration.fiducials = 4;
  write_tracking_file(dir.path() / "out.json", t);
  const TrackingConfig back = load_tracking_file(dir.path() / "out.json");
  EXPECT_EQ(back.tools[1].tip.method, "digitized");
  EXPECT_DOUBLE_EQ(back.tools[1].tip.offset_mm[0], 1.25);
  EXPECT_DOUBLE_EQ(back.tools[0].tip.rms_mm, 0.31);
  EXPECT_DOUBLE_EQ(back.registration.fre_mm, 0.42);
  EXPECT_EQ(back.registration.fiducials, 4);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      EXPECT_DOUBLE_EQ(back.registration.tracker_to_scene.rotation[r][c],
                       t.registration.tracker_to_scene.rotation[r][c]);
}

TEST(TrackingFile, RefusesEachBadFieldInOneLine) {
  const std::string ok = R"({"version": 1, "placement": "per_finger", )" + kTools + "}";
  EXPECT_EQ(refusal(ok), "accepted");
  EXPECT_EQ(refusal(R"({"placement": "per_finger", )" + kTools + "}"), "t.json: version: a value (field is missing)");
  EXPECT_EQ(refusal(R"({"version": 1, "placement": "hand", )" + kTools + "}"),
            "t.json: placement: one of \"triangle\", \"per_finger\", got \"hand\"");
  EXPECT_EQ(refusal(R"({"version": 1, "placement": "triangle", )" + kTools + "}"),
            "t.json: tools: one tool with placement \"triangle\" (the fingers stand around it), got 2");
  EXPECT_EQ(refusal(R"({"version": 1, "placement": "per_finger", "tools": []})"), "t.json: tools: 1 to 3 tools, got 0");
  EXPECT_EQ(
      refusal(
          R"({"version": 1, "placement": "per_finger", "tools": [{"name": "A", "finger": 1}, {"name": "B", "finger": 1}]})"),
      "t.json: tools[1].finger: a finger no other tool has, got 1 twice");
  EXPECT_EQ(refusal(R"({"version": 1, "placement": "per_finger", "tools": [{"name": "A", "finger": 4}]})"),
            "t.json: tools[0].finger: an integer in 1..3, got 4");
  EXPECT_EQ(
      refusal(
          R"({"version": 1, "placement": "per_finger", "tools": [{"name": "A", "finger": 1}, {"name": "A", "finger": 2}]})"),
      "t.json: tools[1].name: a name no other tool has, got 'A' twice");
  EXPECT_EQ(
      refusal(R"({"version": 1, "placement": "triangle", "tools": [{"name": "AVeryLongToolNameOver20"}]})"),
      "t.json: tools[0].name: an OpenIGTLink device name of 1 to 20 characters, got 'AVeryLongToolNameOver20' (23)");
  EXPECT_EQ(refusal(R"({"version": 1, "placement": "triangle", "tools": [{"name": "a b"}]})"),
            "t.json: tools[0].name: printable ASCII without spaces, got 'a b'");
  EXPECT_EQ(
      refusal(R"({"version": 1, "placement": "triangle", "tools": [{"name": "S", "tip": {"offset_mm": [0, 0]}}]})"),
      "t.json: tools[0].tip.offset_mm: 3 numbers [x, y, z] in mm, got 2");
  EXPECT_EQ(
      refusal(
          R"({"version": 1, "placement": "triangle", "tools": [{"name": "S", "tip": {"offset_mm": [0, 0, 1], "method": "guess"}}]})"),
      "t.json: tools[0].tip.method: one of \"pivot\", \"digitized\", \"measured\", got \"guess\"");
  EXPECT_EQ(refusal(R"({"version": 1, "placement": "triangle", "tools": [{"name": "S"}],
                        "tracker_to_scene": {"rotation": [[1, 0, 0], [0, 1, 0], [0, 0, -1]], "translation_mm": [0, 0, 0]}})"),
            "t.json: tracker_to_scene.rotation: a rotation (orthonormal rows, determinant +1, to 0.001), got "
            "[[1, 0, 0], [0, 1, 0], [0, 0, -1]] (a scale or a mirror is not a rigid registration)");
  EXPECT_EQ(
      refusal(R"({"version": 1, "placement": "triangle", "tools": [{"name": "S"}],
                        "tracker_to_scene": {"rotation": [[1, 0], [0, 1]], "translation_mm": [0, 0, 0]}})"),
      "t.json: tracker_to_scene.rotation: a 3 x 3 rotation matrix [[r11, r12, r13], [r21, r22, r23], [r31, r32, r33]], "
      "got [[1, 0], [0, 1]]");
  EXPECT_EQ(refusal(R"({"version": 1, "placement": "triangle", "tools": [{"name": "S", "colour": "red"}]})"),
            "t.json: tools[0].colour: no such field here (unknown field; check its spelling)");
}

TEST(RigLoadCells, HardwareInputsAreCheckedAgainstTheRegulatorsOwn) {
  // The shipped comedi rig: its monitors use AI 0..2, so a load cell on AI 4 is accepted and one
  // on AI 1 is refused; the WAGO module's monitors use input registers 0..2.
  auto with_cells = [](const std::string& rig_file, const std::string& cells) {
    TempDir dir;
    std::ifstream in(kTrackingData / "rigs" / rig_file);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    text.replace(text.rfind('}'), 1, ",\"load_cells\": " + cells + "}");
    try {
      const RigConfig rig = load_rig_file(dir.write("r.json", text));
      return std::string("accepted ") + std::to_string(rig.load_cells->channels.size());
    } catch (const InputError& e) {
      const std::string w = e.what();
      return w.substr(w.find("r.json"));
    }
  };
  const std::string comedi =
      R"({"fingers": "all", "channels": [{"N_per_V": 2, "input": {"channel": %, "volts_span": [0, 5]}}]})";
  auto on = [&](int ch) {
    std::string c = comedi;
    c.replace(c.find('%'), 1, std::to_string(ch));
    return with_cells("ni_pcie_6259_comedi.json", c);
  };
  EXPECT_EQ(on(4), "accepted 1");
  EXPECT_EQ(on(1), "r.json: load_cells.channels[0].input.channel: an analog input no regulator monitor uses, got 1");
  EXPECT_EQ(with_cells(
                "wago_750_559.json",
                R"({"fingers": "all", "channels": [{"N_per_V": 2, "input": {"register": 3, "volts_span": [0, 10]}}]})"),
            "accepted 1");
  EXPECT_EQ(with_cells(
                "wago_750_559.json",
                R"({"fingers": "all", "channels": [{"N_per_V": 2, "input": {"register": 2, "volts_span": [0, 10]}}]})"),
            "r.json: load_cells.channels[0].input.register: a register no regulator monitor reads, got 2");
  EXPECT_EQ(
      with_cells("wago_750_559.json", R"({"fingers": "all", "channels": [{"N_per_V": 2}]})"),
      "r.json: load_cells.channels[0].input: the register the cell is read on: {\"register\": N, \"volts_span\": [low, "
      "high], ...}");
  EXPECT_EQ(
      with_cells("wago_750_559.json",
                 R"({"fingers": "all", "channels": [{"N_per_V": 2, "input": {"register": 3, "volts_span": [0, 10]}}],
                           "simulated": {"stiffness_N_per_mm": 1}})"),
      "r.json: load_cells.simulated: nothing on a \"modbus\" rig (its cells are real)");
}

TEST(RigLoadCells, RefusesEachBadFieldInOneLine) {
  const std::string head = R"({"version": 1, "id": "r", "backend": "simulated", "load_cells": )";
  EXPECT_EQ(rig_refusal(head + R"({"fingers": "each", "channels": [{"N_per_V": 2}, {"N_per_V": 2}, {"N_per_V": 2}]}})"),
            "accepted");
  EXPECT_EQ(rig_refusal(head + R"({"fingers": "each", "channels": [{"N_per_V": 2}]}})"),
            "r.json: load_cells.channels: 3 channels with \"fingers\": \"each\", got 1");
  EXPECT_EQ(rig_refusal(head + R"({"fingers": "all", "channels": [{"N_per_V": 0}]}})"),
            "r.json: load_cells.channels[0].N_per_V: a number in 1e-09..1e+09, got 0");
  EXPECT_EQ(rig_refusal(head + R"({"fingers": "some", "channels": [{"N_per_V": 1}]}})"),
            "r.json: load_cells.fingers: one of \"each\", \"all\", got \"some\"");
  EXPECT_EQ(rig_refusal(head + R"({"fingers": "all", "channels": [{"N_per_V": 1, "input": {"channel": 3}}]}})"),
            "r.json: load_cells.channels[0].input: no input on the simulated rig (its cells are in \"simulated\")");
  EXPECT_EQ(rig_refusal(head + R"({"fingers": "all", "channels": [{"N_per_V": 1}], "simulated": {"tare_V": 20}}})"),
            "r.json: load_cells.simulated.tare_V: below max_V (10.000000 V)");
}
