// Input files: every reader of plumage's files (.plm, .plt, .ffs, journals and shard files) opens
// its input through here, so a path that is not a regular file is refused up front with the path
// named, opening never blocks, and sizes read from a file can be checked against the file's real
// size before anything is allocated. Errors are InputFileError: bad input, exit 2.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>

#include "plumage/error.hpp"

namespace plumage {

// A damaged or wrong input file: missing, not a regular file (a directory, FIFO, socket or
// device), bad magic or version, checksum mismatch, a size or count the file cannot hold, a value
// that is not finite or outside its physical range, a grid out of order. Bad input (exit status 2
// in the command). what() reads "file: message"; the message names the field, byte offset or
// record. (Declared here rather than in error.hpp: only the readers and their callers need it.)
class InputFileError : public Error {
 public:
  InputFileError(std::string file, std::string message)
      : Error(file + ": " + message), file_(std::move(file)), message_(std::move(message)) {}

  const std::string& file() const { return file_; }
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  std::string message_;
};

// The largest input file read whole into memory (64 GiB): a sanity limit above any file plumage
// writes (a production .ffs is a few GB), below what would exhaust a workstation without a word.
inline constexpr std::uintmax_t kMaxInputFileBytes = std::uintmax_t{1} << 36;

// Wavelengths a file may hold, nm: finite, positive and at most 1 mm (far beyond the near-IR).
// Only a sanity bound for damaged files; what a run accepts is declared with its parameter
// (param_table.hpp).
inline constexpr double kFileMaxWavelengthNm = 1e6;

// A regular file opened for reading. Refuses (InputFileError, `what` e.g. "feather material"
// named) a missing or unreadable path and a directory, FIFO, socket or device: the kind is
// checked with stat(2) before opening (a device is never opened) and again with fstat(2) on the
// descriptor, opened with O_NONBLOCK (a FIFO put there meanwhile cannot block the open).
class InputFile {
 public:
  InputFile(const std::filesystem::path& file, std::string_view what);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  // The size at opening, bytes.
  std::uintmax_t size() const { return size_; }
  // Up to `n` more bytes into `out`; fewer only at the end of the file.
  std::size_t read(char* out, std::size_t n);
  // The rest of the file (at most its size at opening); refuses a file over `max_bytes`.
  std::string read_all(std::uintmax_t max_bytes = kMaxInputFileBytes);
  const std::filesystem::path& path() const { return path_; }
  [[noreturn]] void fail(const std::string& message) const;

 private:
  std::filesystem::path path_;
  std::string what_;
  int fd_ = -1;
  std::uintmax_t size_ = 0;
};

// Refuses (InputFileError) what InputFile refuses; opens nothing but a regular file.
void check_input_file(const std::filesystem::path& file, std::string_view what);

// The whole regular file (InputFile::read_all).
std::string read_input_file(const std::filesystem::path& file, std::string_view what,
                            std::uintmax_t max_bytes = kMaxInputFileBytes);

}  // namespace plumage
