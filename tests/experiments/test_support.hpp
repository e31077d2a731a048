#pragma once
// Shared helpers of the experiments tests: a scratch folder per test, the shipped protocols,
// and a recording stimulus output.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

#include "experiments/stimulus_output.hpp"

namespace palprig::testing {

inline std::filesystem::path source_dir() { return PALPRIG_SOURCE_DIR; }
inline std::filesystem::path protocols_dir() { return source_dir() / "data" / "protocols"; }

// A fresh empty folder named after the running test, removed by the destructor.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("palprig-exp-" + std::string(info->test_suite_name()) + "-" + info->name() + "-" +
             std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

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
