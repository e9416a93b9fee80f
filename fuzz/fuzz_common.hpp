// Shared by the libFuzzer harnesses (fuzz/*.cpp): the input is written to a file in this process's
// scratch folder and handed to the project's own reader, the function the commands call. The
// project's typed errors (plumage::Error and its subclasses: ConfigError, OutputPathError, ...)
// are the expected answer to bad bytes; anything else escaping the reader (std::bad_alloc,
// std::length_error, another std exception) terminates the process, which libFuzzer reports as a
// finding, as it does crashes, sanitizer reports, leaks and hangs.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "plumage/checksum.hpp"
#include "plumage/error.hpp"

namespace plumage::fuzz {

// A folder of its own per process (several harnesses may run at once), removed at exit.
inline const std::filesystem::path& scratch() {
  struct Scratch {
    std::filesystem::path dir;
    Scratch() {
      dir = std::filesystem::temp_directory_path() / ("plumage-fuzz-" + std::to_string(::getpid()));
      std::filesystem::remove_all(dir);
      std::filesystem::create_directories(dir);
    }
    ~Scratch() {
      std::error_code ec;
      std::filesystem::remove_all(dir, ec);
    }
  };
  static const Scratch s;
  return s.dir;
}

// Writes the fuzzer's bytes to `file` (created or replaced).
inline void write_bytes(const std::filesystem::path& file, std::string_view bytes) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// The binary formats (.plm, .plt, .ffs) end in the FNV-1a of all bytes before it (u64, little
// endian): a mutated file almost always fails that check first. The same bytes with the trailer
// recomputed reach the content checks behind it, as a hand-forged file would (issue 23: a .plm
// with flipped bytes and a recomputed checksum). Empty when the input is too short or its
// trailer is already right.
inline std::string with_fnv1a_trailer(std::string_view bytes) {
  if (bytes.size() < 8) return {};
  const std::string_view body = bytes.substr(0, bytes.size() - 8);
  const std::uint64_t sum = plumage::fnv1a(body);
  std::string fixed(body);
  for (int i = 0; i < 8; ++i) fixed.push_back(static_cast<char>((sum >> (8 * i)) & 0xff));
  if (fixed == bytes) return {};
  return fixed;
}

// Journals and shards checksum each record instead ('PLMR', u64 body length, body, u64 FNV-1a
// of the body; plumage/characterize_records.hpp): the same repair for every record whose length
// fits in the input. Empty when nothing changed.
inline std::string with_record_checksums(std::string_view bytes) {
  std::string fixed(bytes);
  bool changed = false;
  for (std::size_t at = fixed.find("PLMR"); at != std::string::npos; at = fixed.find("PLMR", at + 4)) {
    std::uint64_t len = 0;
    if (at + 12 > fixed.size()) break;
    std::memcpy(&len, fixed.data() + at + 4, 8);
    if (len > fixed.size() || at + 12 + len + 8 > fixed.size()) continue;
    const std::uint64_t sum = plumage::fnv1a(std::string_view(fixed).substr(at + 12, len));
    if (std::memcmp(fixed.data() + at + 12 + len, &sum, 8) != 0) {
      std::memcpy(fixed.data() + at + 12 + len, &sum, 8);
      changed = true;
    }
  }
  return changed ? fixed : std::string();
}

// Runs one reader call; a plumage::Error is an expected outcome (bad input refused), and its
// message must name something (an empty message would tell the user nothing).
template <class F>
void expect_typed_errors(F&& call) {
  try {
    call();
  } catch (const plumage::Error& e) {
    if (std::string_view(e.what()).empty()) __builtin_trap();
  }
}

}  // namespace plumage::fuzz
