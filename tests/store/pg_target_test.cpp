// PostgreSQL store locations without a server: libpq's own URI parser, passwords refused and
// never quoted, and an unreachable server named with host, port, database and libpq's reason.
#include <gtest/gtest.h>

#include "core/input_error.hpp"
#include "store/pg_target.hpp"
#include "store/postgres_trial_store.hpp"
#include "tests/support/process_support.hpp"

namespace palprig {
namespace {

std::string refusal(const std::string& uri) {
  try {
    parse_pg_target(uri);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(store_pg_target, uri_parts_come_from_libpq) {
  const PgTarget t = parse_pg_target("postgresql://analyst@db.lab.example:6543/study_2026");
  EXPECT_EQ(t.host, "db.lab.example");
  EXPECT_EQ(t.port, "6543");
  EXPECT_EQ(t.dbname, "study_2026");
  EXPECT_EQ(t.user, "analyst");
  EXPECT_EQ(t.describe(), "host db.lab.example port 6543 database study_2026");
  EXPECT_TRUE(is_postgres_location("postgres://x/y"));
  EXPECT_FALSE(is_postgres_location("trials.db"));
}

TEST(store_pg_target, malformed_uri_gives_libpqs_reason) {
  const std::string message = refusal("postgresql://localhost/db?no_such_option=1");
  EXPECT_NE(message.find("no_such_option"), std::string::npos) << message;
  EXPECT_NE(message.find("postgresql://user@host:port/dbname"), std::string::npos) << message;
}

TEST(store_pg_target, password_in_the_uri_is_refused_and_never_quoted) {
  for (const std::string uri :
       {"postgresql://lab:Sup3rSecret@localhost:5432/trials", "postgresql://lab@localhost/trials?password=Sup3rSecret",
        "postgresql://lab:Sup3rSecret@localhost/trials?no_such_option=1"}) {
    const std::string message = refusal(uri);
    ASSERT_FALSE(message.empty()) << uri;
    EXPECT_EQ(message.find("Sup3rSecret"), std::string::npos) << message;
  }
  EXPECT_NE(refusal("postgresql://lab:Sup3rSecret@localhost/trials").find("PGPASSWORD"), std::string::npos);
}

TEST(store_pg_target, unreachable_server_names_host_port_database_and_reason) {
  try {
    PostgresTrialStore store(parse_pg_target("postgresql://lab@127.0.0.1:1/labdb"), TrialStore::Access::read_only, 2);
    FAIL() << "connected to port 1";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("host 127.0.0.1 port 1 database labdb"), std::string::npos) << m;
    EXPECT_NE(m.find("refused"), std::string::npos) << m;
  }
}

TEST(store_pg_target, cli_refuses_unreachable_server_and_password_with_exit_2) {
  const auto down = testing::run_palprig({"stats", "trials", "postgresql://lab@127.0.0.1:1/labdb"});
  EXPECT_EQ(down.exit_code, 2) << down.err;
  EXPECT_NE(down.err.find("host 127.0.0.1 port 1 database labdb"), std::string::npos) << down.err;
  EXPECT_EQ(testing::count_lines(down.err), 1) << down.err;

  const auto secret =
      testing::run_palprig({"export", "postgresql://lab:Sup3rSecret@127.0.0.1:1/labdb", "--out", "/tmp/x"});
  EXPECT_EQ(secret.exit_code, 2);
  EXPECT_EQ(secret.err.find("Sup3rSecret"), std::string::npos) << secret.err;
  EXPECT_EQ(secret.out.find("Sup3rSecret"), std::string::npos) << secret.out;
}

TEST(store_pg_target, session_with_unreachable_server_is_refused_before_the_rig_moves) {
  const std::string protocol = std::string(PALPRIG_SOURCE_DIR) + "/data/protocols/discrimination_002.json";
  const std::string journal = ::testing::TempDir() + "/palprig_unreachable_journal.db";
  const auto r = testing::run_palprig({"experiment", "run", "--protocol", protocol, "--participant", "sim:1", "--db",
                                       "postgresql://lab@127.0.0.1:1/labdb", "--journal", journal, "--quiet"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("host 127.0.0.1 port 1 database labdb: connection: a reachable PostgreSQL server"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(testing::count_lines(r.err), 1) << r.err;
  EXPECT_EQ(r.out.find("trial "), std::string::npos) << "trials ran: " << r.out;
}

}  // namespace
}  // namespace palprig
