// The white furnace of a feather BSDF at every table entry (brdf_report.hpp).
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "plumage/brdf_report.hpp"
#include "plumage/fitter.hpp"

namespace plumage {

FurnaceReport white_furnace(std::shared_ptr<const FeatherMaterial> material, double transmission) {
  FeatherBsdfOptions options;
  options.transmission_albedo = transmission;
  const FeatherBsdf bsdf(material, options);
  const int g = material->grid;
  const std::size_t bins = material->lambda_nm.size();
  FurnaceReport report;
  report.bins.resize(bins);
  tbb::parallel_for(std::size_t{0}, bins, [&](std::size_t w) {
    FurnaceBin& r = report.bins[w];
    r.lambda_nm = material->lambda_nm[w];
    r.transmission = bsdf.transmission_albedo(w);
    auto visit = [&](double ct, double cp, bool node) {
      const Direction wi{ct * std::sqrt(1.0 - cp * cp), std::sqrt(1.0 - ct * ct), ct * cp};
      const FeatherBsdf::Incident in = bsdf.incident_bin(w, wi);
      const double a = in.reflects ? hemisphere_lobe_integral(in.mean, in.theta_abs) : 0.0;
      r.worst_total = std::max(r.worst_total, a + in.transmission);
      if (in.reflects && in.energy_scale < 1.0) ++(node ? r.clamped_nodes : r.clamped_centres);
      if (node && in.energy_scale > 0.0) {
        r.material_raw = std::max(r.material_raw, a / in.energy_scale);
        r.raw_over_one += a / in.energy_scale > 1.0;
      }
    };
    for (int i = 1; i <= g; ++i)
      for (int j = 1; j <= g; ++j) visit(static_cast<double>(i) / g, static_cast<double>(j) / g, true);
    for (int i = 0; i < g; ++i)
      for (int j = 0; j < g; ++j) visit((i + 0.5) / g, (j + 0.5) / g, false);
  });
  report.nodes_per_bin = static_cast<std::size_t>(g) * static_cast<std::size_t>(g);
  report.entries = bins * 2 * report.nodes_per_bin;
  for (const FurnaceBin& b : report.bins) {
    report.worst_total = std::max(report.worst_total, b.worst_total);
    report.worst_raw = std::max(report.worst_raw, b.material_raw);
    report.raw_over_one += b.raw_over_one;
    report.clamped_nodes += b.clamped_nodes;
    report.clamped_centres += b.clamped_centres;
  }
  return report;
}

}  // namespace plumage
