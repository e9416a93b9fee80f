// BEM mesh of a cross section (spec wave-simulation.md §6.3, §6.4, §6.6).
//
// Domains: 0 = exterior air, r + 1 = CrossSection.regions[r]. Every boundary piece between two
// different domains is an interface; it is cut into straight segments of length ≤ h_max (the
// smaller λ/(|n|·ppw) of its two sides). A segment is oriented so that its normal
// n̂ = ŷ × t̂ = (t_z, 0, −t_x) points into domain a = min(domain ids) (for the outer boundary:
// into the air), b is the other side.
//
// Degrees of freedom per spec §6.4/§6.6, in units where J̃ = η0 J:
//   J̃_t = η0 H_y and M_t = −E_y: one tent coefficient per mesh vertex, shared by all segments that
//       meet there (junction tents at points where three or more domains meet, §6.6);
//   J̃_z = −η0 H·t̂ and M_z = E·t̂: one coefficient per (vertex, interface); at a junction, and at
//       a corner sharper than corner_split_deg, every incident segment carries its own half tent.
// Unknown vector: [J̃_t (n_t) | J̃_z (n_z) | M_t (n_t) | M_z (n_z)].
#pragma once

#include <array>
#include <complex>
#include <string>
#include <vector>

#include "plumage/cross_section.hpp"

namespace plumage::bem {

// One straight piece of an interface before subdivision (geometry only, λ-independent).
struct InterfaceEdge {
  Vec2 p, q;       // oriented: n̂ = ŷ × (q − p)/|q − p| points into domain a
  int a = 0, b = 0;  // a < b
};

struct Geometry {
  std::vector<InterfaceEdge> edges;
  std::vector<Material> domain_material;  // [0] = air
  std::vector<std::string> domain_name;   // for error messages
};

// Interfaces of a cross section. Throws plumage::Error naming the regions for overlapping or
// inconsistent outlines.
Geometry build_geometry(const CrossSection& section);

struct Segment {
  int v0 = 0, v1 = 0;  // vertex indices (t̂ from v0 to v1)
  int a = 0, b = 0;
  Vec2 p0, p1;
  double h = 0.0;
  Vec2 t, n;              // unit tangent, unit normal n = (t_z, −t_x)
  std::array<int, 2> zdof{};  // J̃_z / M_z coefficient index at v0, v1
};

struct Mesh {
  std::vector<Vec2> vertices;
  std::vector<Segment> segments;
  int n_t = 0;  // = vertices.size()
  int n_z = 0;
  std::vector<int> z_vertex;  // vertex of each z coefficient
  int a_count = 0;  // number of domains
  std::vector<std::vector<int>> domain_segments;  // segments on each domain's boundary
  int unknowns() const { return 2 * (n_t + n_z); }
  int jt(int v) const { return v; }
  int jz(int z) const { return n_t + z; }
  int mt(int v) const { return n_t + n_z + v; }
  int mz(int z) const { return 2 * n_t + n_z + z; }
};

// Segments of length ≤ λ/(|n_side|·ppw) for both sides (at least one per edge). The axial
// coefficients (J̃_z = −η0 H·t̂, M_z = E·t̂) are shared through a vertex of one interface only
// where its tangent turns by less than `corner_split_deg`; at sharper corners each segment gets
// its own half tent, as at junctions: H·t̂ and E·t̂ are different components of the field on the
// two sides of a corner, and forcing them equal gave mesh-dependent error spikes of 1e-2 on
// blocks (NOTES.md §6.2).
Mesh build_mesh(const Geometry& geometry, double lambda_nm, double points_per_wavelength,
                double corner_split_deg = 30.0);

// Resolution of a mesh at λ (issue 9, warning bem.mesh_coarse): the points per wavelength each
// segment actually has, λ/(|n|·h) with the larger |n| of its two sides — edges shorter than the
// requested h are kept as they are, so this can exceed the requested ppw but never falls below it.
struct MeshResolution {
  double min_ppw = 0.0;         // of the coarsest segment
  int domain = 0;               // its denser side
  double h_nm = 0.0;            // its length
  double length_fraction = 0.0; // share of the total interface length with ppw < `threshold`
};
MeshResolution mesh_resolution(const Mesh& mesh, const Geometry& geometry, double lambda_nm, double threshold);

// Closest approach of two boundary pieces that are not neighbours along the mesh (issue 9,
// warning bem.near_touching): segments sharing no vertex, with no path along the mesh between
// them shorter than `path_factor` × their longer length (so a chain of short segments or a
// junction does not count), and whose distance is below `ratio` × their longer length. Returns
// the pair with the smallest distance/length among those.
struct CloseApproach {
  int pairs = 0;               // pairs below the ratio
  int seg_a = -1, seg_b = -1;  // the worst one (smallest gap / h)
  double gap_nm = 0.0, h_nm = 0.0;
};
CloseApproach closest_approach(const Mesh& mesh, double ratio, double path_factor = 3.0);

}  // namespace plumage::bem
