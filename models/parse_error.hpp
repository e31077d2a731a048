#pragma once
// The one exception type for refused input: it carries the file, the place in it (a line or a
// field path) and what was expected, so the command line can print one clear line and exit 2.
#include <stdexcept>
#include <string>

namespace palprig {

class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string where, std::string expected)
      : std::runtime_error(file + ": " + where + ": " + expected),
        file_(std::move(file)), where_(std::move(where)), expected_(std::move(expected)) {}
  const std::string& file() const noexcept { return file_; }
  const std::string& where() const noexcept { return where_; }
  const std::string& expected() const noexcept { return expected_; }

 private:
  std::string file_, where_, expected_;
};

}  // namespace palprig
