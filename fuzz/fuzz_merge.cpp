// Shard files through merge_shards (what `plumage merge` calls): the input is one or more shards
// separated by kSeparator (the seeds are two real shards of one characterisation); the merged
// material goes to the scratch folder.
#include <vector>

#include "fuzz_common.hpp"
#include "plumage/characterize.hpp"

namespace {
constexpr std::string_view kSeparator = "\n=plumage-fuzz-next-shard=\n";
}

namespace {

void merge(std::string_view rest) {
  using namespace plumage::fuzz;
  std::vector<std::filesystem::path> shards;
  while (shards.size() < 8) {
    const auto cut = rest.find(kSeparator);
    const auto file = scratch() / ("fuzz-input-" + std::to_string(shards.size()) + ".shard");
    write_bytes(file, rest.substr(0, cut));
    shards.push_back(file);
    if (cut == std::string_view::npos) break;
    rest.remove_prefix(cut + kSeparator.size());
  }
  const auto out = scratch() / "merged.plm";
  expect_typed_errors([&] { plumage::merge_shards(shards, out); });
  std::filesystem::remove(out);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace plumage::fuzz;
  merge(as_text(data, size));
  // The same bytes with every record's checksum made right (fuzz_common.hpp).
  const std::string fixed = with_record_checksums(as_text(data, size));
  if (!fixed.empty()) merge(fixed);
  return 0;
}
