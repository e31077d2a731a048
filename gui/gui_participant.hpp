#pragma once
// GuiParticipant: a person at the window, as experiments' Participant (the terminal and the
// simulated observer are the others). The participant screen (GUI thread) and the session loop
// (session thread) share a ParticipantChannel: "ready" is an atomic flag, answers travel in a
// wait-free LatestValue tagged with the trial's position and a serial number, so an answer
// given for one trial can never be taken for the next, and neither thread ever waits.
#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>

#include "experiments/participant.hpp"
#include "experiments/session_clock.hpp"
#include "gui/window_pen_input.hpp"
#include "runtime/latest_value.hpp"

namespace palprig::gui {

inline constexpr int kMaxMarks = 32;  // marks per localisation answer (a scene has a handful of tumors)

struct GivenAnswer {
  int position = -1;         // the trial answered
  std::uint64_t serial = 0;  // 0: nothing given yet
  FingerFlags tumor_under{};
  int confidence = 0;  // the rating 1..levels given with the answer; 0: none asked
  int mark_count = 0;
  std::array<Mark, kMaxMarks> marks{};
  // When the participant gave it: the input event's own time on steady_clock (ns since its
  // epoch; gui/event_clock.hpp); 0: unknown (timed when the session takes it).
  std::int64_t given_at_ns = 0;
};

class ParticipantChannel {
 public:
  // GUI thread.
  void say_ready() noexcept { ready_.store(true); }
  // A pause: a go-ahead given before it does not start the held trial after it.
  void withdraw_ready() noexcept { ready_.store(false); }
  // The finger answer of trial `position` is given and its rating awaited (-1: none).
  void say_rating(int position) noexcept { rating_for_.store(position); }
  // Returns false when `marks` has more than kMaxMarks marks (nothing is handed over then).
  // `given_at`: when the participant gave it (the key or mouse press's own time).
  bool give_answer(int position, const Response& response,
                   std::optional<std::chrono::steady_clock::time_point> given_at = std::nullopt) noexcept;
  WindowPenInput& pen() noexcept { return pen_; }  // the participant's pen (localisation)

  // Session thread.
  bool take_ready() noexcept { return ready_.exchange(false); }
  // The answer given for `position`, once; `given_at` (optional) receives when it was given.
  std::optional<Response> take_answer(int position,
                                      std::optional<std::chrono::steady_clock::time_point>* given_at = nullptr);
  int rating_for() const noexcept { return rating_for_.load(); }

 private:
  std::atomic<bool> ready_{false};
  std::atomic<int> rating_for_{-1};
  LatestValue<GivenAnswer> answers_;
  std::uint64_t next_serial_ = 1;   // GUI thread
  std::uint64_t taken_serial_ = 0;  // session thread
  WindowPenInput pen_;
};

class GuiParticipant final : public Participant {
 public:
  GuiParticipant(std::shared_ptr<ParticipantChannel> channel, bool palpates)
      : channel_(std::move(channel)), palpates_(palpates) {}
  void session_clock(const SessionClock& clock) override { clock_ = &clock; }
  bool ready(double) override { return channel_->take_ready(); }
  void trial_started(const PlannedTrial& trial, const Condition&, double) override {
    position_ = trial.position;
    finger_answer_at_s_.reset();
    (void)channel_->take_answer(position_);  // one given before a pause does not answer it presented again
  }
  void feel(const FeltSample&) override {}
  // The finger answer's time is noted on the first pass that sees it (the rating comes later),
  // for an answer whose input time is unknown.
  bool answering() override { return channel_->rating_for() == position_; }
  std::optional<Response> answer(double t_s) override {
    if (answering() && !finger_answer_at_s_) finger_answer_at_s_ = t_s;
    std::optional<std::chrono::steady_clock::time_point> given_at;
    auto r = channel_->take_answer(position_, &given_at);
    if (!r) return r;
    // The key or click's own time (the finger answer's, when a rating followed it), on the
    // session's clock; else the pass that first saw it.
    if (given_at && clock_) r->given_at_s = clock_->at_steady(*given_at);
    if (!r->given_at_s && finger_answer_at_s_) r->given_at_s = finger_answer_at_s_;
    return r;
  }
  InputSource* pen() override { return palpates_ ? &channel_->pen() : nullptr; }

 private:
  std::shared_ptr<ParticipantChannel> channel_;
  bool palpates_;
  const SessionClock* clock_ = nullptr;
  int position_ = -1;
  std::optional<double> finger_answer_at_s_;
};

}  // namespace palprig::gui
