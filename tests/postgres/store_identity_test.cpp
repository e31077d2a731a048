// The bench journal tells lab stores apart by their own identity (the cluster's system
// identifier and the store id palprig_store keeps), not by host, port and database name. Two
// real throwaway servers from pg_virtualenv on the same port, one after the other, with one
// journal: before, the second server's session 1 was taken for the first server's session 1
// (completed) and refused as run by "another palprig process" that did not exist.
#include <gtest/gtest.h>

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "store/postgres_schema.hpp"
#include "tests/support/process_support.hpp"
#include "tests/support/support.hpp"
#include "tests/postgres/pg_test_support.hpp"
#include "tests/support/run_process.hpp"

namespace palprig {
namespace {

using testing::ScratchDir;

// A TCP port nobody listens on now (the kernel's pick for port 0).
int free_port() {
  const int s = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = 0;
  socklen_t len = sizeof a;
  int port = 0;
  if (::bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0 &&
      ::getsockname(s, reinterpret_cast<sockaddr*>(&a), &len) == 0)
    port = ntohs(a.sin_port);
  ::close(s);
  return port;
}

// One session of `participant` on a fresh pg_virtualenv server at `port` (created for this
// command and dropped after it), its trials committed through `journal`.
test_support::ProcessResult session_on_a_new_server(int port, const std::string& participant,
                                                    const std::string& journal) {
  const std::string protocol = (testing::protocols_dir() / "discrimination_002.json").string();
  const std::string inner = test_support::palprig_bin() + " experiment run --protocol " + protocol + " --participant " +
                            participant + " --quiet --journal " + journal +
                            " --db \"postgresql://$PGUSER@$PGHOST:$PGPORT/$PGDATABASE\"" +
                            " && echo system=$(psql -XAtc 'SELECT system_identifier FROM pg_control_system()')";
  // The lock with_server.sh takes while a cluster is created (pg_createcluster has none).
  return test_support::run_process("flock " + std::string(std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp") +
                                   "/palprig-pg-virtualenv.lock pg_virtualenv -t -c '-p " + std::to_string(port) +
                                   "' sh -c '" +
                                   [&] {
                                     std::string quoted;
                                     for (char c : inner)
                                       quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
                                     return quoted;
                                   }() +
                                   "'");
}

TEST(postgres_store_identity, a_new_server_at_the_same_address_is_another_store) {
  PALPRIG_REQUIRE_PG_SERVER();
  ScratchDir dir;
  const std::string journal = (dir.path() / "journal.sqlite").string();
  const int port = free_port();
  ASSERT_GT(port, 0);
  const auto first = session_on_a_new_server(port, "sim:21", journal);
  ASSERT_EQ(first.exit_code, 0) << first.out << first.err;
  const auto second = session_on_a_new_server(port, "sim:21", journal);
  EXPECT_EQ(second.exit_code, 0) << second.out << second.err;
  EXPECT_EQ(second.err.find("another palprig process"), std::string::npos) << second.err;
  // Two clusters (two system identifiers) on one port, both sessions kept in the journal, each
  // linked to its own store.
  const auto id = [](const std::string& out) { return out.substr(out.rfind("system=")); };
  ASSERT_NE(first.out.rfind("system="), std::string::npos) << first.out;
  ASSERT_NE(second.out.rfind("system="), std::string::npos) << second.out;
  EXPECT_NE(id(first.out), id(second.out));
  const auto links = test_support::run_process("sqlite3 " + journal +
                                               " \"SELECT count(*), count(DISTINCT server) FROM lab_store_sessions\"");
  if (links.exit_code == 0) {
    EXPECT_EQ(links.out, "2|2\n");
  }
}

TEST(postgres_store_identity, the_identity_names_the_cluster_and_the_store) {
  PALPRIG_REQUIRE_PG_SERVER();
  const std::string a = testing::fresh_database("identity_a"), b = testing::fresh_database("identity_b");
  PgConnection ca(parse_pg_target(a)), cb(parse_pg_target(b));
  ensure_pg_schema(ca);
  ensure_pg_schema(cb);
  const std::string ia = pg_store_identity(ca), ib = pg_store_identity(cb);
  const std::string system = ca.exec("SELECT system_identifier::text FROM pg_control_system()").text(0, 0);
  EXPECT_EQ(ia.rfind("postgresql system " + system + " store ", 0), 0u) << ia;
  EXPECT_EQ(ib.rfind("postgresql system " + system + " store ", 0), 0u) << ib;
  EXPECT_NE(ia, ib);                     // two stores on one cluster
  EXPECT_EQ(pg_store_identity(ca), ia);  // and it stays what it is
}

}  // namespace
}  // namespace palprig
