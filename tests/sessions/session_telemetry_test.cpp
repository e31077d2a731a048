// A study session's telemetry (StudySessionRequest::telemetry_file, `experiment run
// --telemetry`): every rig tick of the session, on the session clock the stored onsets use, so
// an analyst can line each trial's stimulus up with what the regulators did.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/input_error.hpp"
#include "sessions/study_session.hpp"
#include "store/trial_store.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

using testing::ScratchDir;

struct Tick {
  double t_s;
  std::array<double, kFingerCount> target_kPa;
};

// The telemetry CSV's t_s and target_kPa_1..3 columns, found by header name.
std::vector<Tick> read_ticks(const std::filesystem::path& csv) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  for (std::stringstream header(line); std::getline(header, line, ',');) names.push_back(line);
  auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
  };
  const std::size_t t_col = column("t_s");
  const std::array<std::size_t, kFingerCount> target_col{column("target_kPa_1"), column("target_kPa_2"),
                                                         column("target_kPa_3")};
  std::vector<Tick> ticks;
  while (std::getline(in, line)) {
    std::vector<double> v;
    for (std::stringstream row(line); std::getline(row, line, ',');) v.push_back(std::stod(line));
    ticks.push_back({v.at(t_col), {v.at(target_col[0]), v.at(target_col[1]), v.at(target_col[2])}});
  }
  return ticks;
}

StudySessionRequest request_in(const ScratchDir& dir) {
  StudySessionRequest r;
  r.protocol_file = testing::protocols_dir() / "discrimination_002.json";
  r.participant_code = "sim:12";
  r.store_location = (dir / "s.db").string();
  r.rig_file = testing::source_dir() / "data" / "rigs" / "simulated.json";
  r.telemetry_file = dir / "session.csv";
  return r;
}

TEST(experiments_session_telemetry, each_trials_stimulus_is_in_the_recording_at_its_stored_onset) {
  ScratchDir dir;
  const StudySessionRequest request = request_in(dir);
  SessionListener quiet;
  const SessionEnd end = run_study_session(request, {}, quiet, RunControl{});
  ASSERT_TRUE(end.completed) << end.fault;
  EXPECT_EQ(end.telemetry_file, request.telemetry_file);
  EXPECT_EQ(end.telemetry_dropped, 0u) << "simulated time waits for the writer";
  const std::vector<Tick> ticks = read_ticks(request.telemetry_file);
  ASSERT_EQ(ticks.size(), end.telemetry_records);

  const auto store = open_trial_store(request.store_location, TrialStore::Access::read_only);
  const auto trials = store->read_trials(true);
  ASSERT_EQ(trials.size(), 32u);
  int simultaneous_checked = 0;
  for (const StoredTrial& trial : trials) {
    if (trial.mode != "simultaneous" || !trial.response_time_s) continue;
    // The ticks at the onset: the last of them commands the trial's levels on every finger
    // (a vent of the inter-trial interval may share its time stamp).
    const auto after = std::upper_bound(ticks.begin(), ticks.end(), trial.onset_s,
                                        [](double t, const Tick& k) { return t + 1e-9 < k.t_s; });
    ASSERT_NE(after, ticks.begin());
    const auto at = std::prev(after);
    EXPECT_NEAR(at->t_s, trial.onset_s, 1e-5);
    for (std::size_t f = 0; f < kFingerCount; ++f)
      EXPECT_NEAR(at->target_kPa[f], trial.stimulus_kPa[f].value(), 1e-9)
          << "trial " << trial.position << " finger " << f;
    // The last tick before the onset commands nothing (the inter-trial interval is vented).
    const auto before = std::lower_bound(ticks.begin(), ticks.end(), trial.onset_s,
                                         [](const Tick& k, double t) { return k.t_s < t - 1e-9; });
    if (before != ticks.begin()) {
      for (std::size_t f = 0; f < kFingerCount; ++f) EXPECT_EQ(std::prev(before)->target_kPa[f], 0.0);
    }
    ++simultaneous_checked;
  }
  EXPECT_GT(simultaneous_checked, 10);
}

TEST(experiments_session_telemetry, an_earlier_recording_is_never_overwritten) {
  ScratchDir dir;
  StudySessionRequest request = request_in(dir);
  {
    std::ofstream earlier(request.telemetry_file);
    earlier << "an earlier attempt's recording\n";
  }
  SessionListener quiet;
  try {
    run_study_session(request, {}, quiet, RunControl{});
    FAIL() << "an existing recording was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "telemetry");
    EXPECT_EQ(e.file(), request.telemetry_file.string());
  }
  std::ifstream kept(request.telemetry_file);
  std::string line;
  std::getline(kept, line);
  EXPECT_EQ(line, "an earlier attempt's recording");
  EXPECT_FALSE(std::filesystem::exists(request.store_location)) << "refused before the store was opened";
}

}  // namespace
}  // namespace palprig
