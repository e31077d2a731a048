#pragma once
// A thin RAII layer over libpq for the lab store: a connection, results read as text with
// typed accessors, parameters passed as text, and a transaction that rolls back unless
// committed. Errors throw PgError carrying the target (host, port, database: never the
// password) and libpq's or the server's reason.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "store/pg_target.hpp"

struct pg_conn;
struct pg_result;

namespace palprig {

// An Error (core/error.hpp, exit 1): the server, not the input. Callers that know a refusal is
// the user's (an unreachable server named on the command line) turn it into an InputError.
class PgError : public Error {
 public:
  // sqlstate: the server's five-character SQLSTATE, empty when the connection itself failed.
  PgError(const std::string& what, std::string sqlstate, bool connection_lost, std::string reason = {})
      : Error(what), sqlstate_(std::move(sqlstate)), connection_lost_(connection_lost), reason_(std::move(reason)) {}
  const std::string& sqlstate() const noexcept { return sqlstate_; }
  // True when the server could not be reached or went away: the caller may retry later.
  bool connection_lost() const noexcept { return connection_lost_; }
  // libpq's or the server's reason alone (one line), without the target.
  const std::string& reason() const noexcept { return reason_; }

 private:
  std::string sqlstate_;
  bool connection_lost_;
  std::string reason_;
};

// A text parameter, or SQL NULL.
using PgParam = std::optional<std::string>;

class PgResult {
 public:
  PgResult() = default;
  explicit PgResult(pg_result* r) noexcept : r_(r) {}
  ~PgResult();
  PgResult(PgResult&& o) noexcept : r_(o.r_) { o.r_ = nullptr; }
  PgResult& operator=(PgResult&& o) noexcept;
  PgResult(const PgResult&) = delete;
  PgResult& operator=(const PgResult&) = delete;

  int rows() const noexcept;
  int columns() const noexcept;
  bool is_null(int row, int column) const noexcept;
  std::string_view text_view(int row, int column) const noexcept;
  std::string text(int row, int column) const { return std::string(text_view(row, column)); }
  std::int64_t integer(int row, int column) const;
  double real(int row, int column) const;
  unsigned type_oid(int column) const noexcept;  // the column's PostgreSQL type (INT8OID, ...)
  std::int64_t affected_rows() const noexcept;   // INSERT/UPDATE/DELETE row count

 private:
  pg_result* r_ = nullptr;
};

class PgConnection {
 public:
  // Connects at once (libpq's URI or key=value syntax; environment variables and ~/.pgpass
  // fill what the text leaves out). Throws PgError naming host, port and database.
  explicit PgConnection(const PgTarget& target, int connect_timeout_s = 10);
  ~PgConnection();
  PgConnection(const PgConnection&) = delete;
  PgConnection& operator=(const PgConnection&) = delete;

  PgResult exec(std::string_view sql);
  PgResult exec(std::string_view sql, const std::vector<PgParam>& params);
  // Results in binary format (integers and doubles as their bits: no printing on the server,
  // no parsing here), for large scans. text_view is raw bytes then: read numbers with
  // integer() and real() (int2/4/8, float4/8), and text() only for text columns.
  PgResult exec_binary(std::string_view sql);
  bool ok() const noexcept;  // the connection is still up
  const PgTarget& target() const noexcept { return target_; }

 private:
  [[noreturn]] void fail(std::string_view what, pg_result* r);

  PgTarget target_;
  pg_conn* conn_ = nullptr;
};

// BEGIN on construction, ROLLBACK in the destructor unless commit() ran.
class PgTransaction {
 public:
  explicit PgTransaction(PgConnection& c, std::string_view begin = "BEGIN");
  ~PgTransaction();
  PgTransaction(const PgTransaction&) = delete;
  PgTransaction& operator=(const PgTransaction&) = delete;
  void commit();

 private:
  PgConnection& c_;
  bool done_ = false;
};

// Text of a value for a parameter: integers in decimal, doubles in the shortest form that reads
// back to the same bits.
std::string pg_text(std::int64_t v);
std::string pg_text(double v);

}  // namespace palprig
