#include "plumage/data_paths.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <vector>

#include "plumage/error.hpp"

namespace plumage {

namespace fs = std::filesystem;

fs::path executable_path() { return fs::read_symlink("/proc/self/exe"); }

fs::path core_library_path() {
  Dl_info info{};
  // Any function of this library names the file it was loaded from.
  if (dladdr(reinterpret_cast<const void*>(&core_library_path), &info) == 0 || !info.dli_fname) return {};
  std::error_code ec;
  fs::path path = fs::weakly_canonical(info.dli_fname, ec);
  return ec ? fs::path(info.dli_fname) : path;
}

fs::path data_directory() {
  std::vector<fs::path> candidates;
  if (const char* env = std::getenv("PLUMAGE_DATA_DIR")) candidates.emplace_back(env);
  if (const fs::path core = core_library_path(); !core.empty())
    candidates.push_back(core.parent_path() / ".." / "share" / "plumage");
  try {
    candidates.push_back(executable_path().parent_path() / ".." / "share" / "plumage");
  } catch (const std::exception&) {
  }
#ifdef PLUMAGE_INSTALL_DATA_DIR
  candidates.emplace_back(PLUMAGE_INSTALL_DATA_DIR);
#endif
#ifdef PLUMAGE_SOURCE_DATA_DIR
  candidates.emplace_back(PLUMAGE_SOURCE_DATA_DIR);
#endif
  std::string looked;
  for (const auto& c : candidates) {
    std::error_code ec;
    if (fs::exists(c / "cie1931_2deg_5nm.csv", ec)) return fs::weakly_canonical(c, ec);
    looked += "\n  " + c.string();
  }
  throw Error("plumage data folder not found (set PLUMAGE_DATA_DIR); looked in:" + looked);
}

}  // namespace plumage
