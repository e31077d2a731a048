#pragma once
// The two files the finite-element model writes for the rest of palprig (JSON, versioned),
// written whole or not at all (io/checked_output.hpp) and read back before they replace an
// older file:
//
//   stress model   {"version": 1, "kind": "stress_model", "inputs": {"fingertip", "tissue",
//                   "actuator", "hash"}, "assumptions": {"plane", "element_mm"},
//                   "tissue": {"indentation_mm", "soft_stress_kPa", "hard_stress_kPa"},
//                   "actuator": {"press_mm", "loading", "uninflated", "slope", "intercept_kPa",
//                                "r_squared", "pressures_kPa", "stresses_kPa"},
//                   "nodule_pressure_kPa"}
//     `palprig fe stress-model` writes it; `calibrate fit --stress-model` reads it instead of the
//     paper's constants: the soft and hard stresses become the calibration's stress model, the
//     line every channel's actuator line.
//   FE table       {"version": 1, "kind": "fe_stress_table", "inputs": {...}, "assumptions": {...},
//                   "axes": {"indentation_mm", "cover_mm", "diameter_mm", "contrast",
//                            "offset_mm"}, "healthy_kPa": [...], "peak_kPa": [...],
//                   "build": {"solves", "wall_s", "workers"}}
//     `palprig fe table` writes it; a function scene's "fe_stress_table" names it.
//
// Refusals name the file, the field and what was expected (InputError); a stress model whose
// line the calibration file would refuse (a flat slope, an intercept at or above the hard
// stress) is refused here already.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "models/fe_stress_table.hpp"
#include "models/stress_model.hpp"

namespace palprig {

inline constexpr int kFeResultFileVersion = 1;

// Where a result came from: its input files and the hash of their bytes and of the settings.
struct FeInputs {
  std::string fingertip, tissue, actuator;
  std::string hash;
  std::string plane;  // "plane strain" | "plane stress"
  double element_mm = 1.0;
};

struct FeStressModelFile {
  std::string file;  // where it was read from (empty for one about to be written)
  FeInputs inputs;
  double indentation_mm = 7.0;
  double soft_stress_kPa = 0, hard_stress_kPa = 0;
  double press_mm = 1.0;
  // How the press met the air: "press-first" (pressed press_mm, then inflated) or "together"
  // (paper 002's "at the same time": the press rising with the air). Absent in files written
  // before the key existed, which were all press-first.
  std::string loading = "press-first";
  // What the uninflated actuator renders: "fitted" (the line's own intercept, the stress the
  // computed actuator gives with no air) or "soft-tissue" (paper 002's reading, "an inactivated
  // actuator to simulate the situation of no tumor": the intercept is soft_stress_kPa and the air
  // adds the line's slope to it, so a nodule needs (hard - soft) / slope). Absent in files
  // written before the key existed, which were all fitted.
  std::string uninflated = "fitted";
  ActuatorModel actuator;
  double r_squared = 0;
  std::vector<double> pressures_kPa, stresses_kPa;
  double nodule_pressure_kPa = 0;  // the air pressure whose stress is hard_stress_kPa
};

nlohmann::json stress_model_json(const FeStressModelFile& m);
FeStressModelFile parse_stress_model(const nlohmann::json& doc, const std::string& file);
FeStressModelFile load_stress_model_file(const std::filesystem::path& path);
void write_stress_model_file(const std::filesystem::path& path, const FeStressModelFile& m);

struct FeTableFile {
  std::string file;
  FeInputs inputs;
  std::shared_ptr<const FeStressTable> table;
  std::size_t solves = 0;
  double wall_s = 0;
  int workers = 0;
};

nlohmann::json fe_table_json(const FeTableFile& t);
FeTableFile parse_fe_table(const nlohmann::json& doc, const std::string& file);
FeTableFile load_fe_table_file(const std::filesystem::path& path);
void write_fe_table_file(const std::filesystem::path& path, const FeTableFile& t);

// "stress_model" or "fe_stress_table" for those files, else "".
std::string fe_result_kind(const nlohmann::json& doc);

}  // namespace palprig
