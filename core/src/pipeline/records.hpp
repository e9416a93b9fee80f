// Private to the pipeline: parsing single work records (the bytes of serialize(), records.cpp).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "plumage/characterize_records.hpp"
#include "plumage/error.hpp"

namespace plumage {

inline constexpr std::uint32_t kRecordMagic = 0x524d4c50;  // "PLMR"

// The record at `pos` (advanced past it), or nothing when the bytes there are incomplete or
// corrupt (a run killed while appending).
std::optional<GroupRecord> parse_record(std::string_view data, std::size_t& pos);
// A whole run of records (e.g. an MPI rank's); Error naming `name` at the first bad one.
std::vector<GroupRecord> parse_records(std::string_view data, const std::string& name);

}  // namespace plumage
