// Feedback to the participant (experiments/trial_feedback): only where the protocol asks for it,
// and the words the terminal and the window both show.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "study/trial_feedback.hpp"
#include "core/input_error.hpp"
#include "tests/support/process_support.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

Protocol protocol_with(const char* feedback) {
  auto doc = nlohmann::json::parse(R"({
    "version": 1, "name": "fb", "task": "discrimination", "levels_kPa": [0, 30],
    "fingers": ["index", "middle", "ring"],
    "combinations": {"how_chosen": "test", "list_kPa": [[0, 30, 0], [0, 0, 0]]},
    "conditions": [{"name": "three", "mode": "simultaneous"}]
  })");
  if (feedback) doc["feedback"] = feedback;
  return parse_protocol(doc, "fb.json", ".");
}

TrialRecord answered(const FingerFlags& truth, const FingerFlags& answer, bool practice = false) {
  TrialRecord t;
  t.planned.practice = practice;
  t.truth = truth;
  t.answer = answer;
  t.answered = true;
  return t;
}

TEST(experiments_trial_feedback, none_unless_the_protocol_asks) {
  EXPECT_EQ(protocol_with(nullptr).feedback, Feedback::none);
  EXPECT_FALSE(trial_feedback(protocol_with(nullptr), answered({false, true, false}, {true, false, false})));
  EXPECT_FALSE(trial_feedback(protocol_with("none"), answered({false, true, false}, {false, true, false})));
  const Protocol practice = protocol_with("practice");
  EXPECT_FALSE(trial_feedback(practice, answered({false, true, false}, {false, true, false}, false)));
  EXPECT_EQ(trial_feedback(practice, answered({false, true, false}, {false, true, false}, true)), "Correct.");
  EXPECT_THROW(protocol_with("sometimes"), InputError);
}

TEST(experiments_trial_feedback, says_where_the_tumor_was_against_the_answer) {
  const Protocol p = protocol_with("all");
  EXPECT_EQ(trial_feedback(p, answered({false, true, false}, {false, true, false})), "Correct.");
  EXPECT_EQ(trial_feedback(p, answered({false, true, false}, {true, false, false})),
            "Not quite: the tumor was under middle; you answered index.");
  EXPECT_EQ(trial_feedback(p, answered({false, false, false}, {true, true, false})),
            "Not quite: there was no tumor; you answered index and middle.");
  EXPECT_EQ(trial_feedback(p, answered({true, true, false}, {false, false, false})),
            "Not quite: the tumor was under index and middle; you answered no finger.");
  TrialRecord late;
  EXPECT_EQ(trial_feedback(p, late), "No answer in time.");
}

TEST(experiments_trial_feedback, localisation_names_the_tumors_found_and_missed) {
  Protocol p = protocol_with("all");
  p.task = TaskKind::localisation;
  TrialRecord t;
  t.answered = true;
  t.localisation.tumors = {{"A", true, 1.0}, {"B", false, 20.0}, {"C", true, 2.0}};
  t.localisation.false_marks = 2;
  EXPECT_EQ(trial_feedback(p, t), "Found: A, C. Missed: B. Marks on no tumor: 2.");
}

// The terminal prints it after each committed trial, a person's session only.
TEST(experiments_trial_feedback, the_terminal_prints_it_after_each_answer) {
  testing::ScratchDir dir;
  auto doc = nlohmann::json::parse(R"({
    "version": 1, "name": "fb-terminal", "task": "discrimination", "levels_kPa": [0, 30],
    "fingers": ["index", "middle", "ring"],
    "combinations": {"how_chosen": "test", "list_kPa": [[0, 30, 0]]},
    "conditions": [{"name": "three", "mode": "simultaneous"}],
    "repetitions": 2, "feedback": "all",
    "timing": {"max_present_s": 0.2, "response_timeout_s": 60, "inter_trial_s": 0.05}
  })");
  const auto protocol = dir / "fb.json";
  {
    std::ofstream out(protocol);
    out << doc.dump();
  }
  const auto run = testing::run_palprig(
      {"experiment", "run", "--protocol", protocol.string(), "--participant", "P1", "--db", (dir / "fb.db").string()},
      "\n2\n1\n");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("  Correct.\n"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("  Not quite: the tumor was under middle; you answered index.\n"), std::string::npos)
      << run.out;
}

}  // namespace
}  // namespace palprig
