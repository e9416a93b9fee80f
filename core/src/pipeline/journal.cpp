// Journals and shard files of a characterisation: a text header and appended, checksummed work
// records (characterize_records.hpp; layout: docs/formats.md).
#include "journal.hpp"

#include "plumage/atomic_file.hpp"
#include "plumage/input_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <optional>
#include <cstring>

#include "records.hpp"

namespace plumage {

namespace {

constexpr std::string_view kJournalMagic = "plumage-characterize-journal ";
constexpr int kJournalFormat = 2;  // 2: config hash and material inputs in the header

// The next '\n'-terminated line at `pos` (advanced past it), or nothing.
std::optional<std::string_view> line_at(std::string_view data, std::size_t& pos) {
  const auto end = data.find('\n', pos);
  if (end == std::string_view::npos) return std::nullopt;
  const std::string_view line = data.substr(pos, end - pos);
  pos = end + 1;
  return line;
}

// Format 2: "config_hash <hex>", "inputs <bytes>" and that many bytes after the fingerprint.
bool parse_header_v2(std::string_view data, std::size_t& pos, JournalContents& j) {
  const auto hash = line_at(data, pos);
  const auto inputs = line_at(data, pos);
  if (!hash || !inputs || hash->rfind("config_hash ", 0) != 0 || inputs->rfind("inputs ", 0) != 0) return false;
  j.config_hash = std::string(hash->substr(12));
  const std::string count(inputs->substr(7));
  char* end = nullptr;
  const unsigned long long n = std::strtoull(count.c_str(), &end, 10);
  if (count.empty() || *end != '\0' || n > data.size() - pos) return false;
  j.inputs = std::string(data.substr(pos, n));
  pos += n;
  return true;
}

// Whether the bytes from `at` to the end are one record by their length field (a record whose
// body is damaged; a kill while appending leaves fewer bytes than its length says).
bool whole_record_at(std::string_view data, std::size_t at) {
  std::uint32_t magic = 0;
  std::uint64_t len = 0;
  if (data.size() - at < 12) return false;
  std::memcpy(&magic, data.data() + at, 4);
  std::memcpy(&len, data.data() + at + 4, 8);
  return magic == kRecordMagic && len == data.size() - at - 20;
}

// The offset of the first record at or after `from` that parses whole, or data.size().
std::size_t next_record(std::string_view data, std::size_t from) {
  char magic[4];
  std::memcpy(magic, &kRecordMagic, 4);
  for (std::size_t at = data.find(std::string_view(magic, 4), from); at != std::string_view::npos;
       at = data.find(std::string_view(magic, 4), at + 1)) {
    std::size_t p = at;
    if (parse_record(data, p)) return at;
  }
  return data.size();
}

}  // namespace

std::string journal_header(const CharacterizeSettings& s) {
  return std::string(kJournalMagic) + std::to_string(kJournalFormat) + "\n" + s.fingerprint() + "\nconfig_hash " +
         s.config_hash + "\ninputs " + std::to_string(s.inputs.size()) + "\n" + s.inputs;
}

JournalContents parse_journal(std::string_view data, const std::string& name) {
  JournalContents j;
  std::size_t pos = 0;
  const auto magic = line_at(data, pos);
  const auto fingerprint = line_at(data, pos);
  if (magic && magic->rfind(kJournalMagic, 0) == 0)
    j.format = std::atoi(std::string(magic->substr(kJournalMagic.size())).c_str());
  if (!fingerprint || (j.format != 1 && j.format != kJournalFormat) ||
      (j.format == kJournalFormat && !parse_header_v2(data, pos, j)))
    throw InputFileError(name, "not a plumage characterisation journal or shard file (bad header)");
  j.fingerprint = std::string(*fingerprint);
  j.valid_bytes = pos;
  while (pos < data.size()) {
    const std::size_t at = pos;
    auto r = parse_record(data, pos);
    if (!r) {
      // A damaged record: resume at the next one that parses whole (its checksum makes a false
      // start in the damaged bytes practically impossible); none means a torn tail.
      pos = next_record(data, at + 1);
      if (pos == data.size()) {
        if (whole_record_at(data, at)) j.damaged.push_back({at, pos});  // damaged, not torn by a kill
        break;
      }
      j.damaged.push_back({at, pos});
      continue;
    }
    j.records.push_back(std::move(*r));
    j.valid_bytes = pos;
  }
  return j;
}

JournalContents read_journal(const std::filesystem::path& file) {
  const std::string data = read_input_file(file, "characterisation journal or shard");
  return parse_journal(data, file.string());
}

JournalWriter::JournalWriter(const std::filesystem::path& file, const CharacterizeSettings& s, std::uintmax_t valid_bytes)
    : file_(file) {
  const bool fresh = valid_bytes == 0;
  check_output_path(file);  // open(2) would write through a symlink or into a device
  if (!fresh) std::filesystem::resize_file(file, valid_bytes);  // drop a torn tail
  fd_ = ::open(file.c_str(), O_WRONLY | O_CREAT | O_APPEND | (fresh ? O_TRUNC : 0), 0644);
  if (fd_ < 0) throw Error(file.string() + ": cannot open journal for writing: " + std::strerror(errno));
  if (fresh) {
    const std::string h = journal_header(s);
    if (::write(fd_, h.data(), h.size()) != static_cast<ssize_t>(h.size()))
      throw Error(file.string() + ": cannot write journal header");
    ::fsync(fd_);
  }
}

JournalWriter::~JournalWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void JournalWriter::append(const GroupRecord& r) {
  const std::string bytes = serialize(r);
  if (::write(fd_, bytes.data(), bytes.size()) != static_cast<ssize_t>(bytes.size()))
    throw Error(file_.string() + ": cannot append to journal: " + std::strerror(errno));
  ::fdatasync(fd_);
}

JournalResume read_journal_resume(const std::filesystem::path& journal, const CharacterizeSettings& s) {
  JournalResume resume;
  check_output_path(journal);  // reading a FIFO would hang; a symlinked journal is refused anyway
  if (!std::filesystem::exists(journal)) return resume;
  const JournalContents j = read_journal(journal);
  resume.fingerprint = j.fingerprint;
  if (j.fingerprint != s.fingerprint()) {
    resume.matches = false;
    return resume;
  }
  for (const auto& r : j.records) resume.done.insert(r.w * static_cast<std::size_t>(s.grid) + (r.a - 1));
  resume.valid_bytes = j.valid_bytes;
  for (const auto& d : j.damaged)
    resume.damaged.push_back(journal.string() + ": damaged record at bytes " + std::to_string(d.offset) + " to " +
                             std::to_string(d.end) + " skipped (its work group is recomputed; " +
                             std::to_string(j.records.size()) + " good records kept)");
  return resume;
}

}  // namespace plumage
