// Load cells on the rig's analog inputs: a Modbus input register read by ModbusRig's
// bus thread from the simulated rig served as a real Modbus TCP server on loopback, the
// simulated rig's cells feeling the press, and the refusals of a rig without cells.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "formats/rig_file.hpp"
#include "rigs/modbus_rig.hpp"
#include "rigs/modbus_sim_server.hpp"
#include "rigs/simulated_rig.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig;
using namespace std::chrono_literals;
using palprig::test_support::TempDir;

namespace {

// The WAGO rig with a shared load cell on the coupler's fourth analog input (register 3).
RigConfig wago_with_cell() {
  TempDir dir;
  std::ifstream in(std::string(PALPRIG_SOURCE_DIR) + "/data/rigs/wago_750_559.json");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text.replace(text.rfind('}'), 1,
               ",\"load_cells\": {\"fingers\": \"all\", \"channels\": [{\"tare_V\": 0.1, \"N_per_V\": 2.0, \"input\": "
               "{\"register\": 3, \"function\": \"input\", \"raw_full_scale\": 32767, \"volts_span\": [0, 10]}}]}}");
  return load_rig_file(dir.write("wago_cell.json", text));
}

}  // namespace

TEST(LoadCells, AModbusInputRegisterIsReadEveryBusCycle) {
  const RigConfig rig = wago_with_cell();
  ASSERT_TRUE(rig.load_cells.has_value());
  ASSERT_TRUE(rig.load_cells->channels[0].modbus.has_value());
  ModbusSimServer server(*rig.modbus, rig.plants);
  server.set_load_cells(*rig.load_cells, 2.0);  // a 2 N weight on the cell
  server.start({ListenAddress{"127.0.0.1", 0}});
  ModbusRigConfig map = *rig.modbus;
  map.links[0].port = server.port(0);
  map.io_thread_fifo_priority = 0;
  ModbusRig client(map);
  client.set_log_sink([](const std::string&) {});
  client.attach_load_cells(*rig.load_cells);
  client.open();
  EXPECT_EQ(client.capabilities().load_cells, 1u);
  LoadCellReading r;
  const auto end = std::chrono::steady_clock::now() + 5s;
  double force = std::nan("");
  while (std::chrono::steady_clock::now() < end) {
    ASSERT_EQ(client.read_load_cells(r, 0), BackendStatus::ok);
    if (std::isfinite(r.force_N[0])) {
      force = r.force_N[0];
      break;
    }
    std::this_thread::sleep_for(2ms);
  }
  EXPECT_EQ(r.count, 1u);
  EXPECT_NEAR(force, 2.0, 0.05);       // 0.002 V of noise, 16-bit registers
  EXPECT_NEAR(r.volts[0], 1.1, 0.03);  // tare 0.1 V + 2 N / 2 N/V
  client.close();
  server.stop();
}

TEST(LoadCells, TheSimulatedRigsCellsFeelThePressAndAWeight) {
  const RigConfig rig = load_rig_file(std::string(PALPRIG_SOURCE_DIR) + "/data/rigs/simulated_load_cells.json");
  SimulatedRig sim(rig.plants, rig.safety.p_max_kPa);
  LoadCellReading r;
  EXPECT_EQ(sim.read_load_cells(r, 0), BackendStatus::error);  // none attached
  EXPECT_NE(std::string(sim.last_error()).find("no load cells"), std::string::npos) << sim.last_error();
  sim.attach_load_cells(*rig.load_cells);
  EXPECT_EQ(sim.read_load_cells(r, 0), BackendStatus::error);  // closed
  sim.open();
  EXPECT_THROW(sim.attach_load_cells(*rig.load_cells), std::logic_error);
  sim.feel_press({4.0, 0.0, 2.0});
  sim.place_load_N(1, 5.0);
  ASSERT_EQ(sim.read_load_cells(r, 0), BackendStatus::ok);
  EXPECT_EQ(r.count, 3u);
  EXPECT_NEAR(r.force_N[0], 2.0, 0.02);
  EXPECT_NEAR(r.force_N[1], 5.0, 0.02);
  EXPECT_NEAR(r.force_N[2], 1.0, 0.02);
  EXPECT_TRUE(sim.capabilities().load_cells_per_finger);
}
