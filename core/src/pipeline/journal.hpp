// Private to the pipeline: what a journal beside the output already holds (journal.cpp).
#pragma once

#include <cstdint>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "plumage/characterize_records.hpp"

namespace plumage {

// The groups done and the journal's valid byte count. `matches` is false (and nothing is done)
// when it was written with other settings.
struct JournalResume {
  std::set<std::size_t> done;
  std::uintmax_t valid_bytes = 0;
  bool matches = true;
  std::string fingerprint;
  std::vector<std::string> damaged;  // one message per damaged record skipped
};
JournalResume read_journal_resume(const std::filesystem::path& journal, const CharacterizeSettings& s);

}  // namespace plumage
