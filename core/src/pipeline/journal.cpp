// Journals and shard files of a characterisation: a text header and appended, checksummed work
// records (characterize_records.hpp; layout: docs/formats.md).
#include "journal.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>

#include "records.hpp"

namespace plumage {

namespace {

constexpr char kJournalMagic[] = "plumage-characterize-journal 1";

}  // namespace

std::string journal_header(const CharacterizeSettings& s) {
  return std::string(kJournalMagic) + "\n" + s.fingerprint() + "\n";
}

JournalContents parse_journal(std::string_view data, const std::string& name) {
  JournalContents j;
  const auto l1 = data.find('\n');
  const auto l2 = l1 == std::string::npos ? std::string::npos : data.find('\n', l1 + 1);
  if (l2 == std::string::npos || data.compare(0, l1, kJournalMagic) != 0)
    throw Error(name + ": not a plumage characterisation journal or shard file (bad header)");
  j.fingerprint = std::string(data.substr(l1 + 1, l2 - l1 - 1));
  std::size_t pos = l2 + 1;
  j.valid_bytes = pos;
  while (pos < data.size()) {
    auto r = parse_record(data, pos);
    if (!r) break;
    j.records.push_back(std::move(*r));
    j.valid_bytes = pos;
  }
  return j;
}

JournalContents read_journal(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error(file.string() + ": cannot open characterisation journal");
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return parse_journal(data, file.string());
}

JournalWriter::JournalWriter(const std::filesystem::path& file, const CharacterizeSettings& s, std::uintmax_t valid_bytes)
    : file_(file) {
  const bool fresh = valid_bytes == 0;
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
  if (!std::filesystem::exists(journal)) return resume;
  const JournalContents j = read_journal(journal);
  resume.fingerprint = j.fingerprint;
  if (j.fingerprint != s.fingerprint()) {
    resume.matches = false;
    return resume;
  }
  for (const auto& r : j.records) resume.done.insert(r.w * static_cast<std::size_t>(s.grid) + (r.a - 1));
  resume.valid_bytes = j.valid_bytes;
  return resume;
}

}  // namespace plumage
