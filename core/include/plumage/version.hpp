// Version of the plumage SDK and of the plug-in ABI.
#pragma once

namespace plumage {

// Bumped whenever a change to a header in core/include/plumage/ breaks binary compatibility with
// plug-ins built against an earlier SDK (a virtual function added, a struct layout changed...).
// The host refuses a plug-in whose exported plumage_abi_version differs.
// 2: ParamSpec gained range and condition (issue 22).
// 3: ScatteringSolver::estimate_memory and TableBuilder::estimate_memory (issue 23, memory budgets).
inline constexpr int kAbiVersion = 3;

inline constexpr const char* kVersionString = "0.1.0";

}  // namespace plumage
