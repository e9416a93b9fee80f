// Validating a plug-in file before dlopen, and the aliases it exports before following them.
#include "plugin_probe.hpp"

#include <dlfcn.h>
#include <elf.h>
#include <fcntl.h>
#include <link.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

namespace plumage::detail {

namespace {

using Ehdr = ElfW(Ehdr);
using Phdr = ElfW(Phdr);
using Shdr = ElfW(Shdr);
using Dyn = ElfW(Dyn);
using Sym = ElfW(Sym);
using u64 = std::uint64_t;
using Problem = std::optional<std::string>;

constexpr unsigned char kHostClass = sizeof(void*) == 8 ? ELFCLASS64 : ELFCLASS32;
constexpr unsigned char kHostData = std::endian::native == std::endian::little ? ELFDATA2LSB : ELFDATA2MSB;

// The build's machine as an ELF e_machine; 0 where this list does not know it (dlopen then judges).
constexpr std::uint16_t kHostMachine =
#if defined(__x86_64__)
    EM_X86_64;
#elif defined(__aarch64__)
    EM_AARCH64;
#elif defined(__i386__)
    EM_386;
#elif defined(__arm__)
    EM_ARM;
#elif defined(__powerpc64__)
    EM_PPC64;
#elif defined(__riscv)
    EM_RISCV;
#elif defined(__s390x__)
    EM_S390;
#else
    0;
#endif

std::string machine_name(unsigned machine) {
  switch (machine) {
    case EM_X86_64: return "x86-64";
    case EM_AARCH64: return "AArch64";
    case EM_386: return "i386";
    case EM_ARM: return "ARM";
    case EM_PPC64: return "PowerPC64";
    case EM_RISCV: return "RISC-V";
    case EM_S390: return "s390";
    default: return "ELF machine " + std::to_string(machine);
  }
}

// Whether [offset, offset + length) lies inside `size` bytes, written so that it cannot overflow.
bool inside(u64 offset, u64 length, u64 size) { return offset <= size && length <= size - offset; }

// "truncated: <what ends> at N bytes, file has M": what_ends carries its own verb ("... end(s)").
std::string truncated(const std::string& what_ends, u64 offset, u64 length, u64 size) {
  const std::string end = length > std::numeric_limits<u64>::max() - offset
                              ? "beyond 2^64" : "at " + std::to_string(offset + length);
  return "truncated: " + what_ends + " " + end + " bytes, file has " + std::to_string(size);
}

// The file as read so far. Everything is read with pread, nothing mapped: a short file gives a
// short read here, where a mapping would fault on the page past its end.
struct Image {
  int fd = -1;
  u64 size = 0;
  Ehdr header{};
  std::vector<Phdr> segments;
  std::vector<Shdr> sections;

  bool read(u64 offset, void* out, std::size_t length) const {
    auto* bytes = static_cast<char*>(out);
    while (length > 0) {
      const ssize_t n = ::pread(fd, bytes, length, static_cast<off_t>(offset));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return false;
      bytes += n;
      offset += static_cast<u64>(n);
      length -= static_cast<std::size_t>(n);
    }
    return true;
  }
};

Problem check_header(Image& image) {
  unsigned char ident[EI_NIDENT] = {};
  if (image.size < EI_NIDENT || !image.read(0, ident, EI_NIDENT) || std::memcmp(ident, ELFMAG, SELFMAG) != 0) {
    return "not an ELF shared object: the file does not begin with the ELF magic bytes (0x7f 'ELF')";
  }
  if (ident[EI_CLASS] != kHostClass) {
    return std::string("not loadable here: a ") + (ident[EI_CLASS] == ELFCLASS32 ? "32" : "64") +
           "-bit ELF file, this host loads " + (kHostClass == ELFCLASS64 ? "64" : "32") + "-bit shared objects";
  }
  if (ident[EI_DATA] != kHostData) return "not loadable here: an ELF file of the other byte order than this host";
  if (ident[EI_VERSION] != EV_CURRENT) {
    return "not an ELF shared object: unknown ELF version " + std::to_string(ident[EI_VERSION]);
  }
  if (image.size < sizeof(Ehdr) || !image.read(0, &image.header, sizeof(Ehdr))) {
    return truncated("the ELF header ends", 0, sizeof(Ehdr), image.size);
  }
  const Ehdr& h = image.header;
  if (h.e_type != ET_DYN) {
    const char* what = h.e_type == ET_REL ? "a relocatable object (.o)" : h.e_type == ET_EXEC ? "an executable"
                       : h.e_type == ET_CORE ? "a core dump" : "of an unknown ELF type";
    return std::string("not an ELF shared object: the file is ") + what;
  }
  if (kHostMachine != 0 && h.e_machine != kHostMachine) {
    return "not loadable here: built for " + machine_name(h.e_machine) + ", this host is " + machine_name(kHostMachine);
  }
  return std::nullopt;
}

Problem read_tables(Image& image) {
  const Ehdr& h = image.header;
  if (h.e_phnum == 0) return "not an ELF shared object: it has no program headers";
  if (h.e_phnum == PN_XNUM) return "unsupported ELF file: more than 65534 program headers";
  if (h.e_phentsize != sizeof(Phdr)) {
    return "damaged ELF header: program header entries of " + std::to_string(h.e_phentsize) + " bytes";
  }
  const u64 ph_bytes = u64{h.e_phnum} * sizeof(Phdr);
  if (!inside(h.e_phoff, ph_bytes, image.size)) {
    return truncated("program headers end", h.e_phoff, ph_bytes, image.size);
  }
  image.segments.resize(h.e_phnum);
  if (!image.read(h.e_phoff, image.segments.data(), ph_bytes)) return "cannot read the program headers";
  if (h.e_shoff == 0) return std::nullopt;  // no section headers: allowed, ld.so never reads them
  if (h.e_shentsize != sizeof(Shdr)) {
    return "damaged ELF header: section header entries of " + std::to_string(h.e_shentsize) + " bytes";
  }
  // With e_shnum == 0 the real count is in the first entry's sh_size (more than 65279 sections).
  u64 count = h.e_shnum;
  if (count == 0) {
    Shdr first{};
    if (!inside(h.e_shoff, sizeof(Shdr), image.size)) {
      return truncated("section headers end", h.e_shoff, sizeof(Shdr), image.size);
    }
    if (!image.read(h.e_shoff, &first, sizeof(Shdr))) return "cannot read the section headers";
    count = first.sh_size;
  }
  if (count > std::numeric_limits<u64>::max() / sizeof(Shdr)) {  // the byte count would overflow
    return "truncated: the file claims " + std::to_string(count) + " section headers, file has " +
           std::to_string(image.size) + " bytes";
  }
  const u64 sh_bytes = count * sizeof(Shdr);
  if (!inside(h.e_shoff, sh_bytes, image.size)) {
    return truncated("section headers end", h.e_shoff, sh_bytes, image.size);
  }
  image.sections.resize(count);
  if (!image.read(h.e_shoff, image.sections.data(), sh_bytes)) return "cannot read the section headers";
  return std::nullopt;
}

const char* segment_type(u64 type) {
  switch (type) {
    case PT_LOAD: return "LOAD";
    case PT_DYNAMIC: return "DYNAMIC";
    case PT_NOTE: return "NOTE";
    case PT_GNU_EH_FRAME: return "GNU_EH_FRAME";
    default: return "other";
  }
}

// A section's name for messages, when the section name table itself is readable.
std::string section_name(const Image& image, std::size_t index) {
  std::string label = "section " + std::to_string(index);
  u64 names = image.header.e_shstrndx == SHN_XINDEX ? image.sections[0].sh_link : image.header.e_shstrndx;
  if (names >= image.sections.size()) return label;
  const Shdr& table = image.sections[names];
  const u64 at = image.sections[index].sh_name;
  if (at >= table.sh_size || !inside(table.sh_offset, table.sh_size, image.size)) return label;
  char buffer[64] = {};
  const u64 length = std::min<u64>(sizeof buffer - 1, table.sh_size - at);
  if (!image.read(table.sh_offset + at, buffer, length)) return label;
  return label + " (" + std::string(buffer, strnlen(buffer, length)) + ")";
}

Problem check_contents(const Image& image) {
  bool loadable = false;
  for (std::size_t i = 0; i < image.segments.size(); ++i) {
    const Phdr& p = image.segments[i];
    const std::string what = "segment " + std::to_string(i) + " (" + segment_type(p.p_type) + ")";
    if (p.p_filesz > 0 && !inside(p.p_offset, p.p_filesz, image.size)) {
      return truncated(what + " ends", p.p_offset, p.p_filesz, image.size);
    }
    if (p.p_type == PT_LOAD) {
      loadable = true;
      if (p.p_filesz > p.p_memsz) return "damaged ELF file: " + what + " is larger in the file than in memory";
    }
  }
  if (!loadable) return "not an ELF shared object: it has no loadable segment";
  for (std::size_t i = 0; i < image.sections.size(); ++i) {
    const Shdr& s = image.sections[i];
    if (s.sh_type == SHT_NOBITS || s.sh_size == 0) continue;  // .bss and the like occupy no file bytes
    if (!inside(s.sh_offset, s.sh_size, image.size)) {
      return truncated(section_name(image, i) + " ends", s.sh_offset, s.sh_size, image.size);
    }
  }
  return std::nullopt;
}

// Whether the virtual range [address, address + length) is backed by file bytes of a loaded segment
// (all of which check_contents found inside the file).
bool file_backed(const Image& image, u64 address, u64 length) {
  for (const Phdr& p : image.segments) {
    if (p.p_type == PT_LOAD && address >= p.p_vaddr && inside(address - p.p_vaddr, length, p.p_filesz)) return true;
  }
  return false;
}

// The tables the dynamic loader reads through the dynamic segment, with the entry giving each size
// (0: the loader reads at least the first entry).
struct DynamicTable {
  u64 tag;
  u64 size_tag;
  const char* name;
};
constexpr DynamicTable kDynamicTables[] = {
    {DT_STRTAB, DT_STRSZ, "DT_STRTAB"},       {DT_SYMTAB, 0, "DT_SYMTAB"},
    {DT_HASH, 0, "DT_HASH"},                  {DT_GNU_HASH, 0, "DT_GNU_HASH"},
    {DT_RELA, DT_RELASZ, "DT_RELA"},          {DT_REL, DT_RELSZ, "DT_REL"},
    {DT_JMPREL, DT_PLTRELSZ, "DT_JMPREL"},    {DT_INIT_ARRAY, DT_INIT_ARRAYSZ, "DT_INIT_ARRAY"},
    {DT_FINI_ARRAY, DT_FINI_ARRAYSZ, "DT_FINI_ARRAY"}, {DT_INIT, 0, "DT_INIT"},
    {DT_FINI, 0, "DT_FINI"},                  {DT_VERSYM, 0, "DT_VERSYM"},
    {DT_VERDEF, 0, "DT_VERDEF"},              {DT_VERNEED, 0, "DT_VERNEED"},
#ifdef DT_RELR
    {DT_RELR, DT_RELRSZ, "DT_RELR"},
#endif
};

Problem check_dynamic(const Image& image) {
  const Phdr* dynamic = nullptr;
  for (const Phdr& p : image.segments) {
    if (p.p_type == PT_DYNAMIC) dynamic = &p;
  }
  if (!dynamic) return "not an ELF shared object: it has no dynamic segment";
  if (!file_backed(image, dynamic->p_vaddr, dynamic->p_filesz)) {
    return "damaged ELF file: the dynamic segment lies outside the loaded segments";
  }
  std::vector<Dyn> entries(dynamic->p_filesz / sizeof(Dyn));
  if (!image.read(dynamic->p_offset, entries.data(), entries.size() * sizeof(Dyn))) {
    return "cannot read the dynamic segment";
  }
  std::size_t end = 0;
  while (end < entries.size() && entries[end].d_tag != DT_NULL) ++end;
  if (end == entries.size()) return "damaged ELF file: the dynamic segment has no DT_NULL terminator";
  auto value = [&](u64 tag) -> std::optional<u64> {
    for (std::size_t i = 0; i < end; ++i) {
      if (static_cast<u64>(entries[i].d_tag) == tag) return entries[i].d_un.d_val;
    }
    return std::nullopt;
  };
  for (const DynamicTable& table : kDynamicTables) {
    const auto address = value(table.tag);
    if (!address) continue;
    const u64 length = table.size_tag != 0 ? value(table.size_tag).value_or(1) : 1;
    if (!file_backed(image, *address, length)) {
      return "damaged ELF file: dynamic entry " + std::string(table.name) +
             " points outside the file's loaded segments";
    }
  }
  const u64 strings = value(DT_STRSZ).value_or(0);
  for (std::size_t i = 0; i < end; ++i) {
    const auto tag = entries[i].d_tag;
    const bool names_string = tag == DT_NEEDED || tag == DT_SONAME || tag == DT_RPATH || tag == DT_RUNPATH;
    if (names_string && entries[i].d_un.d_val >= strings) {
      return "damaged ELF file: a dynamic entry names a string outside the dynamic string table";
    }
  }
  return std::nullopt;
}

std::string file_kind(mode_t mode) {
  return S_ISDIR(mode) ? "a directory" : S_ISFIFO(mode) ? "a FIFO" : S_ISSOCK(mode) ? "a socket"
         : S_ISCHR(mode) || S_ISBLK(mode) ? "a device" : "not a regular file";
}

}  // namespace

std::optional<std::string> probe_plugin_file(const std::filesystem::path& file) {
  // stat before open: opening a device or a FIFO can block or act on it.
  struct stat info {};
  if (::stat(file.c_str(), &info) != 0) return "cannot read the file: " + std::string(std::strerror(errno));
  if (!S_ISREG(info.st_mode)) return "not a regular file (" + file_kind(info.st_mode) + ")";
  Image image;
  image.fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
  if (image.fd < 0) return "cannot open the file: " + std::string(std::strerror(errno));
  Problem problem;
  // fstat again on what was opened: the name may have been replaced since the stat.
  if (::fstat(image.fd, &info) != 0 || !S_ISREG(info.st_mode)) {
    problem = "not a regular file";
  } else {
    image.size = static_cast<u64>(info.st_size);
    problem = check_header(image);
    if (!problem) problem = read_tables(image);
    if (!problem) problem = check_contents(image);
    if (!problem) problem = check_dynamic(image);
  }
  ::close(image.fd);
  return problem;
}

namespace {

struct Segment {
  std::uintptr_t begin = 0;
  std::uintptr_t end = 0;
  unsigned flags = 0;
};

// The loaded segments of the library behind `handle`, as mapped in this process.
std::vector<Segment> loaded_segments(void* handle) {
  struct Search {
    const link_map* map = nullptr;
    std::vector<Segment> segments;
  } search;
  link_map* map = nullptr;
  if (dlinfo(handle, RTLD_DI_LINKMAP, &map) != 0 || !map) return {};
  search.map = map;
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void* data) -> int {
        auto* s = static_cast<Search*>(data);
        if (info->dlpi_addr != s->map->l_addr || !info->dlpi_name || !s->map->l_name ||
            std::strcmp(info->dlpi_name, s->map->l_name) != 0) {
          return 0;
        }
        for (std::size_t i = 0; i < info->dlpi_phnum; ++i) {
          const Phdr& p = info->dlpi_phdr[i];
          const std::uintptr_t begin = info->dlpi_addr + p.p_vaddr;
          if (p.p_type == PT_LOAD) s->segments.push_back({begin, begin + p.p_memsz, p.p_flags});
        }
        return 1;
      },
      &search);
  return search.segments;
}

bool within(const std::vector<Segment>& segments, const void* address, std::size_t length, unsigned flags) {
  const auto at = reinterpret_cast<std::uintptr_t>(address);
  for (const Segment& s : segments) {
    if ((s.flags & flags) == flags && at >= s.begin && inside(at - s.begin, length, s.end - s.begin)) return true;
  }
  return false;
}

}  // namespace

AliasLookup follow_alias(void* handle, const char* name, AliasTarget kind, std::size_t target_size) {
  AliasLookup out;
  const std::string quoted = std::string("'") + name + "'";
  dlerror();
  void* symbol = dlsym(handle, name);
  if (!symbol) {
    out.problem = "it does not export " + quoted;
    return out;
  }
  // dlsym also searches the libraries this one depends on: the alias must be this library's own.
  const std::vector<Segment> segments = loaded_segments(handle);
  if (!within(segments, symbol, sizeof(void*), PF_R)) {
    out.problem = quoted + " is not a readable object of this library";
    return out;
  }
  // The alias is a pointer-sized object holding an address; anything else (a plain `int`, a
  // function) would be followed as a wild pointer.
  Dl_info where{};
  void* extra = nullptr;
  const bool found = dladdr1(symbol, &where, &extra, RTLD_DL_SYMENT) != 0;
  const auto* entry = static_cast<const Sym*>(extra);
  if (!found || !entry || where.dli_saddr != symbol) {
    out.problem = "the loader cannot tell what " + quoted + " is";
    return out;
  }
  const unsigned type = ELF64_ST_TYPE(entry->st_info);  // the same for both ELF classes
  if (type != STT_OBJECT || entry->st_size != sizeof(void*)) {
    const std::string what = type == STT_FUNC     ? std::string("a function")
                             : type == STT_OBJECT ? "a " + std::to_string(entry->st_size) + "-byte object"
                                                  : "a symbol of ELF type " + std::to_string(type);
    out.problem = quoted + " is " + what + ", not the " + std::to_string(sizeof(void*)) +
                  "-byte alias PLUMAGE_PLUGIN exports";
    return out;
  }
  const void* target = *static_cast<const void* const*>(symbol);
  const unsigned flags = kind == AliasTarget::code ? PF_X : PF_R;
  if (!within(segments, target, target_size, flags)) {
    out.problem = quoted + " points outside this library's " + (kind == AliasTarget::code ? "code" : "readable data");
    return out;
  }
  out.target = target;
  return out;
}

}  // namespace plumage::detail
