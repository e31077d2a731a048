#pragma once
// What the Modbus tests of this folder share: a `palprig run` child against a `palprig sim-rig`
// child (tests/support/modbus_support.hpp), and bounded polls instead of sleeps.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <regex>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "tests/support/modbus_support.hpp"
#include "tests/support/run_process.hpp"
#include "tests/support/temp_dir.hpp"

namespace palprig::test_support {

inline const std::string kWagoRig = std::string(PALPRIG_SOURCE_DIR) + "/data/rigs/wago_750_559.json";
inline const std::string kPhantom = std::string(PALPRIG_SOURCE_DIR) + "/data/scenes/phantom_abc.json";

// The shipped WAGO map on 127.0.0.1:port; deadlines are not what these tests are about, so a
// busy test machine's overruns must not end the run.
inline nlohmann::json wago_on_port(int port) {
  auto rig = rig_on_port(read_json(kWagoRig), port);
  rig["modbus"]["io_thread_fifo_priority"] = 0;
  rig["safety"]["max_consecutive_overruns"] = 1000000;
  rig["safety"]["max_lost_time_s"] = 10;
  return rig;
}

// Lines in a file (0 if it does not exist yet).
inline std::size_t line_count(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::size_t n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}

// Poll until `ready()` or the timeout; returns whether it became ready.
template <class Ready>
bool poll_until(Ready ready, double timeout_s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < end) {
    if (ready()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return ready();
}

inline std::unique_ptr<WatchedProcess> start_palprig_run(const TempDir& dir, const std::string& rig, double seconds) {
  return std::make_unique<WatchedProcess>(
      std::vector<std::string>{palprig_bin(), "run", "--realtime", "--no-fifo", "--rig", rig, "--scene", kPhantom,
                               "--input", "sweep", "--duration-s", std::to_string(seconds), "--telemetry",
                               (dir.path() / "telemetry.csv").string(), "--json"},
      (dir.path() / "run.err").string());
}

struct FinishedRun {
  int exit_code = -1;
  nlohmann::json summary;
  std::string err;
};

inline FinishedRun finish_palprig_run(WatchedProcess& run, const TempDir& dir) {
  FinishedRun r;
  r.exit_code = run.wait();
  r.err = read_file(dir.path() / "run.err");
  try {
    run.wait_for_line(std::regex("^\\}$"), 5.0);
  } catch (const std::exception&) {}
  const std::string out = run.all_output();
  r.summary = nlohmann::json::parse(out, nullptr, false);
  return r;
}

}  // namespace palprig::test_support
