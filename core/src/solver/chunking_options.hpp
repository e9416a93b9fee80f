// How the approximate solver evaluates its far field (radiation.hpp).
#pragma once

namespace plumage::detail {

struct ChunkingOptions {
  bool chunked = true;        // false: every (node, direction) kernel entry
  double chunk_phase = 18.0;  // target γ0·R_c of a chunk (R_c its radius)
  double oversampling = 3.0;  // sampling grid step = π/(oversampling · band limit)
};

}  // namespace plumage::detail
