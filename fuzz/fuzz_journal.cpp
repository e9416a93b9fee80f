// Characterisation journals (core/src/pipeline/journal.*): parse_journal from memory, then the
// resume path `characterize` takes on a journal beside its output (read_journal_resume), with
// the settings the journal itself names (so its records are matched, not discarded).
#include "fuzz_common.hpp"
#include "journal.hpp"
#include "plumage/characterize.hpp"

namespace {

void read(const std::filesystem::path& file, std::string_view bytes) {
  using namespace plumage::fuzz;
  write_bytes(file, bytes);
  expect_typed_errors([&] {
    const plumage::JournalContents j = plumage::parse_journal(bytes, file.string());
    const auto settings = plumage::CharacterizeSettings::from_fingerprint(j.fingerprint, j.config_hash, j.inputs);
    plumage::read_journal_resume(file, settings);
  });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace plumage::fuzz;
  const auto file = scratch() / "fuzz-input.plm.journal";
  read(file, as_text(data, size));
  // The same bytes with every record's checksum made right (fuzz_common.hpp).
  const std::string fixed = with_record_checksums(as_text(data, size));
  if (!fixed.empty()) read(file, fixed);
  return 0;
}
