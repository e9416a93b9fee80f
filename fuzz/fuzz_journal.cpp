// Characterisation journals (core/src/pipeline/journal.*): parse_journal from memory, then the
// resume path `characterize` takes on a journal beside its output (read_journal_resume), with
// the settings the journal itself names (so its records are matched, not discarded).
#include "fuzz_common.hpp"
#include "journal.hpp"
#include "plumage/characterize.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace plumage::fuzz;
  const auto file = scratch() / "fuzz-input.plm.journal";
  write_bytes(file, as_text(data, size));
  expect_typed_errors([&] {
    const plumage::JournalContents j = plumage::parse_journal(as_text(data, size), file.string());
    const auto settings = plumage::CharacterizeSettings::from_fingerprint(j.fingerprint, j.config_hash, j.inputs);
    plumage::read_journal_resume(file, settings);
  });
  return 0;
}
