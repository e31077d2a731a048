// `palprig scene render|generate|info` and `palprig run` on function scenes, through the real
// program: files written and read back, bad input refused with exit 2 and one clear line.
#include <fstream>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "formats/scene_file.hpp"
#include "models/stiffness_map.hpp"
#include "tests/support/run_process.hpp"
#include "tests/support/text_and_paths.hpp"

using namespace palprig;
using namespace palprig::test_support;

namespace {}  // namespace

TEST(SceneCommand, GenerateIsReproducibleFromTheSeed) {
  TempDir dir;
  const auto a = dir.path() / "a.json", b = dir.path() / "b.json", c = dir.path() / "c.json";
  for (const auto& p : {a, b}) {
    const ProcessResult r =
        run_process(palprig_bin() + " scene generate --seed 77 --difficulty medium --out " + p.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("seed 77, medium"), std::string::npos) << r.out;
  }
  ASSERT_EQ(run_process(palprig_bin() + " scene generate --seed 78 --difficulty medium --out " + c.string()).exit_code,
            0);
  EXPECT_EQ(read_file(a), read_file(b));
  EXPECT_NE(read_file(a), read_file(c));
  const SceneFile sf = load_scene_file(a);
  EXPECT_GE(sf.tumors.size(), 1u);
  const auto j = nlohmann::json::parse(read_file(a));
  EXPECT_EQ(j["generator"]["seed"], 77);
  EXPECT_EQ(j["kind"], "function");
  // The instructor's view lists each tumor.
  const ProcessResult truth =
      run_process(palprig_bin() + " scene generate --seed 77 --difficulty medium --show-truth --out " + c.string());
  ASSERT_EQ(truth.exit_code, 0);
  EXPECT_NE(truth.out.find("T1 at ("), std::string::npos) << truth.out;
}

TEST(SceneCommand, RenderBakesTheFeltStiffnessIntoAMap) {
  TempDir dir;
  const auto pgm = dir.path() / "phantom.pgm";
  const auto map_scene = dir.path() / "phantom_map.json";
  const ProcessResult r = run_process(palprig_bin() + " scene render " +
                                      palprig::testing::shipped_data("scenes/phantom_abc_function.json") + " --out " +
                                      pgm.string() + " --res-mm 2 --map-scene " + map_scene.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("81 x 61 vertices"), std::string::npos) << r.out;
  std::ifstream in(pgm, std::ios::binary);
  const StiffnessMap m = parse_stiffness_pgm(in, pgm.string(), 160, 120);
  ASSERT_EQ(m.cols(), 81u);
  ASSERT_EQ(m.rows(), 61u);
  EXPECT_GT(m.at(55, 25), 0.7);           // tumor B at (110, 50) mm
  EXPECT_LT(m.at(10, 50), 0.01);          // silicone at (20, 100) mm
  EXPECT_GT(m.at(55, 25), m.at(20, 20));  // B over A
  // The companion map scene runs as a paper 002-style map with the same tumors.
  const SceneFile baked = load_scene_file(map_scene);
  EXPECT_NE(dynamic_cast<const MapScene*>(baked.scene.get()), nullptr);
  ASSERT_EQ(baked.tumors.size(), 3u);
  EXPECT_GT(baked.scene->sample({110, 50}, 2, 0).stiffness, 0.7);

  // CSV, a harder press and a time in the breathing cycle.
  const auto csv = dir.path() / "liver.csv";
  const ProcessResult l =
      run_process(palprig_bin() + " scene render " + palprig::testing::shipped_data("scenes/liver_edge.json") +
                  " --out " + csv.string() + " --res-mm 5 --force-N 4 --t-s 2");
  ASSERT_EQ(l.exit_code, 0) << l.err;
  std::ifstream lin(csv);
  EXPECT_EQ(parse_stiffness_csv(lin, csv.string(), 160, 120).cols(), 33u);
}

TEST(SceneCommand, InfoDescribesLayersInclusionsAndArteries) {
  const ProcessResult r =
      run_process(palprig_bin() + " scene info " + palprig::testing::shipped_data("scenes/groin_femoral.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("artery femoral"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("inguinal ligament (ligament"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("muscle"), std::string::npos);
}

TEST(SceneCommand, BadInputExitsTwoWithOneClearLine) {
  TempDir dir;
  const auto bad = dir.write("bad.json", R"({"version": 1, "kind": "function", "body": {"centre_mm": [80, 60],
    "half_size_mm": [80, 60]}, "layers": [{"name": "fat", "thickness_mm": 10, "stiffness_kPa": 4}],
    "felt_range_kPa": {"soft": 4, "hard": 300},
    "inclusions": [{"name": "T", "stiffness_kPa": 30, "shape": {"type": "sphere", "centre_mm": [1, 2, 8], "radius_mm": -4}}]})");
  ProcessResult r =
      run_process(palprig_bin() + " scene render " + bad.string() + " --out " + (dir.path() / "x.pgm").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(bad.string() + ": inclusions[0].shape.radius_mm: a positive radius"), std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "x.pgm"));

  r = run_process(palprig_bin() + " scene generate --seed 1 --difficulty extreme --out " +
                  (dir.path() / "c.json").string());
  EXPECT_EQ(r.exit_code, 2);
  r = run_process(palprig_bin() + " scene render " + palprig::testing::shipped_data("scenes/brachial_pulse.json") +
                  " --out " + (dir.path() / "x.png").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(".pgm"), std::string::npos) << r.err;
  r = run_process(palprig_bin() + " run --scene " + bad.string() + " --input sweep --duration-s 1");
  EXPECT_EQ(r.exit_code, 2);  // refused before anything moves
}

TEST(SceneCommand, RunDrivesTheRigFromAFunctionSceneWithAPulse) {
  // The pen sweeps the arm; where fingers cross the brachial artery the pulse rides on top.
  const ProcessResult r =
      run_process(palprig_bin() + " run --scene " + palprig::testing::shipped_data("scenes/brachial_pulse.json") +
                  " --input sweep --duration-s 6 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["ticks"], 6000);
  EXPECT_TRUE(j["fault"].is_null());
  EXPECT_LE(j["setpoint_kPa"][0]["max"].get<double>(), 60.0);
}
