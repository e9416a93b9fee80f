// Output paths never destroy anything (plumage/atomic_file.hpp): a symlink, FIFO, directory or
// socket at an output path is refused with OutputPathError and left as it was; a regular file is
// replaced whole; an output that is also an input is refused.
#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "plumage/atomic_file.hpp"

using namespace plumage;
namespace fs = std::filesystem;

namespace {

fs::path fresh_dir() {
  const fs::path dir = fs::temp_directory_path() / "plumage-test-atomic-file";
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string read_all(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string refusal(const fs::path& target, std::string_view flag = {}) {
  try {
    check_output_path(target, flag);
  } catch (const OutputPathError& e) {
    return e.what();
  }
  return "";
}

std::size_t files_in(const fs::path& dir) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

}  // namespace

TEST_CASE("a regular file or a missing path may be written", "[atomic-file]") {
  const fs::path dir = fresh_dir();
  CHECK(refusal(dir / "missing.txt").empty());
  write_text_atomically(dir / "a.txt", "old");
  CHECK(refusal(dir / "a.txt").empty());
  write_text_atomically(dir / "a.txt", "new");
  CHECK(read_all(dir / "a.txt") == "new");
  CHECK(files_in(dir) == 1);  // no temporary left behind
}

TEST_CASE("a symlink at an output path is refused and left pointing where it did", "[atomic-file]") {
  const fs::path dir = fresh_dir();
  write_text_atomically(dir / "real.txt", "keep");
  fs::create_symlink(dir / "real.txt", dir / "link.txt");
  const std::string message = refusal(dir / "link.txt", "--out");
  CHECK(message.find("--out " + (dir / "link.txt").string()) != std::string::npos);
  CHECK(message.find("symlink (to " + (dir / "real.txt").string() + ")") != std::string::npos);
  CHECK(message.find("real path") != std::string::npos);
  CHECK_THROWS_AS(write_text_atomically(dir / "link.txt", "lost"), OutputPathError);
  CHECK(fs::is_symlink(dir / "link.txt"));
  CHECK(fs::read_symlink(dir / "link.txt") == dir / "real.txt");
  CHECK(read_all(dir / "real.txt") == "keep");
  CHECK(files_in(dir) == 2);
  // A dangling link is refused too: writing through it would create a file elsewhere.
  fs::create_symlink(dir / "nowhere.txt", dir / "dangling.txt");
  CHECK_THROWS_AS(write_text_atomically(dir / "dangling.txt", "x"), OutputPathError);
  CHECK(!fs::exists(dir / "nowhere.txt"));
}

TEST_CASE("a FIFO at an output path is refused and stays a FIFO", "[atomic-file]") {
  const fs::path dir = fresh_dir();
  const fs::path fifo = dir / "pipe";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  CHECK(refusal(fifo).find("FIFO") != std::string::npos);
  CHECK_THROWS_AS(write_file_atomically(fifo, [](std::ostream& out) { out << "x"; }, true), OutputPathError);
  CHECK(fs::is_fifo(fs::symlink_status(fifo)));
  CHECK(files_in(dir) == 1);
}

TEST_CASE("a directory at an output path is refused and keeps its contents", "[atomic-file]") {
  const fs::path dir = fresh_dir();
  fs::create_directories(dir / "sub");
  write_text_atomically(dir / "sub" / "inside.txt", "keep");
  CHECK(refusal(dir / "sub").find("a directory") != std::string::npos);
  CHECK_THROWS_AS(write_text_atomically(dir / "sub", "x"), OutputPathError);
  CHECK(read_all(dir / "sub" / "inside.txt") == "keep");
}

TEST_CASE("a folder for outputs must be a folder", "[atomic-file]") {
  const fs::path dir = fresh_dir();
  write_text_atomically(dir / "file", "keep");
  CHECK_THROWS_AS(create_output_directory(dir / "file", "--out"), OutputPathError);
  CHECK_THROWS_AS(write_text_atomically(dir / "file" / "x.txt", "x"), OutputPathError);
  CHECK(read_all(dir / "file") == "keep");
  fs::create_directories(dir / "real");
  fs::create_directory_symlink(dir / "real", dir / "linked");
  CHECK_NOTHROW(create_output_directory(dir / "linked"));  // a link to a folder is a folder
  CHECK_NOTHROW(create_output_directory(dir / "new" / "deeper"));
  CHECK(fs::is_directory(dir / "new" / "deeper"));
}

TEST_CASE("an output that is also an input is refused, under any name", "[atomic-file]") {
  const fs::path dir = fresh_dir();
  write_text_atomically(dir / "in.txt", "input");
  CHECK_THROWS_AS(check_output_not_input(dir / "in.txt", "--out", dir / "in.txt", "shard"), OutputPathError);
  CHECK_THROWS_AS(check_output_not_input(dir / "." / "in.txt", "--out", dir / "in.txt", "shard"), OutputPathError);
  fs::create_hard_link(dir / "in.txt", dir / "hard.txt");
  try {
    check_output_not_input(dir / "hard.txt", "--out", dir / "in.txt", "shard");
    FAIL("a hard link to the input was accepted as output");
  } catch (const OutputPathError& e) {
    CHECK(std::string(e.what()).find("--out " + (dir / "hard.txt").string()) != std::string::npos);
    CHECK(std::string(e.what()).find("shard " + (dir / "in.txt").string()) != std::string::npos);
  }
  CHECK_NOTHROW(check_output_not_input(dir / "other.txt", "--out", dir / "in.txt", "shard"));
  CHECK(read_all(dir / "in.txt") == "input");
}
