// Interfaces and segments of the BEM mesh (spec §6.3, §6.4, §6.6); see mesh.hpp.
#include "mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <queue>
#include <unordered_map>

#include "pair_integrals.hpp"
#include "plumage/error.hpp"

namespace plumage::bem {

namespace {

using Key = std::pair<std::int64_t, std::int64_t>;
// Vertices are identified by their position quantised to 1e-4 nm (generators share vertices
// exactly; this only absorbs the last bits of independently computed copies).
Key key_of(Vec2 p) { return {std::llround(p.x * 1e4), std::llround(p.z * 1e4)}; }

struct KeyHash {
  std::size_t operator()(const Key& k) const {
    return std::hash<std::int64_t>()(k.first * 1000003 ^ k.second);
  }
};

std::string region_label(const CrossSection& s, int r) {
  if (r < 0) return "air";
  const Region& reg = s.regions[r];
  return "region " + std::to_string(r) + " (" + std::string(role_name(reg.role)) + ")";
}

}  // namespace

namespace {

// Depth of each region in the parent tree (0: in air); checks the regions' order and outlines.
std::vector<int> region_depths(const CrossSection& section) {
  const auto& regions = section.regions;
  const int nr = static_cast<int>(regions.size());
  if (nr == 0) throw Error("bem: cross section '" + section.label + "' has no regions");
  std::vector<int> depth(nr, 0);
  for (int r = 0; r < nr; ++r) {
    const int p = regions[r].parent;
    if (p >= r) throw Error("bem: " + region_label(section, r) + " has parent " + std::to_string(p) +
                            ", which does not precede it");
    depth[r] = p < 0 ? 0 : depth[p] + 1;
    if (regions[r].outline.size() < 3) throw Error("bem: " + region_label(section, r) + " has fewer than 3 vertices");
  }
  return depth;
}

// An elementary edge and its owners: (region, +1 if the region's outline runs from the smaller
// to the larger key (region on the left of that direction), −1 otherwise).
struct Owned {
  Vec2 p, q;  // p has the smaller key
  std::vector<std::pair<int, int>> owners;
};
using OwnedEdges = std::map<std::pair<Key, Key>, Owned>;

// The outlines' edges split at vertices of other outlines that lie on them (a child whose side runs
// along part of its parent's side, as in layered slabs), found through a grid of all vertices.
OwnedEdges owned_edges(const CrossSection& section) {
  const auto& regions = section.regions;
  const int nr = static_cast<int>(regions.size());
  double total = 0.0;
  std::size_t count = 0;
  std::vector<Vec2> all;
  for (const Region& reg : regions) {
    for (std::size_t k = 0; k < reg.outline.size(); ++k) {
      all.push_back(reg.outline[k]);
      total += norm(reg.outline[(k + 1) % reg.outline.size()] - reg.outline[k]);
      ++count;
    }
  }
  const double cell = std::max(1e-3, 2.0 * total / count);
  std::unordered_map<Key, std::vector<int>, KeyHash> grid;
  auto cell_of = [&](double x, double z) {
    return Key{static_cast<std::int64_t>(std::floor(x / cell)), static_cast<std::int64_t>(std::floor(z / cell))};
  };
  for (int i = 0; i < static_cast<int>(all.size()); ++i) grid[cell_of(all[i].x, all[i].z)].push_back(i);

  OwnedEdges edges;
  for (int r = 0; r < nr; ++r) {
    const Polygon& poly = regions[r].outline;
    if (signed_area(poly) <= 0.0) throw Error("bem: " + region_label(section, r) + " is not counter-clockwise");
    for (std::size_t k = 0; k < poly.size(); ++k) {
      const Vec2 p = poly[k], q = poly[(k + 1) % poly.size()];
      const Vec2 d = q - p;
      const double len = norm(d);
      if (len <= 0.0) continue;
      // vertices strictly inside the edge
      std::vector<std::pair<double, Vec2>> cuts{{0.0, p}, {1.0, q}};
      const Key c0 = cell_of(std::min(p.x, q.x), std::min(p.z, q.z));
      const Key c1 = cell_of(std::max(p.x, q.x), std::max(p.z, q.z));
      const double tol = 1e-6 + 1e-9 * len;
      for (auto i = c0.first; i <= c1.first; ++i) {
        for (auto j = c0.second; j <= c1.second; ++j) {
          auto it = grid.find({i, j});
          if (it == grid.end()) continue;
          for (int vi : it->second) {
            const Vec2 v = all[vi];
            const double s = dot(v - p, d) / (len * len);
            if (s * len <= tol || (1.0 - s) * len <= tol) continue;
            if (std::abs(cross(d, v - p)) / len > tol) continue;
            cuts.push_back({s, v});
          }
        }
      }
      std::sort(cuts.begin(), cuts.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
        Vec2 a = cuts[c].second, b = cuts[c + 1].second;
        Key ka = key_of(a), kb = key_of(b);
        if (ka == kb) continue;
        int dir = +1;
        if (kb < ka) std::swap(ka, kb), std::swap(a, b), dir = -1;
        Owned& e = edges[{ka, kb}];
        if (e.owners.empty()) e.p = a, e.q = b;
        e.owners.push_back({r, dir});
      }
    }
  }
  return edges;
}

}  // namespace

Geometry build_geometry(const CrossSection& section) {
  const auto& regions = section.regions;
  const std::vector<int> depth = region_depths(section);
  const int nr = static_cast<int>(regions.size());
  const OwnedEdges edges = owned_edges(section);

  Geometry g;
  g.domain_material.push_back(Material::air());
  g.domain_name.push_back("air");
  for (int r = 0; r < nr; ++r) {
    g.domain_material.push_back(regions[r].material);
    g.domain_name.push_back(region_label(section, r));
  }
  auto deepest = [&](const std::vector<int>& rs) {
    int best = rs.front();
    for (int r : rs) {
      if (depth[r] > depth[best]) best = r;
    }
    for (int r : rs) {
      if (r != best && depth[r] == depth[best]) {
        throw Error("bem: " + region_label(section, r) + " and " + region_label(section, best) +
                    " overlap along an edge (same side of a shared boundary)");
      }
    }
    return best;
  };
  auto shallowest_parent = [&](const std::vector<int>& rs) {
    int best = rs.front();
    for (int r : rs) {
      if (depth[r] < depth[best]) best = r;
    }
    return regions[best].parent;
  };
  for (auto& [key, e] : edges) {
    std::vector<int> left, right;
    for (auto [r, dir] : e.owners) (dir > 0 ? left : right).push_back(r);
    const int l = left.empty() ? shallowest_parent(right) : deepest(left);
    const int rr = right.empty() ? shallowest_parent(left) : deepest(right);
    if (l == rr) continue;  // a boundary inside one medium region (e.g. parent edge under a child)
    const int dl = l + 1, dr = rr + 1;
    // n̂ = ŷ × t̂ is the right-hand side of t̂ in the (x, z) view; it must point into a = min.
    InterfaceEdge ie;
    ie.a = std::min(dl, dr);
    ie.b = std::max(dl, dr);
    if (dr == ie.a) ie.p = e.p, ie.q = e.q;
    else ie.p = e.q, ie.q = e.p;
    g.edges.push_back(ie);
  }
  if (g.edges.empty()) throw Error("bem: cross section '" + section.label + "' has no interfaces");
  return g;
}

Mesh build_mesh(const Geometry& geometry, double lambda_nm, double ppw, double corner_split_deg) {
  const double corner_cos = std::cos(corner_split_deg * std::numbers::pi / 180.0);
  Mesh mesh;
  mesh.a_count = static_cast<int>(geometry.domain_material.size());
  std::vector<double> hmax(mesh.a_count);
  for (int d = 0; d < mesh.a_count; ++d) {
    hmax[d] = lambda_nm / (std::abs(geometry.domain_material[d].index(lambda_nm)) * ppw);
  }
  std::unordered_map<Key, int, KeyHash> vid;
  auto vertex = [&](Vec2 p) {
    auto [it, fresh] = vid.try_emplace(key_of(p), static_cast<int>(mesh.vertices.size()));
    if (fresh) mesh.vertices.push_back(p);
    return it->second;
  };
  for (const InterfaceEdge& e : geometry.edges) {
    const double len = norm(e.q - e.p);
    const int n = std::max(1, static_cast<int>(std::ceil(len / std::min(hmax[e.a], hmax[e.b]) - 1e-9)));
    int prev = vertex(e.p);
    for (int k = 1; k <= n; ++k) {
      const Vec2 p = k == n ? e.q : e.p + (static_cast<double>(k) / n) * (e.q - e.p);
      const int cur = vertex(p);
      Segment s;
      s.v0 = prev, s.v1 = cur, s.a = e.a, s.b = e.b;
      s.p0 = mesh.vertices[prev], s.p1 = mesh.vertices[cur];
      const Vec2 d = s.p1 - s.p0;
      s.h = norm(d);
      s.t = (1.0 / s.h) * d;
      s.n = {s.t.z, -s.t.x};
      mesh.segments.push_back(s);
      prev = cur;
    }
  }
  mesh.n_t = static_cast<int>(mesh.vertices.size());
  // z-coefficients: shared by the two segments of one interface through a regular vertex,
  // separate half tents at junctions (§6.6) and at corners where the tangent turns by
  // corner_split_deg or more (both segments run the same way through the vertex, so t̂0·t̂1 is
  // the cosine of the turn).
  std::vector<std::vector<std::pair<int, int>>> incident(mesh.n_t);  // (segment, end)
  for (int s = 0; s < static_cast<int>(mesh.segments.size()); ++s) {
    incident[mesh.segments[s].v0].push_back({s, 0});
    incident[mesh.segments[s].v1].push_back({s, 1});
  }
  int nz = 0;
  for (int v = 0; v < mesh.n_t; ++v) {
    const auto& inc = incident[v];
    if (inc.size() < 2) {
      throw Error("bem: an interface between " + geometry.domain_name[mesh.segments[inc[0].first].a] + " and " +
                  geometry.domain_name[mesh.segments[inc[0].first].b] + " ends at (" +
                  std::to_string(mesh.vertices[v].x) + ", " + std::to_string(mesh.vertices[v].z) +
                  ") nm without closing");
    }
    const Segment& s0 = mesh.segments[inc[0].first];
    const Segment& s1 = mesh.segments[inc[1].first];
    if (inc.size() == 2 && s0.a == s1.a && s0.b == s1.b && inc[0].second != inc[1].second &&
        dot(s0.t, s1.t) > corner_cos) {
      mesh.segments[inc[0].first].zdof[inc[0].second] = nz;
      mesh.segments[inc[1].first].zdof[inc[1].second] = nz;
      mesh.z_vertex.push_back(v);
      ++nz;
    } else {
      for (auto [s, end] : inc) {
        mesh.segments[s].zdof[end] = nz++;
        mesh.z_vertex.push_back(v);
      }
    }
  }
  mesh.n_z = nz;
  mesh.domain_segments.assign(mesh.a_count, {});
  for (int s = 0; s < static_cast<int>(mesh.segments.size()); ++s) {
    mesh.domain_segments[mesh.segments[s].a].push_back(s);
    mesh.domain_segments[mesh.segments[s].b].push_back(s);
  }
  return mesh;
}

MeshResolution mesh_resolution(const Mesh& mesh, const Geometry& geometry, double lambda_nm, double threshold) {
  MeshResolution r;
  std::vector<double> n(geometry.domain_material.size());
  for (std::size_t d = 0; d < n.size(); ++d) n[d] = std::abs(geometry.domain_material[d].index(lambda_nm));
  double total = 0.0, coarse = 0.0;
  r.min_ppw = 1e300;
  for (const Segment& s : mesh.segments) {
    const int dense = n[s.a] >= n[s.b] ? s.a : s.b;
    const double ppw = lambda_nm / (n[dense] * s.h);
    total += s.h;
    if (ppw < threshold) coarse += s.h;
    if (ppw < r.min_ppw) r.min_ppw = ppw, r.domain = dense, r.h_nm = s.h;
  }
  r.length_fraction = total > 0.0 ? coarse / total : 0.0;
  return r;
}

CloseApproach closest_approach(const Mesh& mesh, double ratio, double path_factor) {
  CloseApproach out;
  const int ns = static_cast<int>(mesh.segments.size());
  if (ns == 0) return out;
  double hmax = 0.0;
  for (const Segment& s : mesh.segments) hmax = std::max(hmax, s.h);
  // Segments bucketed by the cells their bounding boxes cover (cell = longest segment, so a
  // segment covers at most 2 × 2 cells and the search reaches ratio·h ≤ one cell further).
  const double cell = hmax;
  auto cell_of = [&](double v) { return static_cast<std::int64_t>(std::floor(v / cell)); };
  std::unordered_map<Key, std::vector<int>, KeyHash> grid;
  for (int i = 0; i < ns; ++i) {
    const Segment& s = mesh.segments[i];
    for (auto x = cell_of(std::min(s.p0.x, s.p1.x)); x <= cell_of(std::max(s.p0.x, s.p1.x)); ++x) {
      for (auto z = cell_of(std::min(s.p0.z, s.p1.z)); z <= cell_of(std::max(s.p0.z, s.p1.z)); ++z) {
        grid[{x, z}].push_back(i);
      }
    }
  }
  // Vertex graph along the mesh (for "neighbours along the mesh").
  std::vector<std::vector<std::pair<int, double>>> adj(mesh.vertices.size());
  for (const Segment& s : mesh.segments) {
    adj[s.v0].push_back({s.v1, s.h});
    adj[s.v1].push_back({s.v0, s.h});
  }
  // Is there a path along the mesh from an end of A to an end of B no longer than `budget`?
  auto connected = [&](const Segment& A, const Segment& B, double budget) {
    std::unordered_map<int, double> best;
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
    for (int v : {A.v0, A.v1}) best[v] = 0.0, queue.push({0.0, v});
    while (!queue.empty()) {
      const auto [d, v] = queue.top();
      queue.pop();
      if (v == B.v0 || v == B.v1) return true;
      if (d > best[v]) continue;
      for (const auto& [w, len] : adj[v]) {
        const double dw = d + len;
        if (dw > budget) continue;
        auto it = best.find(w);
        if (it != best.end() && it->second <= dw) continue;
        best[w] = dw;
        queue.push({dw, w});
      }
    }
    return false;
  };
  double worst = 1e300;
  std::vector<int> seen;
  for (int i = 0; i < ns; ++i) {
    const Segment& A = mesh.segments[i];
    const double reach = ratio * hmax;
    seen.clear();
    for (auto x = cell_of(std::min(A.p0.x, A.p1.x) - reach); x <= cell_of(std::max(A.p0.x, A.p1.x) + reach); ++x) {
      for (auto z = cell_of(std::min(A.p0.z, A.p1.z) - reach); z <= cell_of(std::max(A.p0.z, A.p1.z) + reach); ++z) {
        auto it = grid.find({x, z});
        if (it == grid.end()) continue;
        for (int j : it->second) {
          if (j > i) seen.push_back(j);
        }
      }
    }
    std::sort(seen.begin(), seen.end());
    seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
    for (int j : seen) {
      const Segment& B = mesh.segments[j];
      if (A.v0 == B.v0 || A.v0 == B.v1 || A.v1 == B.v0 || A.v1 == B.v1) continue;
      const double h = std::max(A.h, B.h);
      const double d = segment_distance(A, B);
      if (d >= ratio * h) continue;
      if (connected(A, B, path_factor * h)) continue;
      ++out.pairs;
      if (d / h < worst) worst = d / h, out.seg_a = i, out.seg_b = j, out.gap_nm = d, out.h_nm = h;
    }
  }
  return out;
}

}  // namespace plumage::bem
