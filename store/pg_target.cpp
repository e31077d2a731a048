#include "store/pg_target.hpp"

#include <libpq-fe.h>

#include <memory>
#include <string_view>

#include "core/input_error.hpp"

namespace palprig {

namespace {

// The URI with any password replaced by "***", and the password itself (to scrub it from
// libpq's messages, which may quote the part of the URI they could not read).
struct Redacted {
  std::string text;
  std::string secret;
};

Redacted redact(const std::string& uri) {
  Redacted r{uri, {}};
  // userinfo: scheme://user:secret@host
  const auto scheme_end = r.text.find("://");
  if (scheme_end != std::string::npos) {
    const auto authority = scheme_end + 3;
    const auto authority_end = r.text.find_first_of("/?", authority);
    const auto at = r.text.rfind('@', authority_end == std::string::npos ? std::string::npos : authority_end);
    if (at != std::string::npos && at >= authority) {
      const auto colon = r.text.find(':', authority);
      if (colon != std::string::npos && colon < at) {
        r.secret = r.text.substr(colon + 1, at - colon - 1);
        r.text.replace(colon + 1, at - colon - 1, "***");
      }
    }
  }
  // query: ...?password=secret&...
  for (std::size_t pos = r.text.find("password="); pos != std::string::npos; pos = r.text.find("password=", pos + 1)) {
    const auto value = pos + 9;
    const auto end = r.text.find('&', value);
    const std::string secret = r.text.substr(value, end == std::string::npos ? std::string::npos : end - value);
    if (r.secret.empty()) r.secret = secret;
    r.text.replace(value, secret.size(), "***");
  }
  return r;
}

std::string scrub(std::string message, const std::string& secret) {
  if (secret.empty()) return message;
  for (auto pos = message.find(secret); pos != std::string::npos; pos = message.find(secret, pos)) {
    message.replace(pos, secret.size(), "***");
  }
  return message;
}

std::string trim_end(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

struct OptionsDeleter {
  void operator()(PQconninfoOption* o) const noexcept { PQconninfoFree(o); }
};
using Options = std::unique_ptr<PQconninfoOption, OptionsDeleter>;

}  // namespace

std::string PgTarget::describe() const {
  return "host " + (host.empty() ? std::string("(local socket)") : host) + " port " + port + " database " + dbname;
}

bool is_postgres_location(const std::string& location) {
  return location.rfind("postgresql://", 0) == 0 || location.rfind("postgres://", 0) == 0;
}

PgTarget parse_pg_target(const std::string& uri) {
  const Redacted shown = redact(uri);
  char* error = nullptr;
  Options parsed(PQconninfoParse(uri.c_str(), &error));
  if (!parsed) {
    std::string reason = error ? trim_end(error) : std::string("out of memory");
    PQfreemem(error);
    throw InputError(
        shown.text, "URI",
        "a PostgreSQL connection URI postgresql://user@host:port/dbname (" + scrub(reason, shown.secret) + ")");
  }
  PgTarget target;
  target.conninfo = uri;
  for (const PQconninfoOption* o = parsed.get(); o->keyword; ++o) {
    const std::string_view key = o->keyword;
    if (!o->val) continue;
    if (key == "password" && *o->val) {
      throw InputError(shown.text, "password",
                       "no password in the URI (it would be visible in the process list and the shell history); "
                       "put it in PGPASSWORD or ~/.pgpass");
    }
    if (key == "host") target.host = o->val;
    if (key == "hostaddr" && target.host.empty()) target.host = o->val;
    if (key == "port") target.port = o->val;
    if (key == "dbname") target.dbname = o->val;
    if (key == "user") target.user = o->val;
  }
  // What the environment supplies for the rest (PGHOST, PGPORT, PGDATABASE, PGUSER), as libpq
  // will fill it in when connecting.
  Options defaults(PQconndefaults());
  if (defaults) {
    for (const PQconninfoOption* o = defaults.get(); o->keyword; ++o) {
      const std::string_view key = o->keyword;
      if (!o->val) continue;
      if (key == "host" && target.host.empty()) target.host = o->val;
      if (key == "port" && target.port.empty()) target.port = o->val;
      if (key == "dbname" && target.dbname.empty()) target.dbname = o->val;
      if (key == "user" && target.user.empty()) target.user = o->val;
    }
  }
  if (target.port.empty()) target.port = "5432";
  if (target.dbname.empty()) target.dbname = target.user;  // libpq's own default
  return target;
}

}  // namespace palprig
