// RigBackend's lifecycle (closed -> connected -> armed -> disarmed -> closed) and capabilities,
// on the simulated rig and on a Modbus rig against the simulator served on loopback (real
// sockets, real register words).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "formats/comedi_config.hpp"
#include "formats/rig_file.hpp"
#include "rigs/comedi_rig.hpp"
#include "rigs/modbus_rig.hpp"
#include "rigs/modbus_sim_server.hpp"
#include "rigs/simulated_rig.hpp"

using namespace palprig;
using namespace std::chrono_literals;

namespace {

RigConfig shipped_rig(const std::string& name) {
  return load_rig_file(std::string(PALPRIG_SOURCE_DIR) + "/data/rigs/" + name);
}

std::array<PlantParams, kFingerCount> quiet_plants() {
  PlantParams p;
  p.noise_sd_kPa = 0;
  p.hysteresis_kPa = 0;
  p.dead_time_s = 0;
  p.time_constant_s = 0.01;
  return {p, p, p};
}

// Steps the simulated rig for `seconds` of loop time under `setpoint` (or vented when not armed).
void hold(SimulatedRig& rig, const ChannelPressures& setpoint, double& t, double seconds) {
  for (double end = t + seconds; t < end; t += 0.001) {
    ChannelPressures monitor{};
    if (rig.armed())
      rig.write(setpoint, t);
    else
      rig.vent();
    rig.read_monitors(monitor, t);  // as the rig step does every period
  }
}

// Waits (wall clock) until the server's output words satisfy `done`.
template <class Done>
bool wait_for(Done done, std::chrono::milliseconds timeout) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < end) {
    if (done()) return true;
    std::this_thread::sleep_for(1ms);
  }
  return false;
}

}  // namespace

TEST(BackendLifecycle, SimulatedRigGoesThroughEveryState) {
  SimulatedRig rig(quiet_plants(), 60);
  EXPECT_EQ(rig.state(), BackendState::closed);
  ChannelPressures monitor{};
  EXPECT_EQ(rig.read_monitors(monitor, 0), BackendStatus::error);  // nothing to read yet
  EXPECT_EQ(rig.arm(), BackendStatus::error);                      // nor to arm
  EXPECT_NE(std::string(rig.last_error()).find("closed"), std::string::npos) << rig.last_error();

  rig.open();
  EXPECT_EQ(rig.state(), BackendState::connected);
  EXPECT_EQ(rig.read_monitors(monitor, 0), BackendStatus::ok);  // connected: reading, vented
  // Setpoints before arming are refused, and the refusal vents.
  EXPECT_EQ(rig.write({10, 10, 10}, 0.001), BackendStatus::error);
  EXPECT_NE(std::string(rig.last_error()).find("not armed"), std::string::npos) << rig.last_error();
  double t = 0.001;
  hold(rig, {10, 10, 10}, t, 0.2);
  EXPECT_EQ(rig.plant_output_kPa(0), 0.0);  // nothing flowed

  ASSERT_EQ(rig.arm(), BackendStatus::ok);
  EXPECT_EQ(rig.state(), BackendState::armed);
  hold(rig, {10, 20, 0}, t, 0.3);
  EXPECT_NEAR(rig.plant_output_kPa(0), 10.0, 0.01);
  EXPECT_NEAR(rig.plant_output_kPa(1), 20.0, 0.01);

  ASSERT_EQ(rig.disarm(), BackendStatus::ok);
  EXPECT_EQ(rig.state(), BackendState::disarmed);
  EXPECT_EQ(rig.write({10, 20, 0}, t), BackendStatus::error);  // disarmed: refused, vented
  hold(rig, {10, 20, 0}, t, 0.3);
  EXPECT_LT(rig.plant_output_kPa(1), 0.01);                     // vented to 0 (the regulator exhausts at 0 kPa)
  ASSERT_EQ(rig.read_monitors(monitor, t), BackendStatus::ok);  // still reading
  EXPECT_LT(monitor[1], 0.01);

  ASSERT_EQ(rig.arm(), BackendStatus::ok);  // re-arm from disarmed
  EXPECT_EQ(rig.write({5, 5, 5}, t + 0.001), BackendStatus::ok);
  rig.close();
  EXPECT_EQ(rig.state(), BackendState::closed);
  EXPECT_EQ(rig.write({5, 5, 5}, t + 0.002), BackendStatus::error);
  rig.close();  // twice is harmless
  EXPECT_EQ(rig.state(), BackendState::closed);
}

TEST(BackendLifecycle, ModbusRigIsConnectedAndReadingBeforeItIsArmed) {
  const ModbusRigConfig map = *shipped_rig("wago_750_559.json").modbus;
  ModbusSimServer server(map, quiet_plants());
  server.set_log_sink(nullptr);
  server.start({ListenAddress{"127.0.0.1", 0}});
  ModbusRigConfig client = map;
  client.links[0].host = "127.0.0.1";
  client.links[0].port = server.port(0);
  client.io_thread_fifo_priority = 0;
  ModbusRig rig(client);
  rig.set_log_sink(nullptr);
  rig.open();
  EXPECT_EQ(rig.state(), BackendState::connected);
  // Connected: the bus runs and monitors come back, while every output stays at 0 kPa.
  ChannelPressures monitor{};
  EXPECT_TRUE(wait_for([&] { return rig.read_monitors(monitor, 0) == BackendStatus::ok && std::isfinite(monitor[0]); },
                       2000ms));
  EXPECT_EQ(rig.write({11.75, 25, 0}, 0), BackendStatus::error);
  std::this_thread::sleep_for(50ms);
  EXPECT_EQ(server.output_words(), (std::array<std::uint16_t, kFingerCount>{0, 0, 0}));

  ASSERT_EQ(rig.arm(), BackendStatus::ok);
  const std::array<std::uint16_t, kFingerCount> pressed{3850, 8192, 0};  // 11.75 and 25 kPa
  EXPECT_TRUE(wait_for(
      [&] {
        rig.write({11.75, 25, 0}, 0);
        return server.output_words() == pressed;
      },
      3000ms));

  ASSERT_EQ(rig.disarm(), BackendStatus::ok);
  EXPECT_EQ(rig.state(), BackendState::disarmed);
  EXPECT_TRUE(wait_for(
      [&] {
        return server.output_words() == std::array<std::uint16_t, kFingerCount>{0, 0, 0};
      },
      2000ms));
  EXPECT_EQ(rig.read_monitors(monitor, 0), BackendStatus::ok);  // disarmed: still reading
  rig.close();
  EXPECT_EQ(rig.state(), BackendState::closed);
  server.stop();
}

TEST(BackendCapabilities, DescribedUpFrontWithoutOpening) {
  const SimulatedRig simulated(quiet_plants(), 60);
  BackendCapabilities c = simulated.capabilities();
  EXPECT_EQ(c.channel_count, kFingerCount);
  EXPECT_TRUE(c.has_monitor);
  EXPECT_FALSE(c.has_sensor);
  EXPECT_EQ(c.link_kind, "in-process");
  EXPECT_EQ(simulated.sensor_name(), "");

  ModbusRigConfig map = *shipped_rig("wago_750_559.json").modbus;
  map.links[0].host = "192.0.2.7";
  map.links[0].port = 1502;
  const ModbusRig tcp(map);
  c = tcp.capabilities();
  EXPECT_EQ(c.link_kind, "modbus-tcp");
  EXPECT_EQ(c.endpoint, "192.0.2.7:1502");
  EXPECT_EQ(tcp.state(), BackendState::closed);

  map.links[0].rtu = true;
  map.links[0].device = "/dev/ttyUSB0";
  const ModbusRig rtu(map);
  c = rtu.capabilities();
  EXPECT_EQ(c.link_kind, "modbus-rtu");
  EXPECT_EQ(c.endpoint.rfind("/dev/ttyUSB0", 0), 0u) << c.endpoint;

  ComediRigConfig comedi;
  comedi.device = "/dev/comedi3";
  const ComediRig card(comedi);
  c = card.capabilities();
  EXPECT_EQ(c.link_kind, "comedi");
  EXPECT_EQ(c.endpoint, "/dev/comedi3");
}

TEST(BackendCapabilities, ARigWithoutASensorSaysSoInsteadOfFailingLater) {
  SimulatedRig rig(quiet_plants(), 60);
  rig.open();
  std::array<double, kFingerCount> sensor{};
  EXPECT_FALSE(rig.capabilities().has_sensor);
  EXPECT_EQ(rig.read_sensors(sensor, 0), BackendStatus::error);
  EXPECT_TRUE(std::isnan(sensor[0]));
}
