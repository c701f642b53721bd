#pragma once
// Helpers shared by the fuzz targets: the parsers under test read files, so each input is written
// to a scratch file of the fuzzing process first.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "stocs/util/error.h"

namespace stocs::fuzz {

/// A folder private to this process (parallel fuzzers must not share files), made once and
/// removed at exit. Never freed: the exit handler still needs it after static destruction.
inline const std::filesystem::path& scratchDir() {
  static const std::filesystem::path* dir = [] {
    const auto* d = new std::filesystem::path(std::filesystem::temp_directory_path() /
                                              ("stocs_fuzz_" + std::to_string(::getpid())));
    std::filesystem::create_directories(*d);
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(*dir, ec);
    });
    return d;
  }();
  return *dir;
}

/// Replaces `file` (creating its folder) with the fuzz input.
inline void writeInput(const std::filesystem::path& file, const uint8_t* data, size_t size) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
}

/// Runs `parse`, which may return or throw InputError (its way to reject bad input); anything
/// else escapes and stops the fuzzer.
template <class Parse>
void tolerateInputError(Parse parse) {
  try {
    parse();
  } catch (const InputError&) {
  }
}

/// Writes the input as `file` and parses it with `parse` (see tolerateInputError).
template <class Parse>
void parseInputAs(const std::filesystem::path& file, const uint8_t* data, size_t size,
                  Parse parse) {
  writeInput(file, data, size);
  tolerateInputError(parse);
}

}  // namespace stocs::fuzz
