// Statistics of a set of barbule instances (`plumage geometry --stats`).
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "plumage/geometry.hpp"
#include "plumage/instance_geometry.hpp"

namespace plumage {

namespace {

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

std::string range(const std::vector<double>& v) {
  if (v.empty()) return "-";
  std::ostringstream o;
  o << std::setprecision(4) << *std::min_element(v.begin(), v.end()) << " .. " << *std::max_element(v.begin(), v.end())
    << " (mean " << mean(v) << ")";
  return o.str();
}

}  // namespace

void GeometryStatistics::add(const CrossSection& cs) {
  width_um_.push_back(cs.width_nm() / 1000.0);
  // Thickness at the centre: top minus bottom at x = 0.
  thickness_um_.push_back((z_at(cs.top, 0.0) - z_at(cs.bottom, 0.0)) / 1000.0);
  if (!cs.top_roughness_nm.empty()) {
    const auto [lo, hi] = std::minmax_element(cs.top_roughness_nm.begin(), cs.top_roughness_nm.end());
    rough_lo_.push_back(*lo);
    rough_hi_.push_back(*hi);
    std::vector<double> xs(cs.top.size());
    for (std::size_t i = 0; i < xs.size(); ++i) xs[i] = cs.top[i].x;
    double step = 0.0;
    const auto c = circular_autocovariance(xs, cs.top_roughness_nm, 2048, 1024, step);
    corr_um_.push_back(gaussian_correlation_length(c, step) / 1000.0);
  }
  if (cs.crystal && !cs.crystal->regularity.empty()) {
    const auto [lo, hi] = std::minmax_element(cs.crystal->regularity.begin(), cs.crystal->regularity.end());
    regularity_lo_.push_back(*lo);
    regularity_hi_.push_back(*hi);
  }
  for (const Disc& d : cs.melanosomes) diameters_.push_back(d.diameter_nm);
  for (const Region& r : cs.regions) roles_[std::string(role_name(r.role))] += r.members;
  if (cs.layered) {
    const double quarter = 0.25 * cs.width_nm();
    for (std::size_t i = 0; i < cs.top.size(); ++i) {
      if (std::abs(cs.top[i].x) > quarter) continue;
      const LayerProfile p = layer_profile_at(cs, i);
      for (std::size_t j = 0; j < p.layers.size(); ++j) {
        if (j >= layers_.size()) layers_.push_back({p.layers[j].material.name(), {}});
        layers_[j].second.push_back(p.layers[j].thickness_nm);
      }
    }
  }
}

std::string GeometryStatistics::report(const std::string& label, int instances) const {
  std::ostringstream out;
  out << "statistics of " << instances << " instance(s) of " << label << "\n";
  out << "  width (um)                    " << range(width_um_) << "\n";
  out << "  thickness at x = 0 (um)       " << range(thickness_um_) << "\n";
  if (!rough_lo_.empty()) {
    out << "  top roughness min (nm)        " << range(rough_lo_) << "\n";
    out << "  top roughness max (nm)        " << range(rough_hi_) << "\n";
    out << "  correlation length tau (um)   " << range(corr_um_) << "   [C(dx) ~ exp(-dx^2/(2 tau^2))]\n";
  }
  if (!regularity_lo_.empty()) {
    out << "  regularity min                " << range(regularity_lo_) << "\n";
    out << "  regularity max                " << range(regularity_hi_) << "\n";
  }
  if (!diameters_.empty()) {
    out << "  melanosome diameter (nm)      " << range(diameters_) << ", " << diameters_.size() << " melanosomes\n";
  }
  out << "  bodies by role               ";
  for (const auto& [role, count] : roles_) out << " " << role << " " << count;
  out << "\n";
  if (!layers_.empty()) {
    out << "  mean local stack under the central half (layer: material, thickness nm, share of normals)\n";
    const std::size_t total = layers_.front().second.size();
    for (std::size_t j = 0; j < layers_.size() && j < 14; ++j) {
      out << "    " << std::setw(2) << j + 1 << ": " << std::setw(28) << std::left << layers_[j].first << std::right
          << std::setw(9) << std::fixed << std::setprecision(1) << mean(layers_[j].second) << "  "
          << std::setprecision(2)
          << static_cast<double>(layers_[j].second.size()) / static_cast<double>(std::max<std::size_t>(1, total))
          << std::defaultfloat << std::setprecision(6) << "\n";
    }
    if (layers_.size() > 14) out << "    ... " << layers_.size() << " layers at most\n";
  }
  return out.str();
}

}  // namespace plumage
