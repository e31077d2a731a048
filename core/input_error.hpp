#pragma once
// The BadInput (core/error.hpp) of refused files and arguments: it carries the file, the place in it (a line or a
// field path) and what was expected, so the command line can print one clear line and exit 2.
//
// Bad files put their own bytes into these messages (a value, a line, a key). So that a refusal
// stays one readable line, every part is passed through printable_excerpt(): control
// characters are escaped (\n, \t, \x1b, ...) and each part is cut to a few hundred characters,
// whatever the file held (a 2 MB line, a million-element array, terminal escape sequences).
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/error.hpp"

namespace palprig {

// Longest part of a refusal, in characters, before it is cut with "...".
inline constexpr std::size_t kMaxFileChars = 200;
inline constexpr std::size_t kMaxWhereChars = 160;
inline constexpr std::size_t kMaxExpectedChars = 320;

// `text` with control characters (and DEL) escaped and cut to at most max_chars characters
// plus "..." (the cut never splits an escape or a UTF-8 sequence).
inline std::string printable_excerpt(std::string_view text, std::size_t max_chars) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  out.reserve(text.size() < max_chars ? text.size() : max_chars);
  for (std::size_t i = 0; i < text.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    std::string piece;
    switch (c) {
      case '\n': piece = "\\n"; break;
      case '\r': piece = "\\r"; break;
      case '\t': piece = "\\t"; break;
      default:
        if (c < 0x20 || c == 0x7f)
          piece = {'\\', 'x', kHex[c >> 4], kHex[c & 15]};
        else
          piece = std::string(1, static_cast<char>(c));
    }
    // Do not stop inside a UTF-8 sequence: continuation bytes (10xxxxxx) follow their lead.
    const bool continuation = (c & 0xC0) == 0x80;
    if (!continuation && out.size() + piece.size() > max_chars) {
      out += "...";
      return out;
    }
    out += piece;
  }
  return out;
}

class InputError : public BadInput {
 public:
  InputError(const std::string& file, const std::string& where, const std::string& expected)
      : InputError(Parts{printable_excerpt(file, kMaxFileChars), printable_excerpt(where, kMaxWhereChars),
                         printable_excerpt(expected, kMaxExpectedChars)}) {}
  const std::string& file() const noexcept { return file_; }
  const std::string& where() const noexcept { return where_; }
  const std::string& expected() const noexcept { return expected_; }

 private:
  struct Parts {
    std::string file, where, expected;
  };
  explicit InputError(Parts p)
      : BadInput(p.file + ": " + p.where + ": " + p.expected),
        file_(std::move(p.file)),
        where_(std::move(p.where)),
        expected_(std::move(p.expected)) {}

  std::string file_, where_, expected_;
};

}  // namespace palprig
