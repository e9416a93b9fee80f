// Private to the pipeline: which warning codes (plumage/diagnostics.hpp) belong to which work
// group, and the material's warnings from its records (warning_attribution.cpp).
//
// Groups run one after another in a process, so the codes whose raise counts grew while a group
// was computed are that group's; a record keeps them, and the material's warnings are made from
// the records alone: the same for one process, shards, MPI ranks and resumed runs, whatever the
// thread scheduling.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "plumage/characterize_records.hpp"

namespace plumage {

using RaiseCounts = std::map<std::string, std::size_t>;
RaiseCounts raise_counts();                                    // per code, of this process
std::set<std::string> raised_since(const RaiseCounts& before);  // codes raised again since

// Per code (sorted): in how many work groups it was raised and the first group (in group order).
// `groups` in group order.
std::string material_warnings(const CharacterizeSettings& s, const std::vector<const GroupRecord*>& groups);

// Another process's diagnostics().summary() raised here as "rank <r>: <message>" per code, so
// every MPI rank's warnings reach rank 0's stderr.
void relay_rank_warnings(int rank, const std::string& summary);

}  // namespace plumage
