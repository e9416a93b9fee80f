// Files written whole or not at all: a temporary file beside the target, then rename(2). And
// output paths that never destroy anything: only a regular file (or nothing) is ever replaced.
#pragma once

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string_view>

#include "plumage/error.hpp"

namespace plumage {

// An output path that would destroy something: a symlink, a device node, FIFO, socket or
// directory where a file is to be written, a file where a folder is to be made, or an output that
// is also an input. Bad input (exit status 2 in the command): nothing has been written. (Declared
// here rather than in error.hpp: only the writers and their callers need it.)
class OutputPathError : public Error {
 public:
  using Error::Error;
};

// Refuses (OutputPathError) an output `target` that is a symlink (rename(2) would replace the
// link, not what it points to, and writing through it would change a file the user did not name)
// or that exists and is not a regular file (a device node, FIFO, socket or directory: replacing
// one destroys it). A missing target or a regular file passes. `flag` ("--out"), when given, is
// named in the message.
void check_output_path(const std::filesystem::path& target, std::string_view flag = {});

// Refuses (OutputPathError) a folder for outputs that exists and is not a directory (a symlink to
// a directory is a directory; a dangling one is refused). A missing folder passes.
void check_output_directory(const std::filesystem::path& dir, std::string_view flag = {});

// check_output_directory, then create_directories.
void create_output_directory(const std::filesystem::path& dir, std::string_view flag = {});

// Refuses (OutputPathError) an output that is the same file as an input: both names, "was
// given as" e.g. "--out" and "shard". Same file means std::filesystem::equivalent when both
// exist, the same normalised absolute path otherwise.
void check_output_not_input(const std::filesystem::path& output, std::string_view output_flag,
                            const std::filesystem::path& input, std::string_view input_role);

// Calls `write` on a stream to a temporary file in the target's folder and renames it over
// `target` only if `write` returns normally and the stream is good. On failure the temporary
// file is removed and the exception propagates; `target` is untouched. The target is checked
// (check_output_path) before anything is written and again before the rename.
void write_file_atomically(const std::filesystem::path& target,
                           const std::function<void(std::ostream&)>& write,
                           bool binary = false);

void write_text_atomically(const std::filesystem::path& target, std::string_view text);

}  // namespace plumage
