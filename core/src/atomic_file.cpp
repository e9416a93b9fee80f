#include "plumage/atomic_file.hpp"

#include <unistd.h>

#include <atomic>
#include <fstream>

#include "plumage/error.hpp"

namespace plumage {

namespace fs = std::filesystem;

void write_file_atomically(const fs::path& target, const std::function<void(std::ostream&)>& write,
                           bool binary) {
  static std::atomic<unsigned> counter{0};
  fs::path dir = target.parent_path();
  if (!dir.empty()) fs::create_directories(dir);
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
