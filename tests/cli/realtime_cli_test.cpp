// The real-time command line: palprig rt-check as the lab engineer runs it (short real measured
// runs), and run's --cpu / --no-pm-qos options.
#include <gtest/gtest.h>
#include <sys/utsname.h>

#include <nlohmann/json.hpp>

#include "tests/support/run_process.hpp"

using namespace palprig::test_support;

TEST(RtCheckCli, JsonReportOfAShortRealRun) {
  const ProcessResult r = run_process(palprig_bin() + " rt-check --seconds 1 --rate-hz 500 --json");
  ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 1) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  // Exit 0 exactly when the report says the machine held the rate.
  EXPECT_EQ(j.at("ready").get<bool>(), r.exit_code == 0);
  utsname u{};
  uname(&u);
  EXPECT_EQ(j.at("kernel").at("release"), std::string(u.release));
  EXPECT_EQ(j.at("kernel").at("version"), std::string(u.version));
  const auto& loop = j.at("loop");
  EXPECT_EQ(loop.at("rate_hz"), 500.0);
  EXPECT_EQ(loop.at("budget_us"), 2000.0);
  // 500 periods in 1 s, each either run or skipped after an overrun.
  EXPECT_EQ(loop.at("ticks").get<std::uint64_t>() + loop.at("missed_periods").get<std::uint64_t>(), 500u);
  EXPECT_GT(loop.at("wake_latency").at("p50_us").get<double>(), 0.0);
  EXPECT_GE(loop.at("wake_latency").at("max_us").get<double>(),
            loop.at("wake_latency").at("p999_us").get<double>() - 1.0);
  EXPECT_TRUE(j.at("sched_fifo").contains("permitted"));
  EXPECT_TRUE(j.at("cpu_dma_latency").contains("available"));
  EXPECT_FALSE(j.at("findings").empty());
}

TEST(RtCheckCli, TextReportEndsWithTheVerdict) {
  const ProcessResult r = run_process(palprig_bin() + " rt-check --seconds 0.5");
  ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 1) << r.err;
  EXPECT_NE(
      r.out.find(r.exit_code == 0 ? "palprig rt-check: ready for 1000 Hz" : "palprig rt-check: NOT ready for 1000 Hz"),
      std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("kernel"), std::string::npos);
  EXPECT_NE(r.out.find("wake-up latency p50/p99/p99.9/max"), std::string::npos);
}

TEST(RtCheckCli, BadRateIsRefusedWithExit2) {
  const ProcessResult r = run_process(palprig_bin() + " rt-check --rate-hz 0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--rate-hz"), std::string::npos) << r.err;
}

TEST(RtCheckCli, CpuThatDoesNotExistIsRefusedWithExit2) {
  const ProcessResult r = run_process(palprig_bin() + " rt-check --seconds 0.2 --cpu 1023");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--cpu"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("a CPU this process may run on"), std::string::npos) << r.err;
}

TEST(RunCliRealtime, CpuThatDoesNotExistIsRefusedBeforeAnythingMoves) {
  const ProcessResult r = run_process(palprig_bin() + " run --scene " + source_dir() +
                                      "/data/scenes/phantom_abc.json --realtime --duration-s 0.2 --cpu 1023");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--cpu"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;  // no summary: the loop never ran
}

TEST(RunCliRealtime, SummarySaysWhichPracticesWereInEffect) {
  const ProcessResult r =
      run_process(palprig_bin() + " run --scene " + source_dir() +
                  "/data/scenes/phantom_abc.json --realtime --duration-s 0.2 --no-pm-qos --cpu 0 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const std::string practices = j.at("realtime_practices");
  EXPECT_EQ(practices.find("PM QoS"), std::string::npos) << practices;
  EXPECT_NE(practices.find("CPU 0"), std::string::npos) << practices;
  EXPECT_NE(practices.find("timer slack 1 ns"), std::string::npos) << practices;
}
