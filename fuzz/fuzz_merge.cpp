// Shard files through merge_shards (what `plumage merge` calls): the input is one or more shards
// separated by kSeparator (the seeds are two real shards of one characterisation); the merged
// material goes to the scratch folder.
#include <vector>

#include "fuzz_common.hpp"
#include "plumage/characterize.hpp"

namespace {
constexpr std::string_view kSeparator = "\n=plumage-fuzz-next-shard=\n";
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace plumage::fuzz;
  std::string_view rest = as_text(data, size);
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
  return 0;
}
