// --telemetry must be a regular file or a new path. A FIFO was opened for writing, which waits
// for a reader for ever - before the SIGTERM handler that vents was installed, so the run
// ignored SIGTERM; a device (/dev/zero) is no log either. Both are refused at once, exit 2.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <future>
#include <thread>
#include <string>

#include "controller/telemetry_writer.hpp"
#include "core/input_error.hpp"
#include "tests/support/run_process.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig;
using palprig::test_support::palprig_bin;
using palprig::test_support::run_process;
using palprig::test_support::TempDir;

namespace {

std::string writer_refusal(const std::filesystem::path& p) {
  auto future = std::async(std::launch::async, [&]() -> std::string {
    try {
      TelemetryWriter w(p, TelemetryFormat::binary);
    } catch (const InputError& e) {
      return e.what();
    }
    return "accepted";
  });
  if (future.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
    ADD_FAILURE() << "the telemetry writer blocked on " << p;
    const int fd = ::open(p.c_str(), O_RDONLY | O_NONBLOCK);  // a reader releases the writer's open
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    if (fd >= 0) ::close(fd);
  }
  return future.get();
}

}  // namespace

TEST(TelemetryPath, AFifoOrADeviceIsRefusedWithoutBlocking) {
  TempDir dir;
  const auto fifo = dir.path() / "t.bin";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(writer_refusal(fifo),
            fifo.string() + ": telemetry: a regular file (or a new path) to write telemetry to, got a FIFO");
  EXPECT_EQ(writer_refusal("/dev/zero"),
            "/dev/zero: telemetry: a regular file (or a new path) to write telemetry to, got a device");
  std::filesystem::create_directory(dir.path() / "folder");
  EXPECT_NE(writer_refusal(dir.path() / "folder").find("got a directory"), std::string::npos);
  // A new path and an existing regular file are taken (the latter truncated).
  EXPECT_EQ(writer_refusal(dir.path() / "new.bin"), "accepted");
  const auto old = dir.write("old.bin", "previous");
  EXPECT_EQ(writer_refusal(old), "accepted");
  EXPECT_EQ(std::filesystem::file_size(old), 16u);  // just the new header
}

TEST(TelemetryPath, RunWithAFifoExitsTwoAtOnceInsteadOfHanging) {
  TempDir dir;
  const auto fifo = dir.path() / "t.csv";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // Before the fix this hung in open() and SIGTERM (from timeout) did not end it cleanly.
  const auto r = run_process("timeout -s TERM 20 " + palprig_bin() + " run --scene " + std::string(PALPRIG_SOURCE_DIR) +
                             "/data/scenes/phantom_abc.json --telemetry " + fifo.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("palprig: " + fifo.string() + ": telemetry: a regular file (or a new path)", 0), 0u) << r.err;
}
