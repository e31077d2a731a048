#pragma once
// Libraries name the field a refusal is about ("participant", "from_kPa"; in prose quoted as
// `from_kPa`); the command line names the flag that sets it. This table is the one place that maps one to the other, so
// a library never speaks in flags and the user still reads the flag they typed.
#include <string>
#include <string_view>

#include "core/input_error.hpp"

namespace palprig::cli {

// The flag that sets `field` ("from_kPa" -> "--from-kPa"), or `field` itself when no flag does.
std::string_view flag_of_field(std::string_view field) noexcept;

// `text` with every backquoted field ("above `from_kPa`") written as its flag ("above --from-kPa").
std::string with_flags(const std::string& text);

// The one line printed for a refused input: file, place and expectation, fields named as flags.
std::string input_error_line(const InputError& e);

}  // namespace palprig::cli
