#pragma once
// The pulse-localisation task's protocol (paper 000: find the femoral pulse), protocol "task": "pulse".
// Each trial presents one condition's scene (a function scene with one or more arteries: the
// shipped groin and brachial scenes, or a generated case) under the pen, through the tick's
// pulse stage like every palpation; the participant palpates and marks where the pulse is. The
// mark is scored by its distance to the nearest artery centreline (models/pulse_localisation:
// score_pulse_mark), a hit within the protocol's hit radius. Trial order: every condition
// `repetitions` times, shuffled with the session seed; a resumed session recomputes the same
// order and continues at the first trial not committed.
// Pure data and rules: the session that runs it on a rig is experiments/pulse_session.hpp.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "models/case_generator.hpp"

namespace palprig {

struct PulseCondition {
  std::string name;
  std::filesystem::path scene_file;  // resolved against the protocol's folder
  std::string artery;                // score against this artery; empty: the nearest one
  // "generate": {"difficulty"}: every trial a new generated case (models/case_generator) with a
  // random artery crossing it (generated_pulse_scene), seeded by the session seed and position.
  std::optional<CaseDifficulty> generated;
  // "generate": {"difficulty", "seed"}: that one generated case every trial of the condition (a
  // training session's cases, chosen so a trainee never gets one twice).
  std::optional<std::uint64_t> generated_seed;
};

struct PulseProtocol {
  std::string source, name, description, bids_task;
  std::vector<PulseCondition> conditions;
  int repetitions = 1;
  double hit_radius_mm = 5.0;
  double max_present_s = 60.0;
  double response_timeout_s = 10.0;
  double inter_trial_s = 2.0;
  nlohmann::json snapshot;
};

bool is_pulse_protocol(const nlohmann::json& document);
// base_dir resolves scene paths; every scene is loaded and must have arteries (InputError).
PulseProtocol parse_pulse_protocol(const nlohmann::json& document, const std::string& source,
                                   const std::filesystem::path& base_dir);
PulseProtocol load_pulse_protocol(const std::filesystem::path& path);

// The order of condition indices for a seed (every condition `repetitions` times, shuffled).
std::vector<int> pulse_trial_order(const PulseProtocol& protocol, std::uint64_t seed);

}  // namespace palprig
