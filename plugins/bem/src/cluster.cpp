// Geometric cluster tree and admissible block partition; see cluster.hpp.
#include "cluster.hpp"

#include <algorithm>
#include <cmath>

namespace plumage::bem {

double Cluster::diameter() const { return std::hypot(xmax - xmin, zmax - zmin); }

double cluster_distance(const Cluster& a, const Cluster& b) {
  const double dx = std::max({0.0, a.xmin - b.xmax, b.xmin - a.xmax});
  const double dz = std::max({0.0, a.zmin - b.zmax, b.zmin - a.zmax});
  return std::hypot(dx, dz);
}

namespace {

void bound(const Mesh& mesh, const std::vector<int>& order, Cluster& c) {
  c.xmin = c.zmin = 1e300;
  c.xmax = c.zmax = -1e300;
  for (int k = c.begin; k < c.end; ++k) {
    const Segment& s = mesh.segments[order[k]];
    c.hmax = std::max(c.hmax, s.h);
    for (const Vec2& p : {s.p0, s.p1}) {
      c.xmin = std::min(c.xmin, p.x), c.xmax = std::max(c.xmax, p.x);
      c.zmin = std::min(c.zmin, p.z), c.zmax = std::max(c.zmax, p.z);
    }
  }
}

void split(const Mesh& mesh, ClusterTree& t, int node, int leaf_size) {
  Cluster c = t.nodes[node];
  if (c.size() <= leaf_size) return;
  const bool along_x = (c.xmax - c.xmin) >= (c.zmax - c.zmin);
  auto key = [&](int s) {
    const Segment& g = mesh.segments[s];
    return along_x ? g.p0.x + g.p1.x : g.p0.z + g.p1.z;
  };
  const int mid = c.begin + c.size() / 2;
  // nth_element with a total order (key, then index) keeps the tree deterministic
  std::nth_element(t.order.begin() + c.begin, t.order.begin() + mid, t.order.begin() + c.end, [&](int a, int b) {
    const double ka = key(a), kb = key(b);
    return ka < kb || (ka == kb && a < b);
  });
  for (int h = 0; h < 2; ++h) {
    Cluster ch;
    ch.begin = h == 0 ? c.begin : mid;
    ch.end = h == 0 ? mid : c.end;
    bound(mesh, t.order, ch);
    t.nodes[node].child[h] = static_cast<int>(t.nodes.size());
    t.nodes.push_back(ch);
  }
  const int c0 = t.nodes[node].child[0], c1 = t.nodes[node].child[1];
  split(mesh, t, c0, leaf_size);
  split(mesh, t, c1, leaf_size);
}

void partition(const ClusterTree& t, int r, int c, double eta, double nf, BlockPartition& out) {
  const Cluster& a = t.nodes[r];
  const Cluster& b = t.nodes[c];
  const double dist = cluster_distance(a, b);
  if (std::max(a.diameter(), b.diameter()) <= eta * dist && dist > nf * std::max(a.hmax, b.hmax)) {
    out.admissible.push_back({r, c});
    return;
  }
  if (a.leaf() || b.leaf()) {
    if (a.leaf() && b.leaf()) {
      out.near.push_back({r, c});
    } else if (a.leaf()) {
      for (int k : b.child) partition(t, r, k, eta, nf, out);
    } else {
      for (int k : a.child) partition(t, k, c, eta, nf, out);
    }
    return;
  }
  for (int i : a.child) {
    for (int j : b.child) partition(t, i, j, eta, nf, out);
  }
}

}  // namespace

ClusterTree build_cluster_tree(const Mesh& mesh, const std::vector<int>& segments, int leaf_size) {
  ClusterTree t;
  t.order = segments;
  if (segments.empty()) return t;
  Cluster root;
  root.begin = 0;
  root.end = static_cast<int>(segments.size());
  bound(mesh, t.order, root);
  t.nodes.push_back(root);
  split(mesh, t, 0, std::max(1, leaf_size));
  return t;
}

BlockPartition partition_blocks(const ClusterTree& tree, double eta, double near_factor) {
  BlockPartition p;
  if (!tree.nodes.empty()) partition(tree, 0, 0, eta, near_factor, p);
  return p;
}

}  // namespace plumage::bem
