// palprig sim-rig: serve the rig file's simulated plants as a real Modbus TCP server with the
// rig file's register map, so `palprig run` with that rig file drives it over the network
// exactly as it would drive the modules on the bench.
#include <chrono>
#include <iostream>
#include <thread>

#include "cli/commands.hpp"
#include "rigs/modbus_link.hpp"
#include "rigs/modbus_sim_server.hpp"
#include "formats/rig_file.hpp"
#include "runtime/run_control.hpp"
#include "core/input_error.hpp"

using namespace palprig;

void register_sim_rig_command(CLI::App& app) {
  auto rig_path = std::make_shared<std::string>();
  auto listen = std::make_shared<std::vector<std::string>>();
  auto write_log = std::make_shared<std::string>();
  auto watchdog_ms = std::make_shared<double>(0.0);
  auto duration_s = std::make_shared<double>(0.0);
  auto load_N = std::make_shared<double>(0.0);
  CLI::App* sub = app.add_subcommand(
      "sim-rig", "Serve the simulated pneumatic plant as a Modbus TCP server with a rig file's register map");
  sub->add_option("--rig", *rig_path, "Rig file (JSON) with backend \"modbus\": its register map and plants")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option(
      "--listen", *listen,
      "HOST:PORT to serve, one per link of the map in order (port 0: any free port, printed on start), or "
      "pty to serve that link as Modbus RTU on a new pseudo-terminal; default: the rig file's own TCP addresses");
  sub->add_option("--write-log", *write_log,
                  "Write every output-register write to FILE (CSV t_s,channel,word,kPa,mono_ns; mono_ns: arrival on "
                  "CLOCK_MONOTONIC)");
  sub->add_option("--watchdog-ms", *watchdog_ms,
                  "Like a module's communication watchdog: outputs of a link silent this long go to 0 kPa (0: off)")
      ->check(CLI::Range(0.0, 600000.0));
  sub->add_option("--duration-s", *duration_s, "Stop after this long (default: until SIGINT/SIGTERM)")
      ->check(CLI::Range(0.0, 1e9));
  sub->add_option(
         "--load-N", *load_N,
         "The rig file's load cells: serve each as a cell with this load on it (its tare and gain from the file)")
      ->check(CLI::Range(0.0, 1000.0));
  sub->callback([=]() {
    const RigConfig rig = load_rig_file(*rig_path);
    if (rig.backend != "modbus")
      throw InputError(rig.source, "backend",
                       "\"modbus\" (sim-rig serves the rig's register map), got \"" + rig.backend + "\"");
    const ModbusRigConfig map = rig.modbus.value();
    std::vector<ListenAddress> addresses;
    if (listen->empty()) {
      for (std::size_t i = 0; i < map.links.size(); ++i) {
        if (map.links[i].rtu)
          throw InputError("--listen", "link \"" + map.links[i].name + "\"",
                           "a HOST:PORT to serve this RTU link on over TCP, or pty for RTU on a pseudo-terminal "
                           "(the rig file has no TCP address for it)");
        // The rig file may name the module's host: serve on the address it resolves to.
        const NumericHost numeric = resolve_modbus_host(map.links[i].host);
        const std::string where = "modbus.links[" + std::to_string(i) + "].tcp.host";
        if (!numeric.error.empty()) throw InputError(rig.source, where, numeric.error);
        if (numeric.ipv6)
          throw InputError(rig.source, where,
                           "an IPv4 address to serve on (sim-rig listens on IPv4), got " + numeric.address);
        addresses.push_back({numeric.address, map.links[i].port});
      }
    } else {
      if (listen->size() != map.links.size())
        throw InputError("--listen", std::to_string(listen->size()) + " address(es)",
                         "one HOST:PORT per link of the map (" + std::to_string(map.links.size()) + ")");
      for (const auto& text : *listen) {
        try {
          addresses.push_back(parse_listen_address(text));
        } catch (const BadInput& e) {
          throw InputError("--listen", text, e.what());
        }
      }
    }
    ModbusSimServer server(map, rig.plants);
    if (!write_log->empty()) server.set_write_log(*write_log);
    server.set_watchdog_s(*watchdog_ms / 1000.0);
    if (rig.load_cells)
      server.set_load_cells(*rig.load_cells, *load_N);
    else if (*load_N > 0)
      throw InputError(rig.source, "load_cells", "a \"load_cells\" section (--load-N loads the rig's load cells)");
    install_stop_signals();
    try {
      server.start(addresses);
    } catch (const Error& e) {  // an address that cannot be served: the argument's fault
      std::cerr << "palprig sim-rig: " << e.what() << "\n";
      cli::finish(cli::kExitBadInput);
    }
    for (std::size_t i = 0; i < map.links.size(); ++i) {
      std::cout << "palprig sim-rig: rig '" << rig.id << "' link '" << map.links[i].name << "' (unit "
                << map.links[i].unit_id << ") ";
      if (addresses[i].pty)
        std::cout << "serving Modbus RTU on " << server.pty_path(i) << " (" << map.links[i].baud << " "
                  << map.links[i].data_bits << map.links[i].parity << map.links[i].stop_bits
                  << "; point the rig file's rtu.device there)\n";
      else
        std::cout << "listening on " << addresses[i].host << ":" << server.port(i) << "\n";
    }
    std::cout << "palprig sim-rig: serving " << kFingerCount << " channels; stop with Ctrl-C" << std::endl;
    const auto start = std::chrono::steady_clock::now();
    while (!process_run_control().stop_requested()) {
      if (*duration_s > 0 && std::chrono::steady_clock::now() - start >= std::chrono::duration<double>(*duration_s))
        break;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    server.stop();
    std::cout << "palprig sim-rig: stopped after " << server.requests() << " requests" << std::endl;
  });
}
