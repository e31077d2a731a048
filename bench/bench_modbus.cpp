// Modbus bus cycle on loopback: write three setpoints (FC16) and read three monitors (FC04)
// against the simulated rig served by ModbusSimServer on 127.0.0.1, through palprig's own path
// (RegisterScale encoding, the planned ModbusLink transactions, decoding back to kPa; what the
// ModbusRig I/O thread does per link and cycle) and through a bare libmodbus client doing the
// same two calls. Goal: palprig <= 1.2x the bare client. Also the cost the loop thread pays per
// tick for ModbusRig::write + read_monitors (a hand-off, no bus I/O).
//   build/bin/bench_modbus
#include <benchmark/benchmark.h>
#include <modbus.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <vector>

#include "rigs/modbus_link.hpp"
#include "rigs/modbus_rig.hpp"
#include "rigs/modbus_sim_server.hpp"
#include "formats/rig_file.hpp"

using namespace palprig;

namespace {

struct Loopback {
  ModbusRigConfig map;
  std::unique_ptr<ModbusSimServer> server;
  Loopback() {
    map = load_rig_file(std::string(PALPRIG_SOURCE_DIR) + "/data/rigs/wago_750_559.json").modbus.value();
    const RigConfig rig = load_rig_file(std::string(PALPRIG_SOURCE_DIR) + "/data/rigs/wago_750_559.json");
    server = std::make_unique<ModbusSimServer>(map, rig.plants);
    server->set_log_sink(nullptr);
    server->start({ListenAddress{"127.0.0.1", 0}});
    map.links[0].host = "127.0.0.1";
    map.links[0].port = server->port(0);
    map.io_thread_fifo_priority = 0;
  }
};

Loopback& loopback() {
  static Loopback l;
  return l;
}

void BM_BareLibmodbus_Write3Read3(benchmark::State& state) {
  Loopback& l = loopback();
  modbus_t* ctx = modbus_new_tcp("127.0.0.1", l.map.links[0].port);
  if (!ctx || modbus_connect(ctx) != 0) {
    state.SkipWithError("cannot connect to the loopback server");
    return;
  }
  std::uint16_t words[3] = {3850, 8192, 100}, monitors[3];
  for (auto _ : state) {
    if (modbus_write_registers(ctx, 0, 3, words) != 3 || modbus_read_input_registers(ctx, 0, 3, monitors) != 3) {
      state.SkipWithError(modbus_strerror(errno));
      break;
    }
    benchmark::DoNotOptimize(monitors);
  }
  modbus_close(ctx);
  modbus_free(ctx);
}
BENCHMARK(BM_BareLibmodbus_Write3Read3)->UseRealTime()->MinTime(2.0);

void BM_PalprigModbusLink_Write3Read3(benchmark::State& state) {
  Loopback& l = loopback();
  ModbusLink link(l.map, 0);
  if (!link.connect()) {
    state.SkipWithError(link.last_error());
    return;
  }
  const ChannelPressures setpoint{11.75, 25.0, 0.3};
  ChannelWords out{}, mon{};
  ChannelPressures monitors{};
  for (auto _ : state) {
    for (std::size_t c = 0; c < kFingerCount; ++c) out[c] = l.map.channels[c].output.scale.word_from_kPa(setpoint[c]);
    if (!link.write_outputs(out) || !link.read_monitors(mon)) {
      state.SkipWithError(link.last_error());
      break;
    }
    for (std::size_t c = 0; c < kFingerCount; ++c) monitors[c] = l.map.channels[c].monitor.scale.kPa_from_word(mon[c]);
    benchmark::DoNotOptimize(monitors);
  }
}
BENCHMARK(BM_PalprigModbusLink_Write3Read3)->UseRealTime()->MinTime(2.0);

// The two clients in alternation, round by round (500 cycles each), so that load from other
// programs hits both alike; counters give the median per-cycle time of each and their ratio.
void BM_Interleaved_PalprigOverBare(benchmark::State& state) {
  Loopback& l = loopback();
  modbus_t* ctx = modbus_new_tcp("127.0.0.1", l.map.links[0].port);
  ModbusLink link(l.map, 0);
  if (!ctx || modbus_connect(ctx) != 0 || !link.connect()) {
    state.SkipWithError("cannot connect to the loopback server");
    return;
  }
  const ChannelPressures setpoint{11.75, 25.0, 0.3};
  std::vector<double> bare_us, ours_us, ratios;
  auto now = [] { return std::chrono::steady_clock::now(); };
  for (auto _ : state) {
    constexpr int kCycles = 500;
    std::uint16_t words[3] = {3850, 8192, 100}, monitors[3];
    const auto a = now();
    for (int i = 0; i < kCycles; ++i) {
      modbus_write_registers(ctx, 0, 3, words);
      modbus_read_input_registers(ctx, 0, 3, monitors);
    }
    const auto b = now();
    ChannelWords out{}, mon{};
    ChannelPressures kPa{};
    for (int i = 0; i < kCycles; ++i) {
      for (std::size_t c = 0; c < kFingerCount; ++c) out[c] = l.map.channels[c].output.scale.word_from_kPa(setpoint[c]);
      link.write_outputs(out);
      link.read_monitors(mon);
      for (std::size_t c = 0; c < kFingerCount; ++c) kPa[c] = l.map.channels[c].monitor.scale.kPa_from_word(mon[c]);
    }
    const auto c = now();
    benchmark::DoNotOptimize(kPa);
    bare_us.push_back(std::chrono::duration<double, std::micro>(b - a).count() / kCycles);
    ours_us.push_back(std::chrono::duration<double, std::micro>(c - b).count() / kCycles);
    ratios.push_back(ours_us.back() / bare_us.back());
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
  };
  state.counters["bare_us"] = median(bare_us);
  state.counters["palprig_us"] = median(ours_us);
  state.counters["ratio"] = median(ratios);
  modbus_close(ctx);
  modbus_free(ctx);
}
BENCHMARK(BM_Interleaved_PalprigOverBare)->Iterations(40)->Unit(benchmark::kMillisecond);

// What a loop tick pays: hand the setpoints to the I/O thread and take the newest monitors.
void BM_ModbusRig_LoopSideWriteRead(benchmark::State& state) {
  Loopback& l = loopback();
  ModbusRig rig(l.map);
  rig.set_log_sink(nullptr);
  rig.open();
  ChannelPressures monitors{};
  double t = 0;
  for (auto _ : state) {
    rig.write({11.75, 25.0, 0.3}, t += 0.001);
    rig.read_monitors(monitors, t);
    benchmark::DoNotOptimize(monitors);
  }
  rig.close();
}
BENCHMARK(BM_ModbusRig_LoopSideWriteRead);

}  // namespace

BENCHMARK_MAIN();
