#pragma once
// A StimulusOutput that records what the runner asked for (the experiments suites).
#include <string>
#include <vector>

#include "experiments/stimulus_output.hpp"
#include "tests/support/support.hpp"

namespace palprig::testing {

// Records what the runner asked for; the fingers feel exactly the held pressures.
class RecordingOutput final : public StimulusOutput {
 public:
  struct Call {
    std::string what;  // "hold", "vent", "palpate"
    ChannelPressures kPa{};
    double t_s = 0;
  };
  void hold(const ChannelPressures& target_kPa, double t_s) override {
    now_ = target_kPa;
    calls.push_back({"hold", target_kPa, t_s});
  }
  void palpate(const Scene&, InputSource&, double t_s) override { calls.push_back({"palpate", {}, t_s}); }
  void vent(double t_s) override {
    now_ = {};
    calls.push_back({"vent", {}, t_s});
  }
  ChannelPressures service(double) override { return now_; }
  std::string describe() const override { return "recording"; }

  std::vector<Call> calls;

 private:
  ChannelPressures now_{};
};

}  // namespace palprig::testing
