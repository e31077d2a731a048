#include "store/pg_connection.hpp"

#include <libpq-fe.h>

#include <bit>
#include <charconv>
#include <cstdint>
#include <cmath>
#include <cstdio>

namespace palprig {

namespace {

// libpq's messages span lines ("...failed: Connection refused\n\tIs the server running...");
// a refusal is one line.
std::string one_line(const char* text) {
  std::string s;
  for (const char* p = text ? text : ""; *p; ++p) {
    if (*p == '\n' || *p == '\t') {
      if (!s.empty() && s.back() != ' ') s += (*p == '\n' ? "; " : " ");
    } else {
      s += *p;
    }
  }
  while (!s.empty() && (s.back() == ' ' || s.back() == ';')) s.pop_back();
  return s;
}

}  // namespace

PgResult::~PgResult() { PQclear(r_); }

PgResult& PgResult::operator=(PgResult&& o) noexcept {
  if (this != &o) {
    PQclear(r_);
    r_ = o.r_;
    o.r_ = nullptr;
  }
  return *this;
}

int PgResult::rows() const noexcept { return r_ ? PQntuples(r_) : 0; }
int PgResult::columns() const noexcept { return r_ ? PQnfields(r_) : 0; }
bool PgResult::is_null(int row, int column) const noexcept { return PQgetisnull(r_, row, column) != 0; }

std::string_view PgResult::text_view(int row, int column) const noexcept {
  return {PQgetvalue(r_, row, column), static_cast<std::size_t>(PQgetlength(r_, row, column))};
}

namespace {

// Binary results (exec_binary) carry integers and doubles in network byte order.
std::uint64_t big_endian(std::string_view bytes) {
  std::uint64_t v = 0;
  for (const char c : bytes) v = (v << 8) | static_cast<unsigned char>(c);
  return v;
}

constexpr unsigned kInt2Oid = 21, kInt4Oid = 23, kInt8Oid = 20, kFloat4Oid = 700, kFloat8Oid = 701;

}  // namespace

std::int64_t PgResult::integer(int row, int column) const {
  const std::string_view t = text_view(row, column);
  if (PQfformat(r_, column) == 1) {
    const unsigned type = PQftype(r_, column);
    const std::uint64_t bits = big_endian(t);
    if (type == kInt8Oid && t.size() == 8) return static_cast<std::int64_t>(bits);
    if (type == kInt4Oid && t.size() == 4) return static_cast<std::int32_t>(static_cast<std::uint32_t>(bits));
    if (type == kInt2Oid && t.size() == 2) return static_cast<std::int16_t>(static_cast<std::uint16_t>(bits));
    throw PgError("PostgreSQL: column " + std::string(PQfname(r_, column)) + ": an integer, got binary type " +
                      std::to_string(type),
                  "", false);
  }
  std::int64_t v = 0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (ec != std::errc() || end != t.data() + t.size()) {
    throw PgError(
        "PostgreSQL: column " + std::string(PQfname(r_, column)) + ": an integer, got '" + std::string(t) + "'", "",
        false);
  }
  return v;
}

double PgResult::real(int row, int column) const {
  const std::string_view t = text_view(row, column);
  if (PQfformat(r_, column) == 1) {
    // The IEEE bits as the server holds them: the same double as the text form reads back to.
    const unsigned type = PQftype(r_, column);
    if (type == kFloat8Oid && t.size() == 8) return std::bit_cast<double>(big_endian(t));
    if (type == kFloat4Oid && t.size() == 4) {
      return std::bit_cast<float>(static_cast<std::uint32_t>(big_endian(t)));
    }
    throw PgError("PostgreSQL: column " + std::string(PQfname(r_, column)) + ": a number, got binary type " +
                      std::to_string(type),
                  "", false);
  }
  // PostgreSQL spells the special values out; from_chars reads "inf"/"nan" but not these.
  if (t == "NaN") return std::nan("");
  if (t == "Infinity") return HUGE_VAL;
  if (t == "-Infinity") return -HUGE_VAL;
  double v = 0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (ec != std::errc() || end != t.data() + t.size()) {
    throw PgError("PostgreSQL: column " + std::string(PQfname(r_, column)) + ": a number, got '" + std::string(t) + "'",
                  "", false);
  }
  return v;
}

unsigned PgResult::type_oid(int column) const noexcept { return PQftype(r_, column); }

std::int64_t PgResult::affected_rows() const noexcept {
  const char* n = PQcmdTuples(r_);
  return n && *n ? std::atoll(n) : 0;
}

PgConnection::PgConnection(const PgTarget& target, int connect_timeout_s) : target_(target) {
  const std::string timeout = std::to_string(connect_timeout_s);
  const char* keys[] = {"dbname", "connect_timeout", "application_name", "fallback_application_name", nullptr};
  // expand_dbname = 1: the first "dbname" value is the URI itself, expanded by libpq.
  const char* values[] = {target.conninfo.c_str(), timeout.c_str(), nullptr, "palprig", nullptr};
  conn_ = PQconnectdbParams(keys, values, 1);
  if (!conn_ || PQstatus(conn_) != CONNECTION_OK) {
    const std::string reason = conn_ ? one_line(PQerrorMessage(conn_)) : std::string("out of memory");
    PQfinish(conn_);
    conn_ = nullptr;
    throw PgError("cannot connect to PostgreSQL at " + target_.describe() + ": " + reason, "", true, reason);
  }
  // Notices (e.g. "relation already exists, skipping") are not for the participant's terminal.
  PQsetNoticeProcessor(
      conn_, [](void*, const char*) {}, nullptr);
  // Doubles are sent as text: the shortest text that reads back to the same bits (PostgreSQL 12+
  // with extra_float_digits > 0), so a trial's numbers are the same in either store.
  PQclear(PQexec(conn_, "SET extra_float_digits = 3"));
}

PgConnection::~PgConnection() { PQfinish(conn_); }

bool PgConnection::ok() const noexcept { return conn_ && PQstatus(conn_) == CONNECTION_OK; }

void PgConnection::fail(std::string_view what, pg_result* r) {
  const char* state = r ? PQresultErrorField(r, PG_DIAG_SQLSTATE) : nullptr;
  std::string sqlstate = state ? state : "";
  std::string reason = r ? one_line(PQresultErrorMessage(r)) : std::string();
  if (reason.empty()) reason = one_line(PQerrorMessage(conn_));
  PQclear(r);
  // Class 08 is "connection exception"; a broken socket gives no SQLSTATE at all.
  const bool lost = PQstatus(conn_) != CONNECTION_OK || sqlstate.rfind("08", 0) == 0 || sqlstate.rfind("57P", 0) == 0;
  throw PgError("PostgreSQL at " + target_.describe() + ": " + std::string(what) + ": " + reason, sqlstate, lost,
                reason);
}

PgResult PgConnection::exec(std::string_view sql) {
  const std::string text(sql);
  pg_result* r = PQexec(conn_, text.c_str());
  const auto status = r ? PQresultStatus(r) : PGRES_FATAL_ERROR;
  if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK) fail(sql.substr(0, 60), r);
  return PgResult(r);
}

PgResult PgConnection::exec_binary(std::string_view sql) {
  const std::string text(sql);
  pg_result* r = PQexecParams(conn_, text.c_str(), 0, nullptr, nullptr, nullptr, nullptr, 1);
  const auto status = r ? PQresultStatus(r) : PGRES_FATAL_ERROR;
  if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK) fail(sql.substr(0, 60), r);
  return PgResult(r);
}

PgResult PgConnection::exec(std::string_view sql, const std::vector<PgParam>& params) {
  const std::string text(sql);
  std::vector<const char*> values;
  values.reserve(params.size());
  for (const PgParam& p : params) values.push_back(p ? p->c_str() : nullptr);
  pg_result* r =
      PQexecParams(conn_, text.c_str(), static_cast<int>(values.size()), nullptr, values.data(), nullptr, nullptr, 0);
  const auto status = r ? PQresultStatus(r) : PGRES_FATAL_ERROR;
  if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK) fail(sql.substr(0, 60), r);
  return PgResult(r);
}

PgTransaction::PgTransaction(PgConnection& c, std::string_view begin) : c_(c) { c_.exec(begin); }

PgTransaction::~PgTransaction() {
  if (!done_ && c_.ok()) {
    try {
      c_.exec("ROLLBACK");
    } catch (...) {
      // The server rolls back a transaction whose connection is gone.
    }
  }
}

void PgTransaction::commit() {
  c_.exec("COMMIT");
  done_ = true;
}

std::string pg_text(std::int64_t v) { return std::to_string(v); }

std::string pg_text(double v) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return v > 0 ? "Infinity" : "-Infinity";
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, end);
}

}  // namespace palprig
