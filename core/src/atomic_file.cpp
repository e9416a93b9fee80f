#include "plumage/atomic_file.hpp"

#include <unistd.h>

#include <atomic>
#include <fstream>
#include <string>

#include "plumage/error.hpp"

namespace plumage {

namespace fs = std::filesystem;

namespace {

// "--out x.plm" or "x.plm": how the path was given, for the messages.
std::string named(const fs::path& p, std::string_view flag) {
  return flag.empty() ? p.string() : std::string(flag) + " " + p.string();
}

const char* kind_of(fs::file_type t) {
  switch (t) {
    case fs::file_type::directory: return "a directory";
    case fs::file_type::block: return "a block device";
    case fs::file_type::character: return "a character device";
    case fs::file_type::fifo: return "a FIFO (named pipe)";
    case fs::file_type::socket: return "a socket";
    default: return "not a regular file";
  }
}

}  // namespace

void check_output_path(const fs::path& target, std::string_view flag) {
  std::error_code ec;
  // symlink_status: the link itself, so a link is seen as one and not as what it points to.
  const fs::file_status st = fs::symlink_status(target, ec);
  if (ec || st.type() == fs::file_type::not_found || st.type() == fs::file_type::regular) return;
  if (st.type() == fs::file_type::symlink) {
    const fs::path to = fs::read_symlink(target, ec);
    throw OutputPathError(named(target, flag) + ": is a symlink (to " + (ec ? "?" : to.string()) +
                          "); plumage neither writes through nor replaces a symlink: give the real path");
  }
  throw OutputPathError(named(target, flag) + ": is " + kind_of(st.type()) +
                        ", not a regular file; refusing to replace it (give a file name)");
}

void check_output_directory(const fs::path& dir, std::string_view flag) {
  // The nearest part of the path that exists must be a folder (create_directories makes the rest).
  for (fs::path p = dir; !p.empty(); p = p.parent_path()) {
    std::error_code ec;
    const fs::file_status st = fs::status(p, ec);  // follows links: a link to a folder is a folder
    if (st.type() == fs::file_type::directory) return;
    const std::string where = named(dir, flag) + ": " + (p == dir ? std::string() : p.string() + " ");
    if (st.type() != fs::file_type::not_found) {
      if (ec) return;  // cannot tell (permissions): creating the folder will say why
      throw OutputPathError(where + "exists and is " +
                            (st.type() == fs::file_type::regular ? std::string("a file") : kind_of(st.type())) +
                            ", not a folder; refusing to write into it");
    }
    if (fs::is_symlink(fs::symlink_status(p, ec)))
      throw OutputPathError(where + "is a dangling symlink (to " + fs::read_symlink(p, ec).string() +
                            "); give the real path of the folder");
    if (p == p.parent_path()) return;
  }
}

void create_output_directory(const fs::path& dir, std::string_view flag) {
  check_output_directory(dir, flag);
  if (!dir.empty()) fs::create_directories(dir);
}

void check_output_not_input(const fs::path& output, std::string_view output_flag, const fs::path& input,
                            std::string_view input_role) {
  if (output.empty() || input.empty()) return;  // an input held in memory has no file to protect
  std::error_code ec;
  bool same = fs::exists(output, ec) && fs::exists(input, ec) && fs::equivalent(output, input, ec);
  if (!same && !(fs::exists(output, ec) && fs::exists(input, ec))) {
    // Not both there: compare the names (an error in either leaves them different, not equal).
    std::error_code eo, ei;
    const fs::path o = fs::weakly_canonical(fs::absolute(output), eo), i = fs::weakly_canonical(fs::absolute(input), ei);
    same = !eo && !ei && o == i;
  }
  if (same)
    throw OutputPathError(named(output, output_flag) + ": is also an input (" + std::string(input_role) + " " +
                          input.string() + "); write the output to another file");
}

void write_file_atomically(const fs::path& target, const std::function<void(std::ostream&)>& write,
                           bool binary) {
  static std::atomic<unsigned> counter{0};
  check_output_path(target);
  try {
    create_output_directory(target.parent_path());
  } catch (const OutputPathError& e) {
    throw OutputPathError(target.string() + ": " + e.what());  // the file the caller asked for, too
  }
  fs::path temp = target;
  temp += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
  try {
    {
      std::ofstream out(temp, binary ? std::ios::binary | std::ios::trunc : std::ios::trunc);
      if (!out) throw Error(temp.string() + ": cannot create file");
      write(out);
      out.flush();
      if (!out) throw Error(target.string() + ": write failed");
    }
    // Again: the target may have been replaced while a long write ran.
    check_output_path(target);
    fs::rename(temp, target);
  } catch (...) {
    std::error_code ec;
    fs::remove(temp, ec);
    throw;
  }
}

void write_text_atomically(const fs::path& target, std::string_view text) {
  write_file_atomically(target, [&](std::ostream& out) { out << text; });
}

}  // namespace plumage
