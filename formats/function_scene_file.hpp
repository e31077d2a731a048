#pragma once
// Function scene files (JSON, versioned; "kind": "function"): a tissue block described by
// functions (paper 001) with arteries (papers 000, 003, 004). The full format is in README.md,
// section "Scenes and pulse". In short:
//
//   "body":      {"centre_mm": [x, y], "half_size_mm": [a, b], "exponent": 6}
//   "layers":    [{"name", "thickness_mm", "stiffness_kPa"}, ...]       skin first
//   "support_kPa", "felt_range_kPa": {"soft", "hard"}, "press": {...}, "respiration": {"period_s"}
//   "inclusions": [{"name", "kind", "stiffness_kPa", "shape": SHAPE, "breathing_excursion_mm"}]
//   "arteries":  [{"name", "path_mm": [[x, y], ...], "depth_mm", "radius_mm", "amplitude_kPa",
//                  "rate_bpm", "waveform": {"shape": "rectangular"|"sawtooth"|"table", ...},
//                  "force_window_N": [min, max], ...}]
//   SHAPE:       {"type": "sphere"|"ellipsoid"|"superellipsoid"|"tube"|"blobs"|"union"|
//                 "intersection"|"difference"|"scaled", ...}
//
// Everything is validated on load: unknown fields, negative or zero sizes and moduli, rates
// outside 20..250 BPM, empty or non-periodic waveform tables are refused with the file, the
// field and the reason (InputError).
#include <cstdint>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "formats/json_file.hpp"
#include "formats/scene_description.hpp"
#include "models/case_generator.hpp"
#include "models/pulse_waveform.hpp"

namespace palprig {

// The most work one tick may spend sampling a function scene under its three fingers, in the
// FRep's sphere-equivalent evaluations (StiffnessField::worst_case_sample_cost): about 0.2 ms,
// a fifth of a 1 kHz period. The loader refuses a heavier scene; the lag compensation samples
// the scene ahead only as often as this leaves room for (controller/run_setup.cpp).
inline constexpr double kMaxTickShapeCost = 30000;

// The rest of a scene file whose root load_scene_file has opened (version, name, kind and
// description already read): builds the FunctionScene and the tumor ground truth into out.
void load_function_scene(const JsonObject& root, const std::filesystem::path& path, SceneFile& out);

// One recorded beat as CSV: "t_s,value" rows (a header line and '#' comments allowed), times
// strictly increasing, the last row closing the beat.
PulseWaveform load_waveform_csv(const std::filesystem::path& path);

// A waveform table is a few hundred rows; anything that is not a regular file (a FIFO blocks,
// /dev/zero never ends) or is larger than this is refused before it is opened.
inline constexpr std::uintmax_t kMaxWaveformFileBytes = std::uintmax_t(1) << 20;  // 1 MiB
// Why `path` cannot be a waveform table (empty: it may be read).
std::string waveform_file_refusal(const std::filesystem::path& path);

// A generated rehearsal case as a function scene file (with its generator provenance), and the
// writer that puts it on disk (io/checked_output: whole or not at all; OutputError naming the
// file and the system's reason when it cannot be written).
nlohmann::json generated_case_json(const GeneratedCase& c);
void write_scene_json(const std::filesystem::path& path, const nlohmann::json& scene);

}  // namespace palprig
