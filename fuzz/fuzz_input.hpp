#pragma once
// What every fuzz target shares: the readers take file paths, so each input is written to one
// file per process in /dev/shm (or the temp dir), with the extension the reader expects; and
// refusal is the expected outcome. Only InputError (exit 2 in the command line) is a refusal:
// any other exception escapes, std::terminate aborts, and libFuzzer reports it with the input
// that caused it - a crash, an exit 1 with a library's raw text, a hang or a leak all count.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "core/input_error.hpp"

namespace palprig::fuzz {

inline std::filesystem::path input_file(std::string_view data, const std::string& extension) {
  static const std::filesystem::path dir =
      std::filesystem::exists("/dev/shm") ? std::filesystem::path("/dev/shm") : std::filesystem::temp_directory_path();
  const auto path = dir / ("palprig-fuzz-" + std::to_string(::getpid()) + extension);
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(data.data(), static_cast<std::streamsize>(data.size()));
  return path;
}

inline std::string_view text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

template <class F>
void refused_or_read(F&& read) {
  try {
    read();
  } catch (const InputError&) {
    // bad input, refused with a message: the expected outcome
  }
}

}  // namespace palprig::fuzz
