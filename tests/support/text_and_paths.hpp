#pragma once
// Small text and path helpers the suites share (no rig code: the analyst-only build uses them too). One
// definition here instead of one per file: the suites are unity-built, so two files' helpers of
// the same name would meet in one translation unit.
#include <unistd.h>

#include <sstream>
#include <string>
#include <vector>

namespace palprig::testing {

// The number of '\n' in a program's output: its line count when every line is ended.
inline int count_lines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

// One CSV/TSV line's cells; a trailing separator gives a last empty cell.
inline std::vector<std::string> split_cells(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::stringstream s(line);
  for (std::string cell; std::getline(s, cell, sep);) out.push_back(cell);
  if (!line.empty() && line.back() == sep) out.emplace_back();
  return out;
}

// A shipped data file by its path under data/ ("protocols/x.json").
inline std::string shipped_data(const std::string& rel) { return std::string(PALPRIG_SOURCE_DIR) + "/data/" + rel; }

// A recorded tablet session under tests/fixtures/evemu/.
inline std::string evemu_fixture(const std::string& name) {
  return std::string(PALPRIG_SOURCE_DIR) + "/tests/fixtures/evemu/" + name;
}

// The shipped discrimination protocol of paper 002, the suites' usual study.
inline std::string discrimination_protocol_file() { return shipped_data("protocols/discrimination_002.json"); }

// A prefix that runs a shell command as nobody when the suite runs as root (a reader's or a
// store's refusal must not depend on root's rights), nothing otherwise.
inline std::string as_unprivileged() {
  return ::geteuid() == 0 ? "setpriv --reuid=65534 --regid=65534 --clear-groups " : "";
}

}  // namespace palprig::testing
