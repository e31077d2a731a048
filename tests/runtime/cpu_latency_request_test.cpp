// CpuLatencyRequest: the PM QoS request held while the real-time loop runs.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <pthread.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <cstdint>
#include <thread>

#include "runtime/cpu_latency_request.hpp"
#include "runtime/realtime.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig;
using palprig::test_support::TempDir;

namespace {

// /dev/cpu_dma_latency reads back the current system-wide target as a 32-bit value.
std::int32_t current_target_us() {
  const int fd = ::open(kCpuDmaLatencyPath, O_RDONLY);
  if (fd < 0) return -1;
  std::int32_t v = -1;
  if (::read(fd, &v, sizeof v) != sizeof v) v = -1;
  ::close(fd);
  return v;
}

}  // namespace

TEST(CpuLatencyRequest, WritesZeroAsA32BitValue) {
  TempDir d;
  const auto path = d.write("cpu_dma_latency", "");
  {
    CpuLatencyRequest req(0, path.string());
    ASSERT_TRUE(req.held()) << req.note();
    EXPECT_TRUE(req.note().empty());
  }
  const std::string bytes = test_support::read_file(path);
  ASSERT_EQ(bytes.size(), 4u);  // binary int32, as cyclictest writes it, not the text "0"
  EXPECT_EQ(bytes, std::string(4, '\0'));
}

TEST(CpuLatencyRequest, MissingDeviceIsOneLineNotAFailure) {
  CpuLatencyRequest req(0, "/nonexistent/cpu_dma_latency");
  EXPECT_FALSE(req.held());
  EXPECT_NE(req.note().find("/nonexistent/cpu_dma_latency"), std::string::npos);
  EXPECT_EQ(req.note().find('\n'), std::string::npos);
}

TEST(CpuLatencyRequest, MovedRequestStaysHeldOnce) {
  TempDir d;
  const auto path = d.write("cpu_dma_latency", "");
  CpuLatencyRequest a(0, path.string());
  ASSERT_TRUE(a.held());
  CpuLatencyRequest b(std::move(a));
  EXPECT_FALSE(a.held());  // NOLINT(bugprone-use-after-move): the moved-from request's state is what is tested
  EXPECT_TRUE(b.held());
  b.release();
  EXPECT_FALSE(b.held());
}

TEST(CpuLatencyRequest, KernelHoldsTheTargetAtZeroWhileHeld) {
  if (::access(kCpuDmaLatencyPath, W_OK) != 0) GTEST_SKIP() << kCpuDmaLatencyPath << " not writable here";
  CpuLatencyRequest req(0);
  ASSERT_TRUE(req.held()) << req.note();
  EXPECT_EQ(current_target_us(), 0);
}

TEST(Realtime, PracticesAreAppliedAndDescribed) {
  // On a thread of its own: FIFO, pinning and slack must not leak into other tests.
  std::string described, note;
  bool slack = false, prefaulted = false, pinned = false;
  std::thread t([&] {
    RealtimeOptions o;
    o.fifo = false;         // whether FIFO is permitted depends on the machine
    o.lock_memory = false;  // likewise
    o.pm_qos = false;
    o.cpu = 0;
    const RealtimeSetup r = enter_realtime(o);
    slack = r.timer_slack_set;
    prefaulted = r.stack_prefaulted;
    pinned = r.pinned;
    note = r.note;
    described = describe_practices(r, o);
    cpu_set_t set;
    CPU_ZERO(&set);
    pthread_getaffinity_np(pthread_self(), sizeof set, &set);
    EXPECT_EQ(CPU_COUNT(&set), 1);
    EXPECT_TRUE(CPU_ISSET(0, &set));
    EXPECT_EQ(prctl(PR_GET_TIMERSLACK, 0, 0, 0, 0), 1);
  });
  t.join();
  EXPECT_TRUE(slack) << note;
  EXPECT_TRUE(prefaulted);
  EXPECT_TRUE(pinned) << note;
  EXPECT_EQ(described, "timer slack 1 ns, stack prefaulted 256 KiB, CPU 0");
}

TEST(Realtime, ImpossibleCpuIsANoteNotAFailure) {
  std::string note;
  bool pinned = true;
  std::thread t([&] {
    RealtimeOptions o;
    o.fifo = o.lock_memory = o.pm_qos = false;
    o.cpu = 1000;
    const RealtimeSetup r = enter_realtime(o);
    pinned = r.pinned;
    note = r.note;
  });
  t.join();
  EXPECT_FALSE(pinned);
  EXPECT_NE(note.find("CPU 1000"), std::string::npos);
}
