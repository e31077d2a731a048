// Modbus TCP hosts are names or addresses. Names are resolved with
// getaddrinfo and libmodbus is given the numeric address (its own modbus_new_tcp truncates
// anything over 15 characters and prints to stderr); a name that does not resolve is one
// palprig line, exit 2; a host holding control characters is refused with them escaped.
#include <gtest/gtest.h>

#include <csignal>

#include "formats/modbus_register_map.hpp"
#include "formats/rig_file.hpp"
#include "core/input_error.hpp"
#include "rigs/modbus_link.hpp"
#include "tests/support/modbus_process_support.hpp"

using namespace palprig;
using namespace palprig::test_support;

namespace {

std::size_t lines_in(const std::string& text) {
  std::size_t n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

}  // namespace

TEST(ModbusHost, NamesResolveToTheNumericAddressLibmodbusIsGiven) {
  for (const char* name : {"localhost", "LOCALHOST", "127.0.0.1", "127.000.000.001"}) {
    const NumericHost h = resolve_modbus_host(name);
    EXPECT_EQ(h.error, "") << name;
    EXPECT_EQ(h.address, "127.0.0.1") << name;
    EXPECT_FALSE(h.ipv6) << name;
  }
  const NumericHost v6 = resolve_modbus_host("::1");
  EXPECT_EQ(v6.address, "::1");
  EXPECT_TRUE(v6.ipv6);
}

TEST(ModbusHost, SyntaxIsCheckedBeforeAnyLookup) {
  EXPECT_EQ(modbus_host_refusal("plc-7.hall-b.lab.example.org"), "");  // 28 characters: a normal name
  EXPECT_EQ(modbus_host_refusal("192.168.1.20"), "");
  EXPECT_EQ(modbus_host_refusal("fe80::1"), "");
  for (const std::string& bad : {std::string(""), std::string("a..b"), std::string(".a"), std::string("-a.b"),
                                 std::string("a-.b"), std::string("with space"), std::string("a/b"),
                                 std::string(64, 'x') + ".lab", std::string(254, 'a'), std::string("a\x1b[31mb")})
    EXPECT_NE(modbus_host_refusal(bad), "") << bad;
}

TEST(ModbusHost, ARunThroughAHostNameReachesTheModule) {
  TempDir dir;
  std::unique_ptr<WatchedProcess> sim;
  const int port = start_sim_rig(sim, palprig_bin(), kWagoRig, 0, (dir.path() / "writes.csv").string(),
                                 (dir.path() / "sim.err").string());
  auto rig = wago_on_port(port);
  rig["modbus"]["links"][0]["tcp"]["host"] = "localhost";
  const auto rig_file = dir.write("rig.json", rig.dump(2)).string();
  auto run = start_palprig_run(dir, rig_file, 0.5);
  const FinishedRun r = finish_palprig_run(*run, dir);
  sim->signal(SIGTERM);
  sim->wait();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("truncated"), std::string::npos) << r.err;
  EXPECT_GT(line_count(dir.path() / "writes.csv"), 10u);  // the simulator got the run's writes
}

TEST(ModbusHost, ALongNameThatDoesNotResolveIsOneLineAndExitTwo) {
  TempDir dir;
  auto rig = wago_on_port(502);
  // 31 characters, valid syntax, in the .invalid domain that never resolves (RFC 6761).
  const std::string host = "wago-coupler-hall-b.lab.invalid";
  rig["modbus"]["links"][0]["tcp"]["host"] = host;
  const auto rig_file = dir.write("rig.json", rig.dump(2)).string();
  const auto r = run_process(palprig_bin() + " run --realtime --no-fifo --rig " + rig_file + " --scene " + kPhantom +
                             " --input sweep --duration-s 1");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(lines_in(r.err), 1u) << r.err;
  EXPECT_EQ(r.err.rfind("palprig: " + rig_file + ": modbus.links[0].tcp.host: a host name that resolves", 0), 0u)
      << r.err;
  EXPECT_NE(r.err.find(host), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("truncated"), std::string::npos) << r.err;  // libmodbus's own line
  EXPECT_EQ(r.err.find("Invalid argument"), std::string::npos) << r.err;
}

TEST(ModbusHost, AHostWithControlCharactersIsRefusedEscaped) {
  TempDir dir;
  auto rig = wago_on_port(502);
  const std::string host = std::string(300, 'h') + "\x1b]0;pwned\x07\n\r" + "x";
  rig["modbus"]["links"][0]["tcp"]["host"] = host;
  const auto rig_file = dir.write("rig.json", rig.dump(2)).string();
  try {
    (void)load_rig_file(rig_file);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    const std::string why = e.what();
    EXPECT_NE(why.find("modbus.links[0].tcp.host"), std::string::npos) << why;
    for (char c : why) EXPECT_FALSE(static_cast<unsigned char>(c) < 0x20 || c == 0x7f) << why;
  }
  const auto r = run_process(palprig_bin() + " run --rig " + rig_file + " --scene " + kPhantom + " --duration-s 1");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(lines_in(r.err), 1u) << r.err;
  EXPECT_EQ(r.err.find('\x1b'), std::string::npos);
  // A short one shows its escapes.
  rig["modbus"]["links"][0]["tcp"]["host"] = "plc\x1b[2Jx";
  const auto short_file = dir.write("short.json", rig.dump(2)).string();
  const auto s = run_process(palprig_bin() + " run --rig " + short_file + " --scene " + kPhantom + " --duration-s 1");
  EXPECT_EQ(s.exit_code, 2) << s.err;
  EXPECT_NE(s.err.find("plc\\x1b[2Jx"), std::string::npos) << s.err;
}

TEST(ModbusHost, EndpointsInMessagesAreEscaped) {
  ModbusLinkConfig l;
  l.host = "a\nb";
  l.port = 502;
  EXPECT_EQ(l.endpoint(), "tcp a\\nb:502");
  l.rtu = true;
  l.device = "/dev/tty\x1b";
  EXPECT_EQ(l.endpoint().find('\x1b'), std::string::npos);
}
