// Hostile JSON in any validated file (rig, scene, function scene, calibration, protocol): deep
// nesting, numbers beyond double, huge values and control characters in refusals. Each case is
// refused with one line naming the file and the field, never a crash or the library's raw text.
#include <gtest/gtest.h>

#include <string>

#include "study/protocol.hpp"
#include "formats/calibration_file.hpp"
#include "formats/json_file.hpp"
#include "formats/rig_file.hpp"
#include "formats/scene_file.hpp"
#include "core/input_error.hpp"
#include "tests/support/run_process.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/refusal.hpp"

using namespace palprig;
using palprig::test_support::TempDir;

namespace {

std::string nested(std::size_t levels) { return std::string(levels, '[') + std::string(levels, ']'); }

}  // namespace

TEST(JsonHardening, DeepNestingIsRefusedWhileParsingInEveryFile) {
  TempDir dir;
  // 100,000 levels overflowed the stack when the refusal dumped the value.
  const std::string deep = "{\"version\": 1, \"id\": " + nested(100000) + "}";
  const auto f = dir.write("deep.json", deep).string();
  const std::string expected = f + ": id[0][0][0]";
  for (auto load :
       {+[](const std::string& p) { load_rig_file(p); }, +[](const std::string& p) { load_scene_file(p); },
        +[](const std::string& p) { load_calibration_file(p); }, +[](const std::string& p) { load_protocol(p); }}) {
    const std::string why = palprig::test_support::refusal([&] { load(f); });
    EXPECT_NE(why.find("nested at most 64 deep"), std::string::npos) << why;
    EXPECT_EQ(why.rfind(f + ": id", 0), 0u) << why;
    EXPECT_LT(why.size(), 700u);
  }
}

TEST(JsonHardening, NestingUpToTheLimitStillParses) {
  TempDir dir;
  const auto f = dir.write("ok.json", "{\"a\": " + nested(kMaxJsonDepth - 1) + "}");
  EXPECT_NO_THROW(read_json_file(f));
  const auto g = dir.write("over.json", "{\"a\": " + nested(kMaxJsonDepth) + "}");
  EXPECT_THROW(read_json_file(g), InputError);
}

TEST(JsonHardening, OverflowingNumberNamesFileAndField) {
  TempDir dir;
  const auto f = dir.write("rig.json", R"({"version": 1, "id": "r", "backend": "simulated",
    "safety": {"p_max_kPa": 1e400}})");
  EXPECT_EQ(palprig::test_support::refusal([&] { load_rig_file(f); }),
            f.string() + ": safety.p_max_kPa: a number within +-1.8e308, got 1e400");
  const auto g = dir.write("arr.json", R"({"version": 1, "list": [1, 2, -1e999]})");
  EXPECT_EQ(palprig::test_support::refusal([&] { read_json_file(g); }),
            g.string() + ": list[2]: a number within +-1.8e308, got -1e999");
}

TEST(JsonHardening, OverflowingNumberExitsTwoFromTheCommandLine) {
  TempDir dir;
  const auto scene =
      dir.write("s.json", R"({"version": 1, "map": {"file": "m.csv", "width_mm": 1e400, "height_mm": 10}})");
  const auto r = test_support::run_process(test_support::palprig_bin() + " run --scene " + scene.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err, "palprig: " + scene.string() + ": map.width_mm: a number within +-1.8e308, got 1e400\n");
}

TEST(JsonHardening, HugeValueInARefusalIsCut) {
  TempDir dir;
  std::string million = "[";
  for (int i = 0; i < 1000000; ++i) million += (i ? ",1" : "1");
  million += "]";
  const auto f = dir.write("rig.json", "{\"version\": 1, \"id\": " + million + "}");
  const std::string why = palprig::test_support::refusal([&] { load_rig_file(f); });
  EXPECT_EQ(why.rfind(f.string() + ": id: a string, got [1, 1, 1", 0), 0u) << why.substr(0, 200);
  EXPECT_LT(why.size(), 500u);
  EXPECT_EQ(why.substr(why.size() - 3), "...");
}

TEST(JsonHardening, ControlCharactersInRefusalsAreEscaped) {
  TempDir dir;
  // A key with an escape sequence and a newline: the refusal must stay one printable line.
  const auto f =
      dir.write("rig.json", "{\"version\": 1, \"id\": \"r\", \"backend\": \"simulated\", \"\\u001b[2Jp_max\\n\": 1}");
  const std::string why = palprig::test_support::refusal([&] { load_rig_file(f); });
  EXPECT_EQ(why, f.string() + ": \\x1b[2Jp_max\\n: no such field here (unknown field; check its spelling)");
  const auto g = dir.write("choice.json", "{\"version\": 1, \"kind\": \"map\\u0007\\t\"}");
  const std::string why2 = palprig::test_support::refusal([&] { load_scene_file(g); });
  EXPECT_EQ(why2, g.string() + ": kind: one of \"map\", \"function\", got \"map\\x07\\t\"");
}

TEST(JsonHardening, ExcerptCostsItsLimitNotTheValue) {
  nlohmann::json big = nlohmann::json::array();
  for (int i = 0; i < 100000; ++i) big.push_back(std::string(100, 'x'));
  const std::string e = json_excerpt(big, 80);
  EXPECT_LE(e.size(), 83u);
  EXPECT_EQ(json_excerpt(nlohmann::json::parse(R"({"a": [1, 2], "b": "c"})")), R"({"a": [1, 2], "b": "c"})");
}

TEST(InputErrorText, CutsEachPartAndKeepsUtf8Whole) {
  const InputError e("f.csv", "line 1", std::string(2'000'000, 'z'));
  EXPECT_LT(std::string(e.what()).size(), 400u);
  EXPECT_EQ(printable_excerpt("a\xc3\xa9"
                              "b",
                              2),
            "a\xc3\xa9...");  // never half of the two-byte é
  EXPECT_EQ(printable_excerpt("tab\there\r\n\x7f", 100), "tab\\there\\r\\n\\x7f");
}
