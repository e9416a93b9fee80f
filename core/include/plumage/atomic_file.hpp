// Files written whole or not at all: a temporary file beside the target, then rename(2).
#pragma once

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string_view>

namespace plumage {

// Calls `write` on a stream to a temporary file in the target's folder and renames it over
// `target` only if `write` returns normally and the stream is good. On failure the temporary
// file is removed and the exception propagates; `target` is untouched.
void write_file_atomically(const std::filesystem::path& target,
                           const std::function<void(std::ostream&)>& write,
                           bool binary = false);

void write_text_atomically(const std::filesystem::path& target, std::string_view text);

}  // namespace plumage
