#pragma once
// Protocol: what a session presents, read from a versioned JSON file in the spirit of
// PsychoPy/OpenSesame conditions files. Two tasks, after paper 002:
//   discrimination  fixed per-finger pressures (levels such as 0/10/30 kPa) presented to the
//                   three fingers at once ("simultaneous") or one finger after the other
//                   ("sequential"); the participant says under which fingers a tumor is
//   localisation    the participant palpates a scene (a stiffness map with tumors) and marks
//                   where the tumors are
// Every field is validated on load; unknown fields, empty level lists, combinations the tumor
// rule cannot classify and impossible ordering constraints are refused (InputError) before any
// stimulus. See data/protocols/ for the shipped files and study/README.md for the format.
#include <array>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>

#include "formats/scene_file.hpp"
#include "models/case_generator.hpp"
#include "models/finger_layout.hpp"

namespace palprig {

inline constexpr int kProtocolFileVersion = 1;

enum class TaskKind { discrimination, localisation };
enum class PresentationMode { simultaneous, sequential, scene };
enum class RandomScheme { fixed, full, blocked };
enum class Counterbalancing { none, alternate, latin_square, random };

const char* to_string(TaskKind task) noexcept;
const char* to_string(PresentationMode mode) noexcept;

using FingerFlags = std::array<bool, kFingerCount>;

// One per-finger stimulus pattern and its ground truth (derived from the pressures by the
// tumor rule, never typed in by hand).
struct StimulusCombination {
  std::array<double, kFingerCount> pressure_kPa{};
  FingerFlags tumor{};  // a tumor is present under this finger
  std::string label;    // e.g. "0/30/0"
};

struct Condition {
  std::string name;
  PresentationMode mode = PresentationMode::simultaneous;
};

struct Timing {
  double max_present_s = 30.0;       // stimulus on at most this long (the participant may answer sooner)
  double sequential_step_s = 2.0;    // sequential mode: each finger's pressure is on this long
  double sequential_gap_s = 0.5;     // ... with this pause (vented) between fingers
  double response_timeout_s = 30.0;  // after the stimulus ends, wait this long for an answer
  double inter_trial_s = 2.0;        // vented pause after each answer
  double break_s = 0.0;              // length of a break; 0: until the participant is ready
  // Simultaneous discrimination: the participant may answer while the stimulus is on, which
  // ends it (paper 002's three-finger trials, the stimulus staying until the answer; true), or
  // only once max_present_s has passed (a fixed-length stimulus, the response time after it is a
  // decision time; false). A sequence is always answered after its last finger.
  bool answer_during_stimulus = true;
};

struct Randomisation {
  RandomScheme scheme = RandomScheme::full;
  int max_repeats_in_a_row = 0;  // 0: unlimited
  int min_distance = 0;          // 0/1: none; d: identical trials at least d apart
};

// One case a localisation trial palpates: a scene file, or a generated rehearsal case
// (models/case_generator: the same seed and difficulty always give the same case), with its
// ground truth. A case without tumors is a normal case: "nothing there" is its right answer.
struct LocalisationCase {
  std::string name;                          // the scene's own name ("case-medium-42", "phantom-abc")
  std::filesystem::path scene_file;          // a file's case (resolved against the protocol's folder)
  std::optional<std::uint64_t> seed;         // a generated case's seed
  std::optional<CaseDifficulty> difficulty;  // a generated case's difficulty
  std::vector<TumorTruth> tumors;            // outlines; empty: a normal case
  bool generated() const noexcept { return seed.has_value(); }
  bool normal() const noexcept { return tumors.empty(); }
};

// What a localisation protocol presents (study/localisation_case.hpp gives each trial's case):
//   "scene": one case, every trial                        (cases.size() == 1, listed false)
//   "cases": a set, each case one item of the order (as combinations are for discrimination;
//            PlannedTrial::combination is its index)         (listed true)
//   "generate": {"difficulty"}: every trial a new generated case, seeded by the session seed and
//            the trial's position, its seed stored with the trial   (generate set, cases empty)
struct LocalisationTask {
  std::vector<LocalisationCase> cases;
  bool listed = false;
  std::optional<CaseDifficulty> generate;
  double tolerance_mm = 5.0;  // a mark within radius + tolerance of a tumor's centre hits it
};

// The optional confidence rating after each discrimination answer ("confidence" in the file).
// levels == 0: not asked (every protocol without the field); otherwise ratings 1..levels.
struct ConfidenceScale {
  int levels = 0;
  std::vector<std::string> labels;  // empty, or exactly `levels` names ("guess" .. "sure")
  bool asked() const noexcept { return levels > 0; }
  bool valid(int rating) const noexcept { return rating >= 1 && rating <= levels; }
};

inline constexpr int kMinConfidenceLevels = 2;
inline constexpr int kMaxConfidenceLevels = 9;  // one key 1..9 per level

// Whether the participant is told how each trial went (study/trial_feedback.hpp).
enum class Feedback { none, practice, all };

struct Protocol {
  std::string source;  // the file it came from, for messages
  std::string name;
  std::string bids_task;  // task label in exported file names (letters and digits)
  std::string description;
  TaskKind task = TaskKind::discrimination;
  std::array<std::string, kFingerCount> finger_names{"finger1", "finger2", "finger3"};
  std::vector<std::pair<int, int>> adjacent_fingers;  // 0-based pairs
  std::vector<double> levels_kPa;
  std::vector<StimulusCombination> combinations;
  std::string combinations_how_chosen;
  std::vector<Condition> conditions;
  int repetitions = 1;
  int blocks_per_condition = 1;
  int practice_trials = 0;     // at the start of each condition
  int break_every_trials = 0;  // 0: breaks only between blocks
  Counterbalancing counterbalancing = Counterbalancing::none;
  Randomisation randomisation;
  Timing timing;
  LocalisationTask localisation;       // task == localisation only
  ConfidenceScale confidence;          // discrimination only; not asked unless the file says so
  Feedback feedback = Feedback::none;  // "feedback": none (default), practice trials only, all
  nlohmann::json snapshot;             // the file as read, stored with every session
};

// How many different items the order draws from: the combinations (discrimination), the listed
// cases (localisation "cases"), else 1.
int order_items(const Protocol& protocol) noexcept;

// Throws InputError (file, field, what was expected).
Protocol load_protocol(const std::filesystem::path& path);
// `base_dir` resolves relative paths (the scene of a localisation protocol).
Protocol parse_protocol(const nlohmann::json& document, const std::string& source,
                        const std::filesystem::path& base_dir);

// Paper 002's tumor rule on one pressure pattern: all equal -> no tumor; otherwise exactly two
// levels, the higher under one finger or under two adjacent fingers -> tumor under those.
// Returns false (with the reason) for patterns the rule cannot classify.
bool classify_by_tumor_rule(const std::array<double, kFingerCount>& pressure_kPa,
                            const std::vector<std::pair<int, int>>& adjacent_fingers, FingerFlags& tumor,
                            std::string& reason);

}  // namespace palprig
