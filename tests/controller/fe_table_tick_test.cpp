// Function scenes rendered from the finite-element table (the scene key "fe_stress_table"): the
// same tumor 5 and 15 mm under the surface renders weaker when deeper, healthy tissue asks for no
// air, pressing harder asks for more, and the scene without the key keeps the stiffness rule.
// The table is the shipped one (data/fe/stress_table_002.json, computed by `palprig fe table`
// from paper 002's fingertip and tissue), so these are the mechanics' numbers, not made up.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "controller/tick.hpp"
#include "controller/tick_setup.hpp"
#include "formats/rig_file.hpp"
#include "formats/scene_file.hpp"
#include "models/tissue_scene.hpp"
#include "tests/support/support.hpp"

using namespace palprig;

namespace {

const std::filesystem::path kFeTableData = std::filesystem::path(PALPRIG_SOURCE_DIR) / "data";

// The pressure finger 1 asks for, held still at (x, y) pressing force_N (enough ticks for the
// slew limit to let the target through).
double held_pressure_kPa(const Scene& scene, double x, double y, double force_N) {
  const TickConfig cfg = make_tick_config(load_rig_file(kFeTableData / "rigs" / "simulated.json"), CalibrationModels{});
  TickState st = make_tick_state(cfg);
  TouchSample s;
  s.x_mm = x;
  s.y_mm = y;
  s.force_N = force_N;
  s.in_contact = true;
  double p = 0;
  for (int k = 0; k < 3000; ++k) {
    s.t_s = k * 1e-3;
    p = tick(st, cfg, scene, s, s.t_s).record.target_kPa[0];
  }
  return p;
}

TEST(FeTableScene, DeeperTumorRendersWeaker) {
  const SceneFile sf = load_scene_file(kFeTableData / "scenes" / "fe_depths.json");
  const auto* scene = dynamic_cast<const FunctionScene*>(sf.scene.get());
  ASSERT_NE(scene, nullptr);
  ASSERT_NE(scene->fe_table(), nullptr);
  const double shallow = held_pressure_kPa(*scene, 50, 40, 2.0);
  const double deep = held_pressure_kPa(*scene, 110, 40, 2.0);
  const double healthy = held_pressure_kPa(*scene, 80, 40, 2.0);
  EXPECT_GT(shallow, 1.0) << "a tumor 5 mm down is felt";
  EXPECT_GT(shallow, 1.5 * deep) << "the same tumor 15 mm down is felt much less";
  EXPECT_GE(deep, 0.0);
  EXPECT_NEAR(healthy, 0.0, 1e-9) << "healthy tissue is the actuator's passive stress: no air";
  // 1.5 N sinks 5.8 mm where 2 N sinks 7 (the shipped table's deepest step: a harder press is
  // read at 7 mm).
  EXPECT_LT(held_pressure_kPa(*scene, 50, 40, 1.5), shallow) << "pressing less sinks less: less stress";
  // The rise the tick used is the table's, for this tumor described as its nodule: its outline's
  // top depth and diameter, its modulus over the silicone's, at 2 N's 7 mm indentation.
  const InclusionOutline o = scene->outlines(InclusionKind::tumor).at(0);
  EXPECT_NEAR(o.top_depth_mm, 5.0, 0.5);
  const double expected = scene->fe_table()->rise_kPa(7.0, o.top_depth_mm, 2 * o.radius_mm, 100 / 14.7,
                                                      std::hypot(50 - o.x_mm, 40 - o.y_mm));
  EXPECT_NEAR(scene->fe_stress_rise_kPa({50, 40}, 2.0), expected, 1e-9);
}

TEST(FeTableScene, WithoutTheKeyTheStiffnessRuleApplies) {
  palprig::testing::ScratchDir dir;
  nlohmann::json doc;
  std::ifstream(kFeTableData / "scenes" / "fe_depths.json") >> doc;
  doc.erase("fe_stress_table");
  const auto path = dir / "rule.json";
  std::ofstream(path) << doc.dump();
  const SceneFile rule = load_scene_file(path);
  const SceneFile table = load_scene_file(kFeTableData / "scenes" / "fe_depths.json");
  EXPECT_FALSE(rule.scene->sample({50, 40}, 2.0, 0).fe_stress);
  EXPECT_TRUE(table.scene->sample({50, 40}, 2.0, 0).fe_stress);
  EXPECT_NE(held_pressure_kPa(*rule.scene, 50, 40, 2.0), held_pressure_kPa(*table.scene, 50, 40, 2.0));
}

}  // namespace
