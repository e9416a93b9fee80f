// FeatherMaterial lookups: wavelength bins and bicubic Hermite interpolation over the incident
// grid (spec geometry-and-brdf §4.7 step 3, §4.9 step 2); MaterialLookupTable, the same patches
// with the per-node data precomputed.
#include <algorithm>
#include <cmath>

#include "plumage/conventions.hpp"
#include "plumage/error.hpp"
#include "plumage/feather_material.hpp"

namespace plumage {

namespace {

// Cubic Hermite basis on [0, 1]: value at 0, value at 1, slope at 0, slope at 1.
std::array<double, 4> hermite(double t) {
  const double t2 = t * t, t3 = t2 * t;
  return {2 * t3 - 3 * t2 + 1, -2 * t3 + 3 * t2, t3 - 2 * t2 + t, t3 - t2};
}

// φ_eff and φ_sta follow the nominal azimuth φ_i = acos(cos φ_i) closely (exactly at grazing,
// spec §4.2), whose slope is infinite at cos φ_i = 1: interpolating them directly misses it by
// up to 4°. Their offsets from the node's φ_i are smooth; both lookups interpolate those and add
// φ_i back.
bool is_phi(double MaterialNode::*field) { return field == &MaterialNode::phi_eff || field == &MaterialNode::phi_sta; }

// F's divided back by cos θ_i cos φ_i, and the parameter ranges (feather_material.hpp, lookup()).
void finish(MaterialNode& out, double ct, double cp) {
  const double w_in = ct * cp;
  out.f_eff = w_in > 0.0 ? std::max(out.f_eff, 0.0) / w_in : 0.0;
  out.f_sta = w_in > 0.0 ? std::max(out.f_sta, 0.0) / w_in : 0.0;
  out.m_eff = std::clamp(out.m_eff, 0.001, 1.0);
  out.m_sta = std::clamp(out.m_sta, 0.001, 1.0);
  out.phi_eff = std::clamp(out.phi_eff, -0.5 * kPi, 0.5 * kPi);
  out.phi_sta = std::clamp(out.phi_sta, -0.5 * kPi, 0.5 * kPi);
  out.pol_share = std::clamp(out.pol_share, 0.0, 1.0);
  out.correlation = std::max(out.correlation, 0.0);
}

}  // namespace

std::size_t FeatherMaterial::wavelength_bin(double lambda) const {
  if (lambda_nm.empty()) throw Error("feather material " + label + ": no wavelength bins");
  const double t = std::floor((lambda - lambda_nm.front()) / bin_width_nm);
  return static_cast<std::size_t>(std::clamp(t, 0.0, static_cast<double>(lambda_nm.size() - 1)));
}

MaterialNode FeatherMaterial::lookup(std::size_t w, double cos_theta_i, double cos_phi_i) const {
  const double ct = std::clamp(cos_theta_i, 0.0, 1.0), cp = std::clamp(cos_phi_i, 0.0, 1.0);
  const int i = std::min(static_cast<int>(std::floor(grid * ct)), grid - 1);
  const int j = std::min(static_cast<int>(std::floor(grid * cp)), grid - 1);
  const auto hu = hermite(grid * ct - i), hv = hermite(grid * cp - j);
  // φ fields through their offsets from the nominal φ_i (is_phi above).
  auto q = [&](int a, int b, double MaterialNode::*field) {
    const double v = node(w, a, b).*field;
    return is_phi(field) ? v - std::acos(static_cast<double>(b) / grid) : v;
  };
  // Finite-difference derivatives in index units (central inside, one-sided at the borders).
  auto span = [&](int k) { return std::pair{std::max(k - 1, 0), std::min(k + 1, grid)}; };
  MaterialNode out;
  for (const auto field : kMaterialFields) {
    double value = 0.0;
    for (int a = 0; a < 2; ++a) {
      for (int b = 0; b < 2; ++b) {
        const int ni = i + a, nj = j + b;
        const auto [i0, i1] = span(ni);
        const auto [j0, j1] = span(nj);
        const double f = q(ni, nj, field);
        const double fu = (q(i1, nj, field) - q(i0, nj, field)) / (i1 - i0);
        const double fv = (q(ni, j1, field) - q(ni, j0, field)) / (j1 - j0);
        const double fuv = (q(i1, j1, field) + q(i0, j0, field) - q(i0, j1, field) - q(i1, j0, field)) /
                           ((i1 - i0) * (j1 - j0));
        value += hu[a] * hv[b] * f + hu[2 + a] * hv[b] * fu + hu[a] * hv[2 + b] * fv +
                 hu[2 + a] * hv[2 + b] * fuv;
      }
    }
    out.*field = is_phi(field) ? value + std::acos(cp) : value;
  }
  finish(out, ct, cp);
  return out;
}

MaterialLookupTable::MaterialLookupTable(const FeatherMaterial& m) : grid_(m.grid) {
  const int grid = m.grid;
  const std::size_t per_bin = static_cast<std::size_t>(grid + 1) * static_cast<std::size_t>(grid + 1);
  if (grid < 1 || m.nodes.size() != m.lambda_nm.size() * per_bin) {
    throw Error("feather material " + m.label + ": inconsistent node tables");
  }
  data_.assign(m.nodes.size() * kPerNode, 0.0);
  // The expressions of FeatherMaterial::lookup, evaluated once per node (the slopes at a node do
  // not depend on the cell they are used in).
  auto span = [&](int k) { return std::pair{std::max(k - 1, 0), std::min(k + 1, grid)}; };
  for (std::size_t w = 0; w < m.lambda_nm.size(); ++w) {
    for (int ni = 0; ni <= grid; ++ni) {
      for (int nj = 0; nj <= grid; ++nj) {
        double* out = data_.data() + m.node_index(w, ni, nj) * kPerNode;
        const auto [i0, i1] = span(ni);
        const auto [j0, j1] = span(nj);
        for (int k = 0; k < kMaterialParameters; ++k) {
          const auto field = kMaterialFields[static_cast<std::size_t>(k)];
          auto q = [&](int a, int b) {
            const double v = m.node(w, a, b).*field;
            return is_phi(field) ? v - std::acos(static_cast<double>(b) / grid) : v;
          };
          out[4 * k + 0] = q(ni, nj);
          out[4 * k + 1] = (q(i1, nj) - q(i0, nj)) / (i1 - i0);
          out[4 * k + 2] = (q(ni, j1) - q(ni, j0)) / (j1 - j0);
          out[4 * k + 3] = (q(i1, j1) + q(i0, j0) - q(i0, j1) - q(i1, j0)) / ((i1 - i0) * (j1 - j0));
        }
      }
    }
  }
}

MaterialLookupTable::Point MaterialLookupTable::locate(double cos_theta_i, double cos_phi_i) const {
  const int grid = grid_;
  Point p;
  p.ct = std::clamp(cos_theta_i, 0.0, 1.0);
  p.cp = std::clamp(cos_phi_i, 0.0, 1.0);
  p.i = std::min(static_cast<int>(std::floor(grid * p.ct)), grid - 1);
  p.j = std::min(static_cast<int>(std::floor(grid * p.cp)), grid - 1);
  p.hu = hermite(grid * p.ct - p.i);
  p.hv = hermite(grid * p.cp - p.j);
  p.phi_nominal = std::acos(p.cp);
  return p;
}

MaterialNode MaterialLookupTable::lookup(std::size_t w, double cos_theta_i, double cos_phi_i) const {
  return lookup(w, locate(cos_theta_i, cos_phi_i));
}

MaterialNode MaterialLookupTable::lookup(std::size_t w, const Point& p) const {
  const int i = p.i, j = p.j;
  const auto& hu = p.hu;
  const auto& hv = p.hv;
  const double* corner[2][2] = {{node_data(w, i, j), node_data(w, i, j + 1)},
                                {node_data(w, i + 1, j), node_data(w, i + 1, j + 1)}};
  MaterialNode out;
  for (int k = 0; k < kMaterialParameters; ++k) {
    double value = 0.0;
    for (int a = 0; a < 2; ++a) {
      for (int b = 0; b < 2; ++b) {
        const double* d = corner[a][b] + 4 * k;
        value += hu[a] * hv[b] * d[0] + hu[2 + a] * hv[b] * d[1] + hu[a] * hv[2 + b] * d[2] +
                 hu[2 + a] * hv[2 + b] * d[3];
      }
    }
    const auto field = kMaterialFields[static_cast<std::size_t>(k)];
    out.*field = is_phi(field) ? value + p.phi_nominal : value;
  }
  finish(out, p.ct, p.cp);
  return out;
}

double FeatherMaterial::min_correlation_length() const {
  double l = 1e300;
  for (std::size_t w = 0; w < lambda_nm.size(); ++w) l = std::min(l, node(w, grid, grid).correlation * l0);
  return lambda_nm.empty() ? 0.0 : l;
}

}  // namespace plumage
