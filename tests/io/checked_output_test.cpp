// The one checked writer (io/checked_output.hpp): a file is written whole or not at all, an
// earlier file stays until the new one is complete, and a failure names the file and the reason.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "io/checked_output.hpp"
#include "tests/support/temp_dir.hpp"

namespace palprig {
namespace {

using test_support::read_file;
using test_support::TempDir;

int entries(const std::filesystem::path& folder) {
  int n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(folder)) ++n;
  return n;
}

TEST(CheckedOutput, WritesTheWholeFileAndReplacesTheOldOneKeepingItsMode) {
  TempDir dir;
  const auto path = dir.write("out.csv", "old\n");
  ::chmod(path.c_str(), 0640);
  {
    CheckedOutputFile out(path);
    for (int i = 0; i < 100000; ++i) out.stream() << i << "\n";  // more than one buffer
    EXPECT_EQ(read_file(path), "old\n") << "the old file is replaced only when the new one is complete";
    out.commit();
  }
  const std::string text = read_file(path);
  EXPECT_EQ(text.substr(0, 4), "0\n1\n");
  EXPECT_EQ(text.substr(text.size() - 6), "99999\n");
  struct stat st {};
  ASSERT_EQ(::stat(path.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0640u);
  EXPECT_EQ(entries(dir.path()), 1) << "a temporary file was left";
}

TEST(CheckedOutput, AWriterThatStopsBeforeCommitLeavesTheOldFileAndNoTemporary) {
  TempDir dir;
  const auto path = dir.write("case.json", "{\"old\": true}\n");
  try {
    CheckedOutputFile out(path);
    out.write("{\"new\":");
    throw std::runtime_error("the input was bad half-way");
  } catch (const std::runtime_error&) {}
  EXPECT_EQ(read_file(path), "{\"old\": true}\n");
  EXPECT_EQ(entries(dir.path()), 1);
}

TEST(CheckedOutput, AFullDeviceIsTheFileAndTheSystemsReason) {
  CheckedOutputFile out("/dev/full");
  out.write(std::string(100, 'x'));
  try {
    out.commit();
    FAIL() << "a write to /dev/full was taken as done";
  } catch (const OutputError& e) {
    EXPECT_EQ(std::string(e.what()), "/dev/full: cannot write: No space left on device");
  }
  EXPECT_TRUE(std::filesystem::is_character_file("/dev/full")) << "the device was renamed over";
}

TEST(CheckedOutput, AMissingFolderOrAFolderAsTheFileIsRefusedAtOnce) {
  TempDir dir;
  try {
    CheckedOutputFile out(dir.path() / "no-such-folder" / "map.csv");
    FAIL();
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-folder does not exist"), std::string::npos) << e.what();
  }
  EXPECT_THROW(CheckedOutputFile out(dir.path()), OutputError);
}

}  // namespace
}  // namespace palprig
