#pragma once
// ThresholdProtocol: a protocol file with "task": "threshold" - adaptive measurement of the
// pressure increment a participant detects over a reference pressure, on one finger or on all
// three, by two-interval forced choice or yes/no. One or more tracks (staircases or QUEST)
// run interleaved. Validated like every protocol: unknown fields, impossible ranges and levels
// above 100 kPa are refused with the file and field (InputError); the CLI also refuses
// reference + largest level above the rig's p_max before anything moves.
//
//   2afc    two intervals, the reference in one and reference + level in the other (random
//           order); the participant says which was stronger; correct = chose the stronger
//   yes-no  the reference, then reference + level; the participant says whether the second
//           felt stronger; "yes" counts as the correct answer for the track
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "study/adaptive_track.hpp"

namespace palprig {

enum class ThresholdMethod { two_afc, yes_no };
const char* to_string(ThresholdMethod m) noexcept;

struct ThresholdTiming {
  double interval_s = 1.0;           // each interval's pressure is on this long
  double gap_s = 0.5;                // vented pause between the intervals
  double response_timeout_s = 10.0;  // after the second interval; no answer: the trial is repeated
  double inter_trial_s = 1.0;        // vented pause after the answer
};

struct ThresholdProtocol {
  std::string source, name, description, bids_task;
  ThresholdMethod method = ThresholdMethod::two_afc;
  double reference_kPa = 8.0;
  ThresholdTiming timing;
  std::vector<TrackSpec> tracks;
  nlohmann::json snapshot;  // the file as read, stored with the session

  // The highest pressure any trial can command: reference + the largest allowed level.
  double max_pressure_kPa() const;
};

// True when a protocol document declares "task": "threshold".
bool is_threshold_protocol(const nlohmann::json& document);

ThresholdProtocol parse_threshold_protocol(const nlohmann::json& document, const std::string& source);
ThresholdProtocol load_threshold_protocol(const std::filesystem::path& path);

}  // namespace palprig
