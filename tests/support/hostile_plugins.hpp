// A plug-in folder holding the files a scan must survive (issue 23): truncated copies of a real
// plug-in, a copy without section headers cut inside a segment, random bytes, a text file, the
// ELF magic alone, a folder named like a library, a plain-int ABI symbol; beside one good plug-in.
// Shared by tests/plugins (the registry) and tests/cli (the command).
#pragma once

#include <elf.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace plumage::testing {

struct HostileFile {
  std::string name;    // file name inside the folder
  std::string reason;  // what its problem message must contain
};

struct HostileFolder {
  std::filesystem::path dir;
  std::vector<HostileFile> bad;  // each must be listed as a problem, none loaded
};

inline std::string read_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + file.string());
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void write_bytes(const std::filesystem::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// Fills `dir` (emptied first) from `real_plugin` (a built libplumage_*.so, larger than 60 kB, its
// section header table last as GNU ld writes it), `good` (a plug-in that loads) and `plain_int`
// (the fixture exporting plumage_abi_version as a plain int).
inline HostileFolder make_hostile_plugin_folder(const std::filesystem::path& dir,
                                                const std::filesystem::path& real_plugin,
                                                const std::filesystem::path& good,
                                                const std::filesystem::path& plain_int) {
  namespace fs = std::filesystem;
  fs::remove_all(dir);
  fs::create_directories(dir);
  HostileFolder folder{dir, {}};
  const std::string real = read_bytes(real_plugin);
  Elf64_Ehdr header;
  if (real.size() < 60 * 1024 + 1 || real.size() < sizeof header) throw std::runtime_error("real plug-in too small");
  std::memcpy(&header, real.data(), sizeof header);
  // Where the file says its section headers end, read here independently of the probe.
  const std::uint64_t sections_end = header.e_shoff + std::uint64_t{header.e_shnum} * header.e_shentsize;
  for (std::size_t length : {std::size_t{1024}, std::size_t{16 * 1024}, std::size_t{60 * 1024}, real.size() - 1}) {
    const std::string name = "libplumage_cut_" + std::to_string(length) + ".so";
    write_bytes(dir / name, real.substr(0, length));
    folder.bad.push_back({name, "truncated: section headers end at " + std::to_string(sections_end) +
                                    " bytes, file has " + std::to_string(length)});
  }
  // Without section headers only the segments can tell the truncation: exactly what faulted.
  Elf64_Ehdr stripped = header;
  stripped.e_shoff = 0;
  stripped.e_shnum = 0;
  stripped.e_shstrndx = 0;
  std::string no_sections = real;
  std::memcpy(no_sections.data(), &stripped, sizeof stripped);
  write_bytes(dir / "libplumage_cut_segments.so", no_sections.substr(0, 60 * 1024));
  folder.bad.push_back({"libplumage_cut_segments.so", "(LOAD) ends at"});
  std::mt19937 random(23);
  std::string noise(8192, '\0');
  for (char& c : noise) c = static_cast<char>(random() & 0xff);
  noise[0] = 'x';  // never the ELF magic by chance
  write_bytes(dir / "libplumage_random.so", noise);
  folder.bad.push_back({"libplumage_random.so", "not an ELF shared object"});
  write_bytes(dir / "libplumage_text.so", "this is a text file, not an ELF library\n");
  folder.bad.push_back({"libplumage_text.so", "not an ELF shared object"});
  write_bytes(dir / "libplumage_magic.so", real.substr(0, 20));
  folder.bad.push_back({"libplumage_magic.so", "truncated: the ELF header ends at 64 bytes, file has 20"});
  fs::create_directory(dir / "libplumage_folder.so");
  folder.bad.push_back({"libplumage_folder.so", "not a regular file (a directory)"});
  fs::copy_file(plain_int, dir / "libplumage_plainint.so");
  folder.bad.push_back({"libplumage_plainint.so", "'plumage_abi_version' is a 4-byte object, not the 8-byte alias"});
  fs::copy_file(good, dir / "libplumage_good.so");
  return folder;
}

}  // namespace plumage::testing
