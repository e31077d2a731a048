// A function scene with thousands of shapes in one inclusion: the count is bounded with a clear
// refusal (before the parts are read), and a union of many parts gives exactly the values a
// plain scan of its parts gives (the grid that makes it linear changes no answer).
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <random>
#include <string>

#include <nlohmann/json.hpp>

#include "formats/function_scene_file.hpp"
#include "formats/scene_file.hpp"
#include "models/frep.hpp"
#include "core/input_error.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig;
using palprig::test_support::TempDir;

namespace {

// A scene whose one tumor is a union of n small spheres on a grid (pitch 2.5 mm).
nlohmann::json sphere_union_scene(int n) {
  nlohmann::json parts = nlohmann::json::array();
  const int side = static_cast<int>(std::ceil(std::sqrt(double(n))));
  for (int i = 0; i < n; ++i) {
    const int column = i % side, row = i / side;
    parts.push_back({{"type", "sphere"}, {"centre_mm", {10 + 2.5 * column, 10 + 2.5 * row, 5}}, {"radius_mm", 1.0}});
  }
  return {{"version", 1},
          {"kind", "function"},
          {"body", {{"centre_mm", {100, 100}}, {"half_size_mm", {100, 100}}}},
          {"layers", {{{"name", "skin"}, {"thickness_mm", 40}, {"stiffness_kPa", 10}}}},
          {"felt_range_kPa", {{"soft", 10}, {"hard", 100}}},
          {"inclusions", {{{"name", "many"}, {"stiffness_kPa", 100}, {"shape", {{"type", "union"}, {"of", parts}}}}}}};
}

std::string bounds_refusal(const std::filesystem::path& f) {
  try {
    load_scene_file(f);
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST(FunctionSceneBounds, TooManyShapesInOneUnionAreRefused) {
  TempDir dir;
  const auto f = dir.write("many.json", sphere_union_scene(5000).dump());
  EXPECT_EQ(bounds_refusal(f),
            f.string() + ": inclusions[0].shape.of: at most 4096 shapes in one inclusion, got 5000 here");
}

TEST(FunctionSceneBounds, TooManyShapesAcrossNestedUnionsAreRefused) {
  TempDir dir;
  auto doc = sphere_union_scene(3000);
  auto& of = doc["inclusions"][0]["shape"]["of"];
  nlohmann::json second = {{"type", "union"}, {"of", of}};
  of.push_back(second);  // 3000 + a union of 3000 more
  const auto f = dir.write("nested.json", doc.dump());
  const std::string why = bounds_refusal(f);
  EXPECT_NE(why.find(".type: at most 4096 shapes in one inclusion"), std::string::npos) << why;
}

TEST(FunctionSceneBounds, TooManyBlobsAreRefused) {
  TempDir dir;
  auto doc = sphere_union_scene(1);
  nlohmann::json blobs = nlohmann::json::array();
  for (int i = 0; i < 300; ++i) blobs.push_back({{"centre_mm", {50, 50, 5}}, {"radii_mm", {2, 2, 2}}});
  doc["inclusions"][0]["shape"] = {{"type", "blobs"}, {"threshold", 0.5}, {"blobs", blobs}};
  const auto f = dir.write("blobs.json", doc.dump());
  EXPECT_EQ(bounds_refusal(f), f.string() + ": inclusions[0].shape.blobs: at most 256 blobs in one shape, got 300");
}

TEST(FunctionSceneBounds, ALargeUnionLoadsAndFindsItsTumor) {
  TempDir dir;
  const auto f = dir.write("large.json", sphere_union_scene(4000).dump());
  const SceneFile s = load_scene_file(f);
  ASSERT_EQ(s.tumors.size(), 1u);
  // 64 x 63 spheres from (10, 10) at a 2.5 mm pitch: the outline is centred on the grid.
  EXPECT_NEAR(s.tumors[0].x_mm, 10 + 2.5 * 63 / 2, 1.0);
}

TEST(FrepUnionGrid, ValuesEqualAPlainScanOfTheParts) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pos(0, 100), rad(0.5, 8);
  FrepShape indexed, scanned;
  std::vector<FrepShape::Node> a, b;
  for (int i = 0; i < 500; ++i) {
    const Point3_mm c{pos(rng), pos(rng), pos(rng) / 10};
    const double r = rad(rng);
    if (i % 3 == 0) {
      a.push_back(indexed.tube(c, {c.x_mm + 10, c.y_mm - 5, c.z_mm}, r));
      b.push_back(scanned.tube(c, {c.x_mm + 10, c.y_mm - 5, c.z_mm}, r));
    } else {
      a.push_back(indexed.sphere(c, r));
      b.push_back(scanned.sphere(c, r));
    }
  }
  indexed.unite(a);
  // The same parts as unions of 10 (under the indexing threshold), joined: a plain scan.
  std::vector<FrepShape::Node> groups;
  for (std::size_t i = 0; i < b.size(); i += 10)
    groups.push_back(scanned.unite(std::vector<FrepShape::Node>(b.begin() + long(i), b.begin() + long(i + 10))));
  std::vector<FrepShape::Node> top;
  for (std::size_t i = 0; i < groups.size(); i += 10)
    top.push_back(scanned.unite(std::vector<FrepShape::Node>(groups.begin() + long(i), groups.begin() + long(i + 10))));
  scanned.unite(top);
  int inside = 0;
  for (int i = 0; i < 200000; ++i) {
    const Point3_mm p{pos(rng) * 1.2 - 10, pos(rng) * 1.2 - 10, pos(rng) / 5 - 2};
    ASSERT_EQ(indexed.value(p), scanned.value(p)) << p.x_mm << " " << p.y_mm << " " << p.z_mm;
    inside += indexed.contains(p);
  }
  EXPECT_GT(inside, 1000);  // the comparison covered inside points too
}

// A waveform `file` that is not a small regular file is refused before it is opened: a FIFO
// would block the load, /dev/zero would be read for ever, a huge file is not a beat's table.
TEST(FunctionSceneBounds, AWaveformFileThatIsNotASmallRegularFileIsRefused) {
  TempDir dir;
  const auto fifo = dir.path() / "wave.fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const auto big = dir.write("big.csv", std::string(kMaxWaveformFileBytes + 1, '#'));
  std::filesystem::create_directory(dir.path() / "folder");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"/dev/zero", "a device"},
      {fifo.string(), "a FIFO"},
      {(dir.path() / "folder").string(), "a directory"},
      {big.string(), std::to_string(kMaxWaveformFileBytes + 1) + " bytes"}};
  for (const auto& [file, kind] : cases) {
    SCOPED_TRACE(file);
    nlohmann::json scene = sphere_union_scene(1);
    scene["arteries"] = {{{"name", "radial"},
                          {"path_mm", {{20, 0}, {20, 200}}},
                          {"radius_mm", 1.5},
                          {"depth_mm", 4},
                          {"amplitude_kPa", 5},
                          {"rate_bpm", 72},
                          {"waveform", {{"shape", "table"}, {"file", file}}}}};
    const auto f = dir.write("scene.json", scene.dump());
    const std::string why = bounds_refusal(f);
    EXPECT_EQ(why.rfind(f.string() + ": arteries[0].waveform.file: a regular file of at most 1024 KiB", 0), 0u) << why;
    std::string named = file;  // the table file and what it holds, as the refusal names them
    named.append(" (").append(kind).append(")");
    EXPECT_NE(why.find(named), std::string::npos) << why;
    EXPECT_EQ(why.find('\n'), std::string::npos) << why;
  }
  // The same scene with a real table loads: the refusals above are the file's doing.
  nlohmann::json scene = sphere_union_scene(1);
  scene["arteries"] = {
      {{"name", "radial"},
       {"path_mm", {{20, 0}, {20, 200}}},
       {"radius_mm", 1.5},
       {"depth_mm", 4},
       {"amplitude_kPa", 5},
       {"rate_bpm", 72},
       {"waveform",
        {{"shape", "table"}, {"file", std::string(PALPRIG_SOURCE_DIR) + "/data/waveforms/brachial_pressure.csv"}}}}};
  EXPECT_EQ(bounds_refusal(dir.write("good.json", scene.dump())), "accepted");
}
