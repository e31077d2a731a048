// Over 400 lines: every case drives the same in-process Modbus server fixture.
// ModbusRig against the simulated rig served as a real Modbus TCP server on 127.0.0.1, in
// process: exact register words, several clients, a lost and returning peer, a device that
// refuses the map, a silent loop, and multi-module maps.
#include <gtest/gtest.h>
#include <modbus.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <memory>
#include <thread>
#include <vector>

#include "rigs/modbus_rig.hpp"
#include "rigs/modbus_sim_server.hpp"
#include "controller/rig_step.hpp"
#include "formats/rig_file.hpp"
#include "core/input_error.hpp"
#include "tests/support/modbus_support.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig;
using namespace std::chrono_literals;
using palprig::test_support::TempDir;

namespace {

RigConfig loopback_rig(const std::string& name) {
  return load_rig_file(std::string(PALPRIG_SOURCE_DIR) + "/data/rigs/" + name);
}

std::array<PlantParams, kFingerCount> loopback_plants() {
  PlantParams p;
  p.noise_sd_kPa = 0;
  p.hysteresis_kPa = 0;
  p.dead_time_s = 0;
  p.time_constant_s = 0.01;
  return {p, p, p};
}

// The client's view of a map whose links were served on `ports`.
ModbusRigConfig client_map(ModbusRigConfig map, const std::vector<int>& ports) {
  for (std::size_t i = 0; i < map.links.size(); ++i) {
    map.links[i].host = "127.0.0.1";
    map.links[i].port = ports[i];
  }
  map.io_thread_fifo_priority = 0;
  return map;
}

std::vector<int> serve(ModbusSimServer& server, std::size_t links) {
  server.start(std::vector<ListenAddress>(links, ListenAddress{"127.0.0.1", 0}));
  std::vector<int> ports;
  for (std::size_t i = 0; i < links; ++i) ports.push_back(server.port(i));
  return ports;
}

// The rig file's map served by a simulated module on loopback (a listener per link) and a client
// rig opened on it, its log lines to `log` (empty: dropped): where most cases here start.
struct ServedModule {
  const ModbusRigConfig map;
  ModbusSimServer server;
  std::vector<int> ports;
  std::unique_ptr<ModbusRig> rig;
  explicit ServedModule(const std::string& rig_file, ModbusRig::LogSink log = nullptr)
      : map(loopback_rig(rig_file).modbus.value()), server(map, loopback_plants()) {
    server.set_log_sink(nullptr);
    ports = serve(server, map.links.size());
    rig = std::make_unique<ModbusRig>(client_map(map, ports));
    rig->set_log_sink(std::move(log));
    rig->open();
  }
};

// Act as the loop: write `setpoint` every millisecond until `done` or the timeout.
bool drive(RigBackend& rig, const ChannelPressures& setpoint, std::chrono::milliseconds timeout,
           const std::function<bool()>& done) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  if (!rig.armed()) rig.arm();  // as the loop does at its start
  double t = 0;
  while (std::chrono::steady_clock::now() < end) {
    rig.write(setpoint, t += 0.001);
    ChannelPressures monitors;
    rig.read_monitors(monitors, t);
    if (done()) return true;
    std::this_thread::sleep_for(1ms);
  }
  return false;
}

struct Quiet {  // collects the rig's log lines instead of printing them
  std::vector<std::string> lines;
  std::mutex m;
  ModbusRig::LogSink sink() {
    return [this](const std::string& l) {
      std::lock_guard<std::mutex> g(m);
      lines.push_back(l);
    };
  }
  bool contains(const std::string& s) {
    std::lock_guard<std::mutex> g(m);
    for (const auto& l : lines)
      if (l.find(s) != std::string::npos) return true;
    return false;
  }
};

}  // namespace

TEST(ModbusLoopback, WritesTheExactWordsOfTheMapAndReadsMonitorsBack) {
  Quiet log;
  ServedModule module("wago_750_559.json", log.sink());
  ModbusSimServer& server = module.server;
  ModbusRig& rig = *module.rig;
  EXPECT_TRUE(rig.linked());
  // 11.75 kPa (paper 002's hard-nodule pressure) -> 1.175 V -> 3850 counts of 32767;
  // 25 kPa -> 8192; 0 kPa -> 0.
  const ChannelPressures setpoint{11.75, 25.0, 0.0};
  const std::array<std::uint16_t, kFingerCount> expected{3850, 8192, 0};
  EXPECT_TRUE(drive(rig, setpoint, 3000ms, [&] { return server.output_words() == expected; }))
      << server.output_words()[0] << " " << server.output_words()[1] << " " << server.output_words()[2];
  // The plant follows and its monitor (ITV style, 25 kPa/V from 1 V) comes back over the bus.
  ChannelPressures monitors{};
  EXPECT_TRUE(drive(rig, setpoint, 3000ms,
                    [&] {
                      rig.read_monitors(monitors, 0);
                      return std::fabs(monitors[0] - 11.75) < 0.05 && std::fabs(monitors[1] - 25.0) < 0.05 &&
                             std::fabs(monitors[2]) < 0.05;
                    }))
      << monitors[0] << " " << monitors[1] << " " << monitors[2];
  rig.close();
  EXPECT_EQ(server.output_words(), (std::array<std::uint16_t, kFingerCount>{0, 0, 0}));  // close() vents
  EXPECT_TRUE(log.contains("bus cycles"));
}

TEST(ModbusLoopback, ServesSeveralClientsAtOnce) {
  Quiet log;
  ServedModule module("wago_750_559.json", log.sink());
  ModbusSimServer& server = module.server;
  ModbusRig& rig = *module.rig;
  const std::vector<int>& ports = module.ports;
  // A second client, e.g. a lab's logger, reads the monitors and outputs while the rig runs.
  modbus_t* other = modbus_new_tcp("127.0.0.1", ports[0]);
  ASSERT_EQ(modbus_connect(other), 0);
  const ChannelPressures setpoint{20.0, 20.0, 20.0};
  std::uint16_t outputs[3] = {}, monitors[3] = {};
  EXPECT_TRUE(drive(rig, setpoint, 3000ms,
                    [&] {
                      return modbus_read_registers(other, 0, 3, outputs) == 3 &&
                             modbus_read_input_registers(other, 0, 3, monitors) == 3 && outputs[0] == 6553 &&
                             monitors[0] > 3277;  // 2 V of 10 V; monitor above its 1 V zero
                    }))
      << outputs[0] << " " << monitors[0];
  EXPECT_EQ(server.clients(), 2);
  modbus_close(other);
  modbus_free(other);
  rig.close();
}

TEST(ModbusLoopback, LostPeerVentsAlarmsReconnectsAndRampsFromZero) {
  TempDir dir;
  ModbusRigConfig map = loopback_rig("wago_750_559.json").modbus.value();
  auto server = std::make_unique<ModbusSimServer>(map, loopback_plants());
  server->set_log_sink(nullptr);
  const auto ports = serve(*server, 1);
  ModbusRigConfig cmap = client_map(map, ports);
  cmap.reconnect_initial_s = 0.02;
  cmap.reconnect_max_s = 0.1;
  ModbusRig rig(cmap);
  Quiet log;
  rig.set_log_sink(log.sink());
  rig.open();
  const ChannelPressures setpoint{40.0, 40.0, 40.0};  // 4 V -> 13107 counts
  ASSERT_TRUE(drive(rig, setpoint, 3000ms, [&] { return server->output_words()[0] == 13107; }));

  server.reset();  // the module disappears
  ASSERT_TRUE(drive(rig, setpoint, 2000ms, [&] { return !rig.linked(); }));
  ChannelPressures monitors{};
  rig.read_monitors(monitors, 0);
  EXPECT_TRUE(std::isnan(monitors[0]));  // no reading is reported as none, not as the last one
  EXPECT_TRUE(log.contains("lost"));
  EXPECT_GE(rig.forced_vents(), 1u);  // the vent on a lost link is counted as well
  // Still down a while later: the rig keeps trying, the loop is never blocked.
  EXPECT_FALSE(drive(rig, setpoint, 150ms, [&] { return rig.linked(); }));

  // The module returns on the same port.
  ModbusSimServer back(map, loopback_plants());
  back.set_log_sink(nullptr);
  const auto log_path = dir.path() / "writes.csv";
  back.set_write_log(log_path);
  back.start({ListenAddress{"127.0.0.1", ports[0]}});
  ASSERT_TRUE(drive(rig, setpoint, 3000ms, [&] { return rig.linked(); }));
  ASSERT_TRUE(drive(rig, setpoint, 3000ms, [&] { return back.output_words()[0] == 13107; }));
  rig.close();
  back.stop();
  EXPECT_TRUE(log.contains("back after"));

  // No spike: the returning module is first written 0 kPa, then the pressure rises no faster
  // than the rig's slew limit (2000 kPa/s) allows between two writes, up to the setpoint. The
  // times are the server's, when each write arrived; the ramp runs on the bus thread's clock
  // when it sent them. On a busy machine (a sanitizer build beside other suites) one write can
  // arrive late and the next on time, so two arrivals 0.4 ms apart carried values sent 7 ms
  // apart: the bound allows two bus periods and 10 ms of such scheduling slack. A spike, the
  // whole 40 kPa in one write a bus period after the last, is still far above it.
  const auto writes = palprig::test_support::read_csv(log_path.string());
  ASSERT_GT(writes.rows.size(), 6u);
  const std::size_t t = writes.col("t_s"), ch = writes.col("channel"), kpa = writes.col("kPa");
  EXPECT_EQ(writes.rows[0][kpa], 0.0);
  std::array<double, 4> last_kPa{}, last_t{};
  double peak = 0;
  for (const auto& row : writes.rows) {
    const auto c = static_cast<std::size_t>(row[ch]);
    if (last_t[c] > 0) {
      const double allowed = 2000.0 * (row[t] - last_t[c] + 2.0 / cmap.io_rate_hz + 0.010) + 0.01;
      EXPECT_LE(row[kpa] - last_kPa[c], allowed) << "at t=" << row[t];
    }
    last_kPa[c] = row[kpa];
    last_t[c] = row[t] > 0 ? row[t] : 1e-9;
    peak = std::max(peak, row[kpa]);
  }
  EXPECT_LE(peak, 40.0 + 0.01);
}

TEST(ModbusLoopback, OutputsRiseFromZeroUnderTheSlewLimitAfterOpen) {
  TempDir dir;
  const ModbusRigConfig map = loopback_rig("wago_750_559.json").modbus.value();
  ModbusSimServer server(map, loopback_plants());
  server.set_log_sink(nullptr);
  const auto log_path = dir.path() / "writes.csv";
  server.set_write_log(log_path);
  ModbusRigConfig cmap = client_map(map, serve(server, 1));
  ModbusRig rig(cmap);
  rig.set_log_sink(nullptr);
  rig.open();
  std::this_thread::sleep_for(20ms);  // a few bus cycles at 0 kPa before the loop's first write
  // The loop asks for 50 kPa at once (a tick's first setpoint is not slew-limited).
  ASSERT_TRUE(drive(rig, {50, 50, 50}, 3000ms, [&] { return server.output_words()[0] == 16384; }));
  rig.close();
  server.stop();
  const auto writes = palprig::test_support::read_csv(log_path.string());
  const std::size_t t = writes.col("t_s"), ch = writes.col("channel"), kpa = writes.col("kPa");
  // The writes are timed where the server receives them, not where the bus thread sent them: one
  // write delivered late makes the next look steeper by the delay (under the sanitizers with other
  // suites beside it, once 8.82 kPa against the 8.76 kPa that two bus periods of slack allowed).
  // So each step gets the slack of the returning-module case above (two periods and 10 ms: a
  // missing ramp is still a 50 kPa jump), and the whole rise is held to the rate, which delivery
  // delays cannot fake: from the first write above 0 to the first at 50 kPa takes at least
  // (50 - first) / 2000 s, less two periods for the two writes' delivery. Channels are 1..3.
  const double period_s = 1.0 / cmap.io_rate_hz;
  std::array<double, 4> last_kPa{}, last_t{}, first_t{}, first_kPa{}, top_t{};
  std::array<bool, 4> seen{}, rising{}, topped{};
  std::array<std::size_t, 4> rising_writes{};
  for (const auto& row : writes.rows) {
    const auto c = static_cast<std::size_t>(row[ch]);
    if (seen[c]) {
      EXPECT_LE(row[kpa] - last_kPa[c], 2000.0 * (row[t] - last_t[c] + 2 * period_s + 0.010) + 0.01)
          << "at t=" << row[t];
    }
    if (row[kpa] > 0 && !rising[c]) {
      rising[c] = true;
      first_t[c] = row[t];
      first_kPa[c] = row[kpa];
    }
    if (row[kpa] >= 49.99 && !topped[c]) {
      topped[c] = true;
      top_t[c] = row[t];
    }
    if (row[kpa] > 0 && row[kpa] < 49.99) ++rising_writes[c];
    seen[c] = true;
    last_kPa[c] = row[kpa];
    last_t[c] = row[t];
  }
  ASSERT_TRUE(topped[1]) << "channel 1 never reached 50 kPa";  // what the drive waited for
  for (std::size_t c = 1; c <= kFingerCount; ++c) {
    if (!topped[c]) continue;  // a channel whose 50 kPa write came after channel 1's and the close
    EXPECT_GE(top_t[c] - first_t[c], (50.0 - first_kPa[c]) / 2000.0 - 2 * period_s) << "channel " << c;
    // A ramp, not a jump: writes between 0 and 50 kPa. 50 kPa at 2000 kPa/s takes 25 ms, about 12
    // bus cycles; the bus slews by the time that passed, so a bus thread the machine stalled for
    // part of the rise sends fewer of them (4 a channel once on a loaded virtual machine), and
    // the rise's duration above is what holds the rate.
    EXPECT_GE(rising_writes[c], 2u) << "channel " << c;
  }
}

TEST(ModbusLoopback, TheBusThreadVentsWhenTheLoopFallsSilent) {
  Quiet log;
  ServedModule module("wago_750_559.json", log.sink());
  ModbusSimServer& server = module.server;
  ModbusRig& rig = *module.rig;
  ASSERT_TRUE(drive(rig, {30, 30, 30}, 3000ms, [&] { return server.output_words()[2] == 9830; }));
  EXPECT_EQ(rig.forced_vents(), 0u);
  // No more writes: after setpoint_timeout (100 ms) the I/O thread vents on its own.
  const auto end = std::chrono::steady_clock::now() + 2s;
  while (server.output_words()[2] != 0 && std::chrono::steady_clock::now() < end) std::this_thread::sleep_for(5ms);
  EXPECT_EQ(server.output_words(), (std::array<std::uint16_t, kFingerCount>{0, 0, 0}));
  EXPECT_TRUE(rig.linked());  // silence is the loop's, not the link's
  // ... but the vent is counted (before the outputs went to 0) and said, once.
  EXPECT_EQ(rig.forced_vents(), 1u);
  EXPECT_TRUE(log.contains("no setpoint from the loop for more than 0.1"));
  // The loop back: pressure again, the count unchanged.
  ASSERT_TRUE(drive(rig, {30, 30, 30}, 3000ms, [&] { return server.output_words()[2] == 9830; }));
  EXPECT_EQ(rig.forced_vents(), 1u);
  rig.close();
}

// A machine that stalls the loop's thread past the bus's setpoint timeout: the I/O thread vents,
// and the loop's next setpoint ramps the plant up again from 0 kPa. RigStep's next step is not
// linked (the sweep then redoes its hold from the right hysteresis branch: a deflation
// hold once read 2 kPa below its level, the rising branch, on a sanitizer run). A vented loop
// (every setpoint 0) that falls silent loses nothing and is not counted.
TEST(ModbusLoopback, ALoopStalledPastTheSetpointTimeoutFindsItsNextStepNotLinked) {
  ServedModule module("wago_750_559.json");
  ModbusSimServer& server = module.server;
  ModbusRig& rig = *module.rig;
  RigStep step(TickConfig{}, rig);
  ASSERT_EQ(step.arm(), BackendStatus::ok);
  double t = 0;
  auto step_for = [&](double level, std::chrono::milliseconds how_long) {
    const auto end = std::chrono::steady_clock::now() + how_long;
    while (std::chrono::steady_clock::now() < end) {
      step.step_direct({level, level, level}, t += 0.001);
      std::this_thread::sleep_for(1ms);
    }
  };
  step_for(0, 300ms);  // vented, then silent for 300 ms: nothing to lose
  std::this_thread::sleep_for(300ms);
  EXPECT_TRUE(step.step_direct({0, 0, 0}, t += 0.001).linked);
  EXPECT_EQ(rig.forced_vents(), 0u);

  const auto until = std::chrono::steady_clock::now() + 3s;
  while (server.output_words()[0] != 9830 && std::chrono::steady_clock::now() < until) step_for(30, 10ms);
  ASSERT_EQ(server.output_words()[0], 9830);
  EXPECT_EQ(step.vents_between_steps(), 0u);
  // The stall: no step until the bus has vented (100 ms of silence; polled, for a busy machine).
  const auto vented_by = std::chrono::steady_clock::now() + 3s;
  while (server.output_words()[0] != 0 && std::chrono::steady_clock::now() < vented_by)
    std::this_thread::sleep_for(5ms);
  ASSERT_EQ(server.output_words()[0], 0);
  const StepResult& r = step.step_direct({30, 30, 30}, t += 0.001);
  EXPECT_FALSE(r.linked);
  EXPECT_EQ(step.vents_between_steps(), 1u);
  EXPECT_EQ(step.link_outages(), 0u);  // the link held: the silence was the loop's
  std::this_thread::sleep_for(1ms);
  EXPECT_TRUE(step.step_direct({30, 30, 30}, t += 0.001).linked);
  EXPECT_EQ(step.vents_between_steps(), 1u);
  step.disarm();
  rig.close();
}

TEST(ModbusLoopback, AnOutageLongerThanTheLimitIsABackendError) {
  const ModbusRigConfig map = loopback_rig("wago_750_559.json").modbus.value();
  auto server = std::make_unique<ModbusSimServer>(map, loopback_plants());
  server->set_log_sink(nullptr);
  ModbusRigConfig cmap = client_map(map, serve(*server, 1));
  cmap.max_outage_s = 0.2;
  ModbusRig rig(cmap);
  rig.set_log_sink(nullptr);
  rig.open();
  server.reset();
  bool failed = false;
  drive(rig, {10, 10, 10}, 3000ms, [&] { return failed = rig.write({10, 10, 10}, 0) == BackendStatus::error; });
  EXPECT_TRUE(failed);
  EXPECT_NE(std::string(rig.last_error()).find("max_outage_s"), std::string::npos) << rig.last_error();
  rig.close();
}

TEST(ModbusLoopback, ADeviceThatRefusesTheMapIsRefusedAtOpen) {
  const ModbusRigConfig map = loopback_rig("wago_750_559.json").modbus.value();
  ModbusSimServer server(map, loopback_plants());  // serves holding registers 0..2 only
  server.set_log_sink(nullptr);
  ModbusRigConfig wrong = client_map(map, serve(server, 1));
  wrong.channels[2].output.address = 7;
  ModbusRig rig(wrong);
  rig.set_log_sink(nullptr);
  try {
    rig.open();
    FAIL() << "open() accepted a register the device does not have";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("Illegal data address"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("refused"), std::string::npos) << e.what();
  }
}

TEST(ModbusLoopback, NothingListeningIsRefusedAtOpenWithTheReason) {
  const ModbusRigConfig map = loopback_rig("wago_750_559.json").modbus.value();
  int port;
  {
    ModbusSimServer probe(map, loopback_plants());
    probe.set_log_sink(nullptr);
    port = serve(probe, 1)[0];
  }  // closed again: nothing listens there now
  ModbusRig rig(client_map(map, {port}));
  rig.set_log_sink(nullptr);
  try {
    rig.open();
    FAIL() << "open() succeeded with nothing listening";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("Connection refused"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("127.0.0.1:" + std::to_string(port)), std::string::npos) << e.what();
  }
}

TEST(ModbusLoopback, TwoModuleMapsWriteEachRegisterOnItsOwnLink) {
  // Moxa: outputs on the E1241 at 1024..1026 (12 bit), monitors on the E1240 at 0..2 (16 bit).
  ServedModule module("moxa_iologik_e1241.json");
  ModbusSimServer& server = module.server;
  ModbusRig& rig = *module.rig;
  const std::vector<int>& ports = module.ports;
  const ChannelPressures setpoint{25.0, 12.5, 60.0};
  EXPECT_TRUE(drive(rig, setpoint, 3000ms, [&] {
    return server.output_words() == std::array<std::uint16_t, kFingerCount>{1024, 512, 2457};
  }));
  modbus_t* ao = modbus_new_tcp("127.0.0.1", ports[0]);
  modbus_t* ai = modbus_new_tcp("127.0.0.1", ports[1]);
  ASSERT_EQ(modbus_connect(ao), 0);
  ASSERT_EQ(modbus_connect(ai), 0);
  std::uint16_t words[3] = {};
  EXPECT_EQ(modbus_read_registers(ao, 1024, 3, words), 3);
  EXPECT_EQ(words[0], 1024);
  EXPECT_EQ(modbus_read_registers(ai, 1024, 3, words), -1);  // the AI module has no outputs
  EXPECT_EQ(modbus_read_input_registers(ai, 0, 3, words), 3);
  modbus_close(ao);
  modbus_close(ai);
  modbus_free(ao);
  modbus_free(ai);
  ChannelPressures monitors{};
  EXPECT_TRUE(drive(rig, setpoint, 3000ms, [&] {
    rig.read_monitors(monitors, 0);
    return std::fabs(monitors[2] - 60.0) < 0.1;
  })) << monitors[2];
  rig.close();
}

TEST(ModbusLoopback, RtuOnAPseudoTerminalCarriesTheSameMap) {
  // The map as a lab would wire it on RS-485: one RTU link, unit 7, 115200 8E1.
  ModbusRigConfig map = loopback_rig("wago_750_559.json").modbus.value();
  map.links[0].rtu = true;
  map.links[0].baud = 115200;
  map.links[0].parity = 'E';
  map.links[0].unit_id = 7;
  ModbusSimServer server(map, loopback_plants());
  server.set_log_sink(nullptr);
  ListenAddress pty;
  pty.pty = true;
  try {
    server.start({pty});
  } catch (const palprig::Error& e) {
    GTEST_SKIP() << "this machine gives no pseudo-terminals (" << e.what() << "); the RTU path needs one to run";
  }
  ASSERT_EQ(server.pty_path(0).rfind("/dev/pts/", 0), 0u) << server.pty_path(0);
  ModbusRigConfig cmap = map;
  cmap.links[0].device = server.pty_path(0);
  cmap.io_thread_fifo_priority = 0;
  ModbusRig rig(cmap);
  rig.set_log_sink(nullptr);
  rig.open();
  EXPECT_NE(rig.describe().find("rtu " + server.pty_path(0) + " 115200 8E1"), std::string::npos) << rig.describe();
  const ChannelPressures setpoint{11.75, 25.0, 40.0};
  EXPECT_TRUE(drive(rig, setpoint, 3000ms, [&] {
    return server.output_words() == std::array<std::uint16_t, kFingerCount>{3850, 8192, 13107};
  }));
  ChannelPressures monitors{};
  EXPECT_TRUE(drive(rig, setpoint, 3000ms, [&] {
    rig.read_monitors(monitors, 0);
    return std::fabs(monitors[2] - 40.0) < 0.05;
  })) << monitors[2];
  rig.close();
  // A client addressing another unit on the same bus gets no answer: a timeout, not a reply.
  cmap.links[0].unit_id = 8;
  ModbusRig stranger(cmap);
  stranger.set_log_sink(nullptr);
  EXPECT_THROW(stranger.open(), InputError);
}

TEST(ModbusLoopback, SimulatedModuleWatchdogZeroesOutputsOfASilentLink) {
  const ModbusRigConfig map = loopback_rig("wago_750_559.json").modbus.value();
  ModbusSimServer server(map, loopback_plants());
  Quiet log;
  server.set_log_sink(log.sink());
  server.set_watchdog_s(0.1);
  const auto ports = serve(server, 1);
  modbus_t* client = modbus_new_tcp("127.0.0.1", ports[0]);
  ASSERT_EQ(modbus_connect(client), 0);
  const std::uint16_t words[3] = {13107, 13107, 13107};
  ASSERT_EQ(modbus_write_registers(client, 0, 3, words), 3);
  EXPECT_EQ(server.output_words()[1], 13107);
  // The client goes quiet without venting (a crashed controller): the module's own watchdog
  // takes the outputs to 0 kPa.
  const auto end = std::chrono::steady_clock::now() + 2s;
  while (server.output_words()[1] != 0 && std::chrono::steady_clock::now() < end) std::this_thread::sleep_for(5ms);
  EXPECT_EQ(server.output_words(), (std::array<std::uint16_t, kFingerCount>{0, 0, 0}));
  EXPECT_TRUE(log.contains("watchdog"));
  modbus_close(client);
  modbus_free(client);
}
