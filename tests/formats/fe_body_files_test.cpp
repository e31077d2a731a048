// The finite-element model's files: the shipped ones load as paper 002 describes them, and a
// refused file names the file, the field and what was expected (one line, InputError), for the
// fields, the laws and the shapes that cannot be meshed.
#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <fstream>

#include "formats/fe_body_files.hpp"
#include "formats/fe_result_files.hpp"
#include "tests/support/refusal.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

using test_support::refusal;
using testing::ScratchDir;
using testing::source_dir;

std::filesystem::path fe_data(const std::string& name) { return source_dir() / "data" / "fe" / name; }
// The stress model shipped before the loading and uninflated keys existed (pressed 0.5 mm first,
// the line's own intercept), kept so that such files are shown to load as they were written.
std::filesystem::path stress_model_before_keys() {
  return source_dir() / "tests" / "fixtures" / "fe" / "stress_model_before_keys.json";
}

nlohmann::json shipped(const std::string& name) {
  std::ifstream in(fe_data(name));
  return nlohmann::json::parse(in);
}

TEST(FeBodyFiles, ShippedFilesArePaper002s) {
  const FingertipBody f = load_fingertip_file(fe_data("fingertip_002.json"));
  EXPECT_DOUBLE_EQ(f.width_mm, 16);
  EXPECT_DOUBLE_EQ(f.height_mm, 12);
  EXPECT_DOUBLE_EQ(f.skin_thickness_mm, 0.8);
  EXPECT_EQ(f.skin.kind, MaterialKind::ogden);
  EXPECT_DOUBLE_EQ(f.skin.alpha, -10.898);
  EXPECT_DOUBLE_EQ(f.tissue.mu_kPa, 19.34);
  const TissueBlock healthy = load_tissue_file(fe_data("soft_tissue_002.json"));
  EXPECT_TRUE(healthy.inclusions.empty());
  EXPECT_DOUBLE_EQ(healthy.width_mm, 30);
  EXPECT_DOUBLE_EQ(healthy.height_mm, 100);
  const TissueBlock nodule = load_tissue_file(fe_data("soft_tissue_002_nodule.json"));
  ASSERT_EQ(nodule.inclusions.size(), 1u);
  EXPECT_DOUBLE_EQ(nodule.inclusions[0].diameter_mm, 10);
  EXPECT_DOUBLE_EQ(nodule.inclusions[0].law.mu_kPa, 73.4);
  const ActuatorBody a = load_actuator_file(fe_data("actuator_002.json"));
  EXPECT_DOUBLE_EQ(a.chamber_width_mm, 4);
  EXPECT_DOUBLE_EQ(a.layer_thickness_mm, 3);
  EXPECT_NEAR(a.membrane.youngs_kPa, 1994, 1);  // Shore A 40 through eq. 3-4
}

TEST(FeBodyFiles, TheMembraneIsBondedUnlessTheFileSaysItSlides) {
  nlohmann::json doc = shipped("actuator_002.json");
  EXPECT_FALSE(parse_actuator(doc, "a.json").membrane_slides);  // the paper's adhesive
  doc["membrane"]["on_substrate"] = "sliding";
  EXPECT_TRUE(parse_actuator(doc, "a.json").membrane_slides);
  doc["membrane"]["on_substrate"] = "bonded";
  EXPECT_FALSE(parse_actuator(doc, "a.json").membrane_slides);
  doc["membrane"]["on_substrate"] = "glued";
  EXPECT_EQ(refusal([&] { (void)parse_actuator(doc, "a.json"); }),
            "a.json: membrane.on_substrate: one of \"bonded\", \"sliding\", got \"glued\"");
}

TEST(FeBodyFiles, MaterialsDefaultToTable1) {
  nlohmann::json doc = shipped("fingertip_002.json");
  doc.erase("materials");
  const FingertipBody f = parse_fingertip(doc, "f.json");
  EXPECT_DOUBLE_EQ(f.skin.mu_kPa, table1::skin().mu_kPa);
  EXPECT_DOUBLE_EQ(f.nail.youngs_kPa, table1::nail().youngs_kPa);
}

struct Refused {
  const char* file;
  const char* pointer;  // JSON pointer of the value to set
  nlohmann::json value;
  const char* expected;  // the whole refusal line
};

// How GoogleTest prints a case (it goes into the test's listing, so into ctest's name): its file
// and field, not the struct's bytes, which hold pointers and change from run to run.
void PrintTo(const Refused& r, std::ostream* os) { *os << r.file << " " << r.pointer; }

class FeBodyRefusals : public ::testing::TestWithParam<Refused> {};

TEST_P(FeBodyRefusals, NameFileFieldAndExpectation) {
  const Refused& r = GetParam();
  nlohmann::json doc = shipped(r.file);
  if (r.value.is_null())
    doc.erase(nlohmann::json::json_pointer(r.pointer).back());
  else
    doc[nlohmann::json::json_pointer(r.pointer)] = r.value;
  ScratchDir dir;
  const auto path = dir / r.file;
  std::ofstream(path) << doc.dump();
  const std::string kind = fe_body_kind(shipped(r.file));
  const std::string line = refusal([&] {
    if (kind == "fingertip") (void)load_fingertip_file(path);
    if (kind == "tissue") (void)load_tissue_file(path);
    if (kind == "actuator") (void)load_actuator_file(path);
  });
  EXPECT_EQ(line, path.string() + ": " + r.expected);
}

INSTANTIATE_TEST_SUITE_P(
    Fields, FeBodyRefusals,
    ::testing::Values(
        Refused{"fingertip_002.json", "/version", 2,
                "version: version 1 or older (this palprig is older than the file), got 2"},
        Refused{"fingertip_002.json", "/outline/width_mm", 2, "outline.width_mm: a number in 4..40, got 2"},
        Refused{"fingertip_002.json", "/skin_thickness_mm", 5, "skin_thickness_mm: a number in 0.1..3, got 5"},
        Refused{"fingertip_002.json", "/bone/centre_height_mm", 11.5,
                "bone.centre_height_mm: a bone inside the tissue, at least 0.5 mm from the skin (outline 16 x 12 mm, "
                "skin 0.8 mm)"},
        Refused{"fingertip_002.json", "/materials/skin/law", "mooney_rivlin",
                "materials.skin.law: one of \"ogden\", \"arruda_boyce\", \"linear_elastic\", got \"mooney_rivlin\""},
        Refused{"fingertip_002.json", "/materials/skin/alpha", 0,
                "materials.skin.alpha: an Ogden exponent of magnitude 0.1..50 (0 has no stress)"},
        Refused{"fingertip_002.json", "/materials/nail/shore_a", 40,
                "materials.nail.youngs_kPa: exactly one of youngs_kPa, shore_a (20..80) or shore_d (30..85)"},
        Refused{"fingertip_002.json", "/materials/tissue/mu_kpa", 1,
                "materials.tissue.mu_kpa: no such field here (unknown field; check its spelling)"},
        Refused{"soft_tissue_002_nodule.json", "/inclusions/0/centre_depth_mm", 4,
                "inclusions[0].centre_depth_mm: a centre at least 0.5 mm deeper than the radius (5 mm): the "
                "inclusion must stay under the surface"},
        Refused{"soft_tissue_002_nodule.json", "/inclusions/0/x_mm", 12,
                "inclusions[0].x_mm: an inclusion at least 0.5 mm inside the block's sides (half width 15 mm, "
                "radius 5 mm)"},
        Refused{"soft_tissue_002_nodule.json", "/inclusions/1",
                nlohmann::json{{"x_mm", 2}, {"centre_depth_mm", 12}, {"diameter_mm", 4}},
                "inclusions[1].centre_depth_mm: inclusions at least 0.5 mm apart (nodule is -2.07557 mm away)"},
        Refused{"soft_tissue_002.json", "/block/sides", "glued",
                "block.sides: one of \"free\", \"rollers\", got \"glued\""},
        Refused{"soft_tissue_002.json", "/material/locking_stretch", 1,
                "material.locking_stretch: a number in 1.001..100, got 1"},
        Refused{"actuator_002.json", "/chamber/width_mm", 30, "chamber.width_mm: a number in 0.5..22, got 30"},
        Refused{"actuator_002.json", "/membrane/material/shore_a", 95,
                "membrane.material.shore_a: a number in 20..80, got 95"},
        Refused{"actuator_002.json", "/kind", "fingertip", "kind: one of \"actuator\", got \"fingertip\""}),
    // Each case named by its file and field (fingertip_002_outline_width_mm), not by its index.
    [](const ::testing::TestParamInfo<Refused>& case_info) {
      std::string name = std::filesystem::path(case_info.param.file).stem().string() + case_info.param.pointer;
      for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      return name;
    });

// A stress model with soft 5 and nodule 8 kPa stresses and a line of slope 0.25.
FeStressModelFile small_stress_model(double intercept_kPa) {
  FeStressModelFile m;
  m.inputs = {"f.json", "t.json", "a.json", "0123", "plane strain", 1.0};
  m.soft_stress_kPa = 5;
  m.hard_stress_kPa = 8;
  m.actuator.slope = 0.25;
  m.actuator.intercept_kPa = intercept_kPa;
  return m;
}

TEST(FeResultFiles, StressModelTheCalibrationCouldNotUseIsRefused) {
  ScratchDir dir;
  FeStressModelFile m = small_stress_model(9);  // at or above the nodule's stress: no pressure renders it
  const auto path = dir / "model.json";
  EXPECT_EQ(refusal([&] { write_stress_model_file(path, m); }),
            path.string() +
                ": actuator.intercept_kPa: the uninflated actuator's stress below the nodule stress (8 "
                "kPa): otherwise no air pressure renders a nodule");
  EXPECT_FALSE(std::filesystem::exists(path)) << "a refused file is not left behind";
  m.actuator.intercept_kPa = 4;
  write_stress_model_file(path, m);
  const FeStressModelFile back = load_stress_model_file(path);
  EXPECT_DOUBLE_EQ(back.actuator.slope, 0.25);
  EXPECT_DOUBLE_EQ(back.hard_stress_kPa, 8);
  EXPECT_EQ(back.inputs.hash, "0123");
  EXPECT_EQ(back.loading, "press-first");
}

TEST(FeResultFiles, StressModelSaysHowThePressMetTheAir) {
  // A file written before the key existed was pressed first; the shipped model is loaded as the
  // paper loads its actuator.
  EXPECT_EQ(load_stress_model_file(stress_model_before_keys()).loading, "press-first");
  EXPECT_EQ(load_stress_model_file(fe_data("stress_model_002.json")).loading, "together");
  ScratchDir dir;
  FeStressModelFile m = small_stress_model(0.13);
  m.loading = "together";
  const auto path = dir / "model.json";
  write_stress_model_file(path, m);
  EXPECT_EQ(load_stress_model_file(path).loading, "together");
  nlohmann::json doc = stress_model_json(m);
  doc["actuator"]["loading"] = "sideways";
  EXPECT_EQ(refusal([&] { (void)parse_stress_model(doc, "model.json"); }),
            "model.json: actuator.loading: one of \"press-first\", \"together\", got \"sideways\"");
}

TEST(FeResultFiles, StressModelSaysWhatTheUninflatedActuatorRenders) {
  // Files written before the key existed used the line's own intercept; the shipped model reads
  // the uninflated actuator as paper 002 does, as soft tissue.
  const FeStressModelFile before = load_stress_model_file(stress_model_before_keys());
  EXPECT_EQ(before.uninflated, "fitted");
  EXPECT_NEAR(before.actuator.intercept_kPa, 6.5775, 1e-4);
  const FeStressModelFile shipped = load_stress_model_file(fe_data("stress_model_002.json"));
  EXPECT_EQ(shipped.uninflated, "soft-tissue");
  EXPECT_DOUBLE_EQ(shipped.actuator.intercept_kPa, shipped.soft_stress_kPa);
  EXPECT_NEAR(shipped.nodule_pressure_kPa, 11.75, 0.10 * 11.75);  // paper 002's air for the nodule, within 10 %
  ScratchDir dir;
  FeStressModelFile m = small_stress_model(5);  // the soft tissue's 5 kPa
  m.uninflated = "soft-tissue";
  const auto path = dir / "model.json";
  write_stress_model_file(path, m);
  const FeStressModelFile back = load_stress_model_file(path);
  EXPECT_EQ(back.uninflated, "soft-tissue");
  EXPECT_DOUBLE_EQ(back.actuator.intercept_kPa, 5);
  // "soft-tissue" with an intercept that is not the soft stress says one thing and does another.
  nlohmann::json doc = stress_model_json(m);
  doc["actuator"]["intercept_kPa"] = 4.5;
  EXPECT_EQ(refusal([&] { (void)parse_stress_model(doc, "model.json"); }),
            "model.json: actuator.intercept_kPa: the soft-tissue stress (5 kPa), as \"uninflated\": "
            "\"soft-tissue\" says");
  doc = stress_model_json(m);
  doc["actuator"]["uninflated"] = "inflated";
  EXPECT_EQ(refusal([&] { (void)parse_stress_model(doc, "model.json"); }),
            "model.json: actuator.uninflated: one of \"fitted\", \"soft-tissue\", got \"inflated\"");
}

}  // namespace
}  // namespace palprig
