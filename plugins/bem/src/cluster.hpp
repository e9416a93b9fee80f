// Cluster tree of the segments of one domain and the block partition of that domain's operator
// (hierarchical matrix, NOTES.md §5): clusters are contiguous ranges of a permuted segment list,
// split at the median along the longer side of their bounding box; a pair of clusters is
// admissible (low rank, compressed by ACA) when max(diam) ≤ η · dist of their bounding boxes.
#pragma once

#include <vector>

#include "mesh.hpp"

namespace plumage::bem {

struct Cluster {
  int begin = 0, end = 0;  // range in ClusterTree::order
  double xmin = 0, xmax = 0, zmin = 0, zmax = 0;
  double hmax = 0;  // longest segment
  int child[2] = {-1, -1};
  bool leaf() const { return child[0] < 0; }
  int size() const { return end - begin; }
  double diameter() const;
};

struct ClusterTree {
  std::vector<int> order;  // mesh segment indices, permuted so that every cluster is a range
  std::vector<Cluster> nodes;  // nodes[0] = root
};

ClusterTree build_cluster_tree(const Mesh& mesh, const std::vector<int>& segments, int leaf_size);

struct BlockPair {
  int row = 0, col = 0;  // cluster node indices
};

struct BlockPartition {
  std::vector<BlockPair> admissible;  // low-rank blocks
  std::vector<BlockPair> near;        // exact (inadmissible leaf pairs)
};

// Recursive partition of root × root; `eta` as above. A pair is admissible only if, in addition,
// its distance exceeds near_factor · (longest segment of both): every segment pair of an admissible
// block is then integrated by the smooth far-field rule (pair_integrals.hpp). Without it, a block
// mixing both rules is not smooth at the quadrature-error level and ACA cannot compress it to ε
// (junction body: mat-vec error 1.3e-4 at ε = 1e-6).
BlockPartition partition_blocks(const ClusterTree& tree, double eta, double near_factor);

double cluster_distance(const Cluster& a, const Cluster& b);

}  // namespace plumage::bem
