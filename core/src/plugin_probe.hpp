// Checks the registry makes on a plug-in before trusting it (private to core). dlopen maps a file's
// segments as they are and follows whatever its exported symbols hold, so a truncated file faults
// on a page past its end (SIGBUS) and a wrongly typed symbol on a wild pointer (SIGSEGV): both
// would kill the whole process, where a bad plug-in must only become a reported problem.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

namespace plumage::detail {

// Why `file` cannot be handed to dlopen, or nullopt when it is a regular file holding a
// shared object for this host (ELF class, byte order, machine) whose program headers, section
// headers, segments, sections and dynamic entries all lie inside the file. Reads headers only
// (with pread, never mmap); never throws.
std::optional<std::string> probe_plugin_file(const std::filesystem::path& file);

// What an exported alias must point at.
enum class AliasTarget { data, code };

// Where one alias of PLUMAGE_PLUGIN (a pointer-sized object, Boost.DLL's BOOST_DLL_ALIAS) points,
// checked before anything follows it: `target` is null and `problem` says why when the symbol is
// missing, is not a pointer-sized object of this library, or points outside this library's
// readable (for code: executable) segments, with `target_size` bytes there.
struct AliasLookup {
  const void* target = nullptr;
  std::string problem;
};
AliasLookup follow_alias(void* handle, const char* name, AliasTarget kind, std::size_t target_size);

}  // namespace plumage::detail
