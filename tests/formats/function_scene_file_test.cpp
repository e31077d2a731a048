// Function scene files: the shipped scenes load (and the map scene still does), the phantom's
// tumors match paper 002's map, generated cases round-trip through the file, and bad scenes and
// waveform tables are refused with the file, the field and the reason.
#include <cmath>
#include <functional>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "formats/function_scene_file.hpp"
#include "formats/scene_file.hpp"
#include "models/case_generator.hpp"
#include "core/input_error.hpp"
#include "models/tissue_scene.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig;
using palprig::test_support::TempDir;

namespace {

const std::string kScenes = std::string(PALPRIG_SOURCE_DIR) + "/data/scenes/";

nlohmann::json brachial() {
  std::ifstream in(kScenes + "brachial_pulse.json");
  nlohmann::json j = nlohmann::json::parse(in);
  // Keep the test independent of the table's location.
  j["arteries"][0]["waveform"] = {{"shape", "rectangular"}, {"duty", 0.2}};
  return j;
}

}  // namespace

TEST(FunctionSceneFile, ShippedScenesLoad) {
  for (const char* name : {"phantom_abc_function", "liver_edge", "groin_femoral", "brachial_pulse"}) {
    SCOPED_TRACE(name);
    const SceneFile sf = load_scene_file(kScenes + name + std::string(".json"));
    ASSERT_NE(dynamic_cast<const FunctionScene*>(sf.scene.get()), nullptr);
    EXPECT_EQ(sf.name, name);
  }
  EXPECT_NE(load_scene_file(kScenes + "groin_femoral.json").scene->pulse(), nullptr);
  EXPECT_NE(load_scene_file(kScenes + "brachial_pulse.json").scene->pulse(), nullptr);
  EXPECT_EQ(load_scene_file(kScenes + "liver_edge.json").scene->pulse(), nullptr);
  const SceneFile brachial = load_scene_file(kScenes + "brachial_pulse.json");
  EXPECT_EQ(brachial.scene->pulse()->artery(0).spec().waveform.shape(), WaveShape::table);
  EXPECT_TRUE(brachial.scene->pulse()->artery(0).spec().own_force_window);
}

TEST(FunctionSceneFile, ALayersDragIsReadAndTheShippedLiverSkinDrags) {
  const SceneFile liver = load_scene_file(kScenes + "liver_edge.json");
  const DragSetting skin = liver.scene->drag(0);
  EXPECT_EQ(skin.f_stick_N, 1.0);
  EXPECT_EQ(skin.d_lat_max_mm, 20.0);
  EXPECT_EQ(skin.relax_s, 0.1);
  EXPECT_EQ(liver.scene->drag(2).d_lat_max_mm, 20.0);  // pressed into the muscle: the skin's, carried along
  EXPECT_FALSE(load_scene_file(kScenes + "brachial_pulse.json").scene->drag(0).drags());
  TempDir dir;
  nlohmann::json j = brachial();
  j["layers"][0]["drag"] = {{"f_stick_N", 0.8}, {"d_lat_max_mm", 30}};
  const SceneFile sf = load_scene_file(dir.write("s.json", j.dump()));
  EXPECT_EQ(sf.scene->drag(0).relax_s, 0.05);  // the default
}

TEST(FunctionSceneFile, AnArteryMayLeaveItsForceWindowToCalibration) {
  TempDir dir;
  nlohmann::json j = brachial();
  j["arteries"][0].erase("force_window_N");
  const SceneFile sf = load_scene_file(dir.write("s.json", j.dump()));
  EXPECT_FALSE(sf.scene->pulse()->artery(0).spec().own_force_window);
  EXPECT_EQ(sf.scene->pulse()->artery(0).spec().force_window.min_N, 1.2);  // 60 mmHg over 1.5 cm^2 until calibrated
}

TEST(FunctionSceneFile, MapScenesStillLoadAsBefore) {
  const SceneFile sf = load_scene_file(kScenes + "phantom_abc.json");
  EXPECT_NE(dynamic_cast<const MapScene*>(sf.scene.get()), nullptr);
  ASSERT_EQ(sf.tumors.size(), 3u);
  EXPECT_EQ(sf.tumors[1].name, "B");
  EXPECT_EQ(sf.tumors[1].radius_mm, 10);
  EXPECT_EQ(sf.scene->pulse(), nullptr);
}

TEST(FunctionSceneFile, PhantomTumorsMatchPaper002sMap) {
  const SceneFile fn = load_scene_file(kScenes + "phantom_abc_function.json");
  const SceneFile map = load_scene_file(kScenes + "phantom_abc.json");
  ASSERT_EQ(fn.tumors.size(), map.tumors.size());
  for (std::size_t i = 0; i < fn.tumors.size(); ++i) {
    EXPECT_EQ(fn.tumors[i].name, map.tumors[i].name);
    EXPECT_NEAR(fn.tumors[i].x_mm, map.tumors[i].x_mm, 0.5);
    EXPECT_NEAR(fn.tumors[i].y_mm, map.tumors[i].y_mm, 0.5);
    EXPECT_NEAR(fn.tumors[i].radius_mm, map.tumors[i].radius_mm, 0.6);
  }
  // At the reference press (2 N): felt in the order of their size (paper 002's sensitivities
  // rise A < C < B), silicone as 0.
  auto felt = [&](double x, double y) { return fn.scene->sample({x, y}, 2.0, 0).stiffness; };
  const double a = felt(40, 40), b = felt(110, 50), c = felt(70, 90);
  EXPECT_GT(b, c);
  EXPECT_GT(c, a);
  EXPECT_GT(a, 0.2);
  EXPECT_GT(b, 0.7);
  EXPECT_EQ(felt(20, 100), 0.0);
}

TEST(FunctionSceneFile, ShippedWaveformTableLoads) {
  const PulseWaveform w = load_waveform_csv(std::string(PALPRIG_SOURCE_DIR) + "/data/waveforms/brachial_pressure.csv");
  EXPECT_EQ(w.shape(), WaveShape::table);
  EXPECT_NEAR(w.recorded_period_s(), 0.8, 1e-9);
  double lo = 1, hi = 0, peak_at = 0;
  for (int i = 0; i < 1000; ++i) {
    const double v = w.value(i / 1000.0);
    lo = std::min(lo, v);
    if (v > hi) hi = v, peak_at = i / 1000.0;
  }
  EXPECT_NEAR(lo, 0, 1e-3);
  EXPECT_NEAR(hi, 1, 5e-3);  // the peak may fall between the probes
  EXPECT_GT(peak_at, 0.1);   // systolic peak early in the beat
  EXPECT_LT(peak_at, 0.25);
}

TEST(FunctionSceneFile, GeneratedCaseRoundTripsThroughTheFile) {
  TempDir dir;
  for (CaseDifficulty d : {CaseDifficulty::easy, CaseDifficulty::medium, CaseDifficulty::hard}) {
    const GeneratedCase c = generate_case(2024, d);
    const auto path = dir.path() / (std::string(to_string(d)) + ".json");
    write_scene_json(path, generated_case_json(c));
    EXPECT_EQ(generated_case_json(generate_case(2024, d)).dump(),
              generated_case_json(c).dump());  // same seed, same file
    const SceneFile sf = load_scene_file(path);
    const FunctionScene direct(case_tissue(c), {});
    ASSERT_EQ(sf.tumors.size(), c.tumors.size());
    for (double x = 5; x < 160; x += 7)
      for (double y = 5; y < 120; y += 7)
        for (double F : {0.5, 2.0})
          ASSERT_EQ(sf.scene->sample({x, y}, F, 0).stiffness, direct.sample({x, y}, F, 0).stiffness);
  }
}

// Each case breaks one thing in a valid scene and names where the refusal must point.
struct BadScene {
  const char* what;
  std::function<void(nlohmann::json&)> spoil;
  const char* field;   // must appear in InputError::where()
  const char* reason;  // must appear in the message
};

TEST(FunctionSceneFile, BadScenesAreRefusedWithFileFieldAndReason) {
  const std::vector<BadScene> cases = {
      {"unknown top-level field", [](auto& j) { j["colour"] = "red"; }, "colour", "unknown field"},
      {"misspelt shape field",
       [](auto& j) { j["inclusions"][0]["shape"]["centre_mmm"] = j["inclusions"][0]["shape"]["centre_mm"]; },
       "inclusions[0].shape.centre_mmm", "unknown field"},
      {"negative radius", [](auto& j) { j["inclusions"][3]["shape"]["of"][0]["radius_mm"] = -2; },
       "inclusions[3].shape.of[0].radius_mm", "positive"},
      {"negative stiffness", [](auto& j) { j["layers"][2]["stiffness_kPa"] = -15; }, "layers[2].stiffness_kPa",
       "positive"},
      {"zero thickness", [](auto& j) { j["layers"][0]["thickness_mm"] = 0; }, "layers[0].thickness_mm", "positive"},
      {"negative body size", [](auto& j) { j["body"]["half_size_mm"][0] = -80; }, "body.half_size_mm[0]", "positive"},
      {"negative radii", [](auto& j) { j["inclusions"][0]["shape"]["radii_mm"][1] = -3; },
       "inclusions[0].shape.radii_mm[1]", "positive"},
      {"rate too high", [](auto& j) { j["arteries"][0]["rate_bpm"] = 300; }, "arteries[0].rate_bpm", "20..250"},
      {"rate too low", [](auto& j) { j["arteries"][0]["rate_bpm"] = 10; }, "arteries[0].rate_bpm", "20..250"},
      {"artery above the skin", [](auto& j) { j["arteries"][0]["depth_mm"] = 1; }, "arteries[0].depth_mm", "radius"},
      {"range that never reaches the skin", [](auto& j) { j["arteries"][0]["range_mm"] = 5; }, "arteries[0].range_mm",
       "larger than the depth"},
      {"bad path point",
       [](auto& j) {
         j["arteries"][0]["path_mm"][1] = {1, 2, 3};
       },
       "arteries[0].path_mm[1]", "[x_mm, y_mm]"},
      {"force window upside down",
       [](auto& j) {
         j["arteries"][0]["force_window_N"] = {3, 1};
       },
       "arteries[0].force_window_N", "F_min < F_max"},
      {"soft not below hard", [](auto& j) { j["felt_range_kPa"]["hard"] = 2; }, "felt_range_kPa.hard", "above soft"},
      {"drag without d_lat_max",
       [](auto& j) {
         j["layers"][0]["drag"] = {{"f_stick_N", 1}};
       },
       "layers[0].drag.d_lat_max_mm", "field is missing"},
      {"negative f_stick",
       [](auto& j) {
         j["layers"][0]["drag"] = {{"f_stick_N", -1}, {"d_lat_max_mm", 20}};
       },
       "layers[0].drag.f_stick_N", "0.01..100"},
      {"stretch beyond 100 mm",
       [](auto& j) {
         j["layers"][1]["drag"] = {{"f_stick_N", 1}, {"d_lat_max_mm", 250}};
       },
       "layers[1].drag.d_lat_max_mm", "0..100"},
      {"misspelt drag key",
       [](auto& j) {
         j["layers"][0]["drag"] = {{"f_stick_N", 1}, {"d_lat_max_mm", 20}, {"relax", 0.1}};
       },
       "layers[0].drag.relax", "unknown field"},
      {"unknown shape type", [](auto& j) { j["inclusions"][0]["shape"]["type"] = "cube"; }, "inclusions[0].shape.type",
       "\"sphere\""},
      {"unknown inclusion kind", [](auto& j) { j["inclusions"][0]["kind"] = "gland"; }, "inclusions[0].kind",
       "\"tumor\""},
      {"unknown waveform",
       [](auto& j) {
         j["arteries"][0]["waveform"] = {{"shape", "sine"}};
       },
       "arteries[0].waveform.shape", "\"rectangular\""},
      {"duty out of range", [](auto& j) { j["arteries"][0]["waveform"]["duty"] = 1.5; }, "arteries[0].waveform.duty",
       "0.01..0.99"},
      {"no layers", [](auto& j) { j["layers"] = nlohmann::json::array(); }, "layers", "at least one"},
      {"missing felt range", [](auto& j) { j.erase("felt_range_kPa"); }, "felt_range_kPa", "missing"},
      {"newer version", [](auto& j) { j["version"] = 99; }, "version", "older"},
      {"unknown kind", [](auto& j) { j["kind"] = "mesh"; }, "kind", "\"function\""},
      {"blob with both sizes",
       [](auto& j) {
         j["inclusions"][0]["shape"] = {
             {"type", "blobs"},
             {"threshold", 0.3},
             {"blobs", {{{"centre_mm", {1, 2, 3}}, {"radii_mm", {1, 1, 1}}, {"inverse_scale_per_mm2", {1, 1, 1}}}}}};
       },
       "inclusions[0].shape.blobs[0].radii_mm", "exactly one"},
  };
  TempDir dir;
  for (const BadScene& c : cases) {
    SCOPED_TRACE(c.what);
    nlohmann::json j = brachial();
    c.spoil(j);
    const auto path = dir.write("bad.json", j.dump(2));
    try {
      load_scene_file(path);
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), path.string());
      EXPECT_NE(e.where().find(c.field), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(c.reason), std::string::npos) << e.what();
    }
  }
  // The unchanged scene loads, so each refusal above is the spoiled field's doing.
  EXPECT_NO_THROW(load_scene_file(dir.write("good.json", brachial().dump())));
}

TEST(FunctionSceneFile, BadWaveformTablesAreRefused) {
  TempDir dir;
  const std::vector<std::pair<std::string, std::string>> tables = {
      {"", "empty"},
      {"# only a comment\nt_s,value\n", "empty"},
      {"t_s,value\n0,80\n0.2,120\n0.4,100\n0.6,95\n", "not periodic"},
      {"0,80\n0.2,120\n0.2,100\n0.6,80\n", "increase"},
      {"0,80\n0.2,abc\n0.4,100\n0.6,80\n", "line 2"},
      {"0,80\n0.2,120\n0.8,80\n", "at least 4"},
  };
  for (const auto& [text, reason] : tables) {
    SCOPED_TRACE(reason);
    const auto csv = dir.write("wave.csv", text);
    nlohmann::json j = brachial();
    j["arteries"][0]["waveform"] = {{"shape", "table"}, {"file", "wave.csv"}};  // relative to the scene file
    const auto scene = dir.write("scene.json", j.dump());
    try {
      load_scene_file(scene);
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), csv.string());
      EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
    }
  }
  const auto missing = dir.path() / "scene2.json";
  nlohmann::json j = brachial();
  j["arteries"][0]["waveform"] = {{"shape", "table"}, {"file", "nowhere.csv"}};
  std::ofstream(missing) << j.dump();
  EXPECT_THROW(load_scene_file(missing), InputError);
}
