// Input files opened without blocking, regular files only (input_file.hpp).
#include "plumage/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace plumage {

namespace {

// "a directory", "a FIFO" … for a file that is not regular; "" for a regular file.
std::string kind_of(mode_t mode) {
  if (S_ISREG(mode)) return "";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  return "not a regular file";
}

}  // namespace

InputFile::InputFile(const std::filesystem::path& file, std::string_view what) : path_(file), what_(what) {
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) fail(std::string("cannot open ") + what_ + ": " + std::strerror(errno));
  if (const std::string kind = kind_of(st.st_mode); !kind.empty())
    fail("is " + kind + ", not a " + what_ + " file (an input must be a regular file)");
  fd_ = ::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd_ < 0) fail(std::string("cannot open ") + what_ + ": " + std::strerror(errno));
  if (::fstat(fd_, &st) != 0 || !kind_of(st.st_mode).empty()) {
    ::close(fd_);
    fd_ = -1;
    fail("is not a regular file (replaced while being opened)");
  }
  size_ = static_cast<std::uintmax_t>(st.st_size);
}

InputFile::~InputFile() {
  if (fd_ >= 0) ::close(fd_);
}

void InputFile::fail(const std::string& message) const { throw InputFileError(path_.string(), message); }

std::size_t InputFile::read(char* out, std::size_t n) {
  std::size_t done = 0;
  while (done < n) {
    const ssize_t got = ::read(fd_, out + done, n - done);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) fail(std::string("cannot read ") + what_ + ": " + std::strerror(errno));
    if (got == 0) break;
    done += static_cast<std::size_t>(got);
  }
  return done;
}

std::string InputFile::read_all(std::uintmax_t max_bytes) {
  if (size_ > max_bytes)
    fail(std::to_string(size_) + " bytes, more than the " + std::to_string(max_bytes) + " a " + what_ + " may hold");
  std::string data(static_cast<std::size_t>(size_), '\0');
  data.resize(read(data.data(), data.size()));  // a file that shrank meanwhile reads short
  return data;
}

void check_input_file(const std::filesystem::path& file, std::string_view what) { InputFile f(file, what); }

std::string read_input_file(const std::filesystem::path& file, std::string_view what, std::uintmax_t max_bytes) {
  InputFile f(file, what);
  return f.read_all(max_bytes);
}

}  // namespace plumage
