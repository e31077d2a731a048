// A function scene whose sampling cannot fit a 1 kHz tick is refused when it
// is loaded (one line naming the file and what was expected, exit 2, nothing moves), while the
// shipped scenes, generated cases and large but indexed unions load as before.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "formats/function_scene_file.hpp"
#include "formats/scene_file.hpp"
#include "models/case_generator.hpp"
#include "core/input_error.hpp"
#include "models/tissue_scene.hpp"
#include "tests/support/run_process.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig;
using palprig::test_support::TempDir;

namespace {

// n inclusions, each the intersection of `parts` large spheres that all overlap the middle of
// the body: every point there visits every sphere of every inclusion.
nlohmann::json overlapping_intersections(int n, int parts) {
  nlohmann::json incs = nlohmann::json::array();
  for (int i = 0; i < n; ++i) {
    nlohmann::json of = nlohmann::json::array();
    for (int k = 0; k < parts; ++k)
      of.push_back({{"type", "sphere"}, {"centre_mm", {100 + 0.01 * k, 60, 0}}, {"radius_mm", 30}});
    incs.push_back({{"name", "slow" + std::to_string(i)},
                    {"stiffness_kPa", 50},
                    {"shape", {{"type", "intersection"}, {"of", of}}}});
  }
  return {{"version", 1},
          {"kind", "function"},
          {"body", {{"centre_mm", {100, 60}}, {"half_size_mm", {80, 60}}}},
          {"layers", {{{"name", "skin"}, {"thickness_mm", 40}, {"stiffness_kPa", 10}}}},
          {"felt_range_kPa", {{"soft", 10}, {"hard", 100}}},
          {"inclusions", incs}};
}

std::string cost_refusal(const std::filesystem::path& f) {
  try {
    load_scene_file(f);
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST(SceneCostBound, ASceneTooSlowForTheTickIsRefusedAtLoadNamingTheFile) {
  TempDir dir;
  // 64 x 500 spheres over one spot: within the shape limits (500 < 4096 per inclusion), but a
  // tick there would visit 32,000 spheres at each of its 360 points.
  const auto f = dir.write("slow.json", overlapping_intersections(64, 500).dump());
  // The bound is counted from the scene's shapes, not measured by sampling it (no wall-clock
  // bound here: under a sanitizer on a busy machine reading the 32,000 spheres alone takes
  // seconds).
  const std::string why = cost_refusal(f);
  EXPECT_EQ(why.rfind(f.string() + ": inclusions: ", 0), 0u) << why;
  EXPECT_NE(why.find("at most 30000 shape evaluations per tick, got "), std::string::npos) << why;
  EXPECT_EQ(why.find('\n'), std::string::npos);
}

TEST(SceneCostBound, TheRunCommandRefusesItWithExitTwoBeforeAnythingMoves) {
  TempDir dir;
  const auto f = dir.write("slow.json", overlapping_intersections(64, 500).dump());
  const auto telemetry = dir.path() / "t.csv";
  for (const char* mode : {"--replay", "--realtime --no-fifo"}) {
    const auto r =
        palprig::test_support::run_process(palprig::test_support::palprig_bin() + " run " + mode + " --scene " +
                                           f.string() + " --duration-s 2 --telemetry " + telemetry.string());
    EXPECT_EQ(r.exit_code, 2) << mode << ": " << r.err;
    EXPECT_NE(r.err.find(f.string() + ": inclusions: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("shape evaluations per tick"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(telemetry)) << "a tick ran";
  }
}

TEST(SceneCostBound, ScenesThatFitStillLoad) {
  TempDir dir;
  // Fewer of the same shapes: 4 x 11 evaluations at each of 360 points.
  EXPECT_EQ(cost_refusal(dir.write("fast.json", overlapping_intersections(4, 10).dump())), "accepted");
  // Every shipped function scene.
  int function_scenes = 0;
  for (const auto& e : std::filesystem::directory_iterator(std::string(PALPRIG_SOURCE_DIR) + "/data/scenes")) {
    if (e.path().extension() != ".json") continue;
    const auto doc = nlohmann::json::parse(palprig::test_support::read_file(e.path()));
    if (doc.value("kind", "") != "function") continue;
    ++function_scenes;
    EXPECT_EQ(cost_refusal(e.path()), "accepted") << e.path();
  }
  EXPECT_GT(function_scenes, 0);
  // Generated rehearsal cases of every difficulty.
  for (CaseDifficulty d : {CaseDifficulty::easy, CaseDifficulty::medium, CaseDifficulty::hard})
    for (std::uint64_t seed = 1; seed <= 40; ++seed) {
      const auto path = dir.path() / "case.json";
      write_scene_json(path, generated_case_json(generate_case(seed, d)));
      EXPECT_EQ(cost_refusal(path), "accepted") << to_string(d) << " seed " << seed;
    }
}

TEST(SceneCostBound, TheBoundCountsTheFullestGridCellOfAUnionNotAllItsParts) {
  // 4000 small spheres in one union (the largest the shape limit allows in practice) cost a
  // few spheres per point through the union's grid.
  FrepShape shape;
  std::vector<FrepShape::Node> parts;
  parts.reserve(4000);
  for (int i = 0; i < 4000; ++i) {
    const int column = i % 64, row = i / 64;
    parts.push_back(shape.sphere({10 + 2.5 * column, 10 + 2.5 * row, 5}, 1.0));
  }
  shape.unite(parts);
  EXPECT_LT(shape.worst_case_cost(), 20.0);
  FrepShape scan;
  std::vector<FrepShape::Node> all;
  all.reserve(100);
  for (int i = 0; i < 100; ++i) all.push_back(scan.sphere({100, 60, 0}, 30));
  scan.intersect(all);
  EXPECT_EQ(scan.worst_case_cost(), 101.0);
}
