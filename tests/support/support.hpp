#pragma once
// Shared helpers of the suites: a scratch folder per test and the shipped protocols
// (no rig code: the analyst-only build uses it too; RecordingOutput is in recording_output.hpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

namespace palprig::testing {

inline std::filesystem::path source_dir() { return PALPRIG_SOURCE_DIR; }
inline std::filesystem::path protocols_dir() { return source_dir() / "data" / "protocols"; }

// A fresh empty folder named after the running test, removed by the destructor.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() / ("palprig-exp-" + std::string(info->test_suite_name()) + "-" +
                                                      info->name() + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

}  // namespace palprig::testing
