// Table assembly (spec §4.7 steps 1–2): reference correlation length, grazing extrapolation of
// row i = 0 (cos θ_i = 0) and column j = 0 (cos φ_i = 0), Gaussian smoothing of m and l.
// Step 3 (bicubic Hermite patches) is FeatherMaterial::lookup. Afterwards the F's of the fitted
// nodes are renormalised to the smoothed m (fitter.hpp, assemble_tables).
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "plumage/error.hpp"
#include "plumage/fitter.hpp"

namespace plumage {

namespace {

using Field = double MaterialNode::*;

// Column j = 0 linear from j = 1, 2 (rows i ≥ 1).
void column_linear(FeatherMaterial& m, std::size_t w, Field f, bool clamp01) {
  for (int i = 1; i <= m.grid; ++i) {
    double v = 2.0 * (m.node(w, i, 1).*f) - (m.grid >= 2 ? m.node(w, i, 2).*f : m.node(w, i, 1).*f);
    if (clamp01) v = std::clamp(v, 0.0, 1.0);
    m.node(w, i, 0).*f = v;
  }
}

// Row i = 0 constant: 2·mean(row 1) − mean(row 2), means over all G + 1 columns.
void row_constant(FeatherMaterial& m, std::size_t w, Field f) {
  double r1 = 0, r2 = 0;
  const int i2 = m.grid >= 2 ? 2 : 1;
  for (int j = 0; j <= m.grid; ++j) r1 += m.node(w, 1, j).*f, r2 += m.node(w, i2, j).*f;
  const double v = (2.0 * r1 - r2) / (m.grid + 1);
  for (int j = 0; j <= m.grid; ++j) m.node(w, 0, j).*f = v;
}

// Row i = 0 linear from rows 1, 2, corner included.
void row_linear(FeatherMaterial& m, std::size_t w, Field f) {
  const int i2 = m.grid >= 2 ? 2 : 1;
  for (int j = 0; j <= m.grid; ++j) m.node(w, 0, j).*f = 2.0 * (m.node(w, 1, j).*f) - (m.node(w, i2, j).*f);
}

// Each node becomes the normalised average with weights exp(−Δi²) exp(−Δj²), skipping nodes
// with both |Δi| ≥ 3 and |Δj| ≥ 3 (spec §4.7).
void smooth(FeatherMaterial& m, std::size_t w, Field f) {
  const int n = m.grid + 1;
  std::vector<double> src(static_cast<std::size_t>(n * n));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) src[static_cast<std::size_t>(i * n + j)] = m.node(w, i, j).*f;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      double s = 0, ws = 0;
      for (int a = 0; a < n; ++a) {
        for (int b = 0; b < n; ++b) {
          const int di = std::abs(a - i), dj = std::abs(b - j);
          if (di >= 3 && dj >= 3) continue;
          const double wt = std::exp(-double(di * di)) * std::exp(-double(dj * dj));
          s += wt * src[static_cast<std::size_t>(a * n + b)];
          ws += wt;
        }
      }
      m.node(w, i, j).*f = s / ws;
    }
  }
}

// Paper Eq. 12 makes the fitted lobe's directional albedo ∫ L dω equal the simulated reflected
// energy E; F_eff was normalised with the *fitted* m_eff, and smoothing then changes m_eff. At
// grazing incidence the integral is very sensitive to m (the horizon cuts the lobe and G1
// falls), so the smoothed table's albedo drifted from E (up to A_r = 1.17 > 1 measured on the
// rock-dove preview). Restore ∫ L dω = E at every fitted node with the smoothed m: F_eff scales by
// I(fitted m)/I(smoothed m), both by the accurate hemisphere integral (the rule of the fitter's
// normalisation, so the restored albedo is E to rounding). F_sta follows from its definition
// (spec §4.4): F_sta ∝ F_eff · Σ_cone L_eff / Σ_cone L_sta with the stored lobes.
void renormalise_scales(FeatherMaterial& m, std::size_t w, const std::vector<MaterialNode>& fitted) {
  const int n = m.grid + 1;
  for (int i = 1; i <= m.grid; ++i) {
    const double theta = std::acos(static_cast<double>(i) / m.grid);
    for (int j = 1; j <= m.grid; ++j) {
      const MaterialNode& raw = fitted[static_cast<std::size_t>(i * n + j)];
      MaterialNode& out = m.node(w, i, j);
      if (out.m_eff != raw.m_eff && raw.f_eff > 0.0) {
        const double before = hemisphere_lobe_integral(Lobe{raw.m_eff, raw.phi_eff, m.sigma, 1.0}, theta);
        const double after = hemisphere_lobe_integral(Lobe{out.m_eff, out.phi_eff, m.sigma, 1.0}, theta);
        if (before > 0.0 && after > 0.0) out.f_eff = raw.f_eff * (before / after);
      }
      if ((out.m_eff != raw.m_eff || out.m_sta != raw.m_sta) && raw.f_sta > 0.0 && raw.f_eff > 0.0) {
        const double eff_before = cone_lobe_sum(Lobe{raw.m_eff, raw.phi_eff, m.sigma, 1.0}, theta);
        const double eff_after = cone_lobe_sum(Lobe{out.m_eff, out.phi_eff, m.sigma, 1.0}, theta);
        const double sta_before = cone_lobe_sum(Lobe{raw.m_sta, raw.phi_sta, m.sigma, 1.0}, theta);
        const double sta_after = cone_lobe_sum(Lobe{out.m_sta, out.phi_sta, m.sigma, 1.0}, theta);
        if (eff_before > 0.0 && sta_after > 0.0)
          out.f_sta = raw.f_sta * (out.f_eff / raw.f_eff) * (eff_after / eff_before) * (sta_before / sta_after);
      }
    }
  }
}

}  // namespace

void assemble_tables(FeatherMaterial& m) {
  if (m.grid < 1 || m.nodes.size() != m.lambda_nm.size() * static_cast<std::size_t>((m.grid + 1) * (m.grid + 1)))
    throw Error("assemble_tables: node count does not match the grid");
  // Step 1: l0 from the first bin at normal incidence.
  m.l0 = m.node(0, m.grid, m.grid).correlation;
  if (!(m.l0 > 0)) throw Error("assemble_tables: the reference correlation length (first bin, normal incidence) is not positive");
  // Bins are independent: one task each (same result on any number of threads).
  tbb::parallel_for(std::size_t{0}, m.lambda_nm.size(), [&m](std::size_t w) {
    const int n = m.grid + 1;
    std::vector<MaterialNode> fitted(static_cast<std::size_t>(n * n));
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) fitted[static_cast<std::size_t>(i * n + j)] = m.node(w, i, j);
    for (int i = 1; i <= m.grid; ++i)
      for (int j = 1; j <= m.grid; ++j) m.node(w, i, j).correlation /= m.l0;
    // Step 2: extrapolation (columns first, then the grazing row over all columns).
    for (Field f : {&MaterialNode::m_eff, &MaterialNode::m_sta}) {
      column_linear(m, w, f, true);
      row_constant(m, w, f);
    }
    column_linear(m, w, &MaterialNode::correlation, false);
    row_constant(m, w, &MaterialNode::correlation);
    column_linear(m, w, &MaterialNode::pol_share, false);
    row_linear(m, w, &MaterialNode::pol_share);
    for (int i = 0; i <= m.grid; ++i) {
      m.node(w, i, 0).phi_eff = m.node(w, i, 0).phi_sta = 0.5 * kPi;
      m.node(w, i, 0).f_eff = m.node(w, i, 0).f_sta = 0.0;
    }
    for (int j = 0; j <= m.grid; ++j) {
      m.node(w, 0, j).phi_eff = m.node(w, 0, j).phi_sta = std::acos(static_cast<double>(j) / m.grid);
      m.node(w, 0, j).f_eff = m.node(w, 0, j).f_sta = 0.0;
    }
    for (Field f : {&MaterialNode::m_eff, &MaterialNode::m_sta, &MaterialNode::correlation}) smooth(m, w, f);
    renormalise_scales(m, w, fitted);
  });
}

}  // namespace plumage
