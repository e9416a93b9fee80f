// Hemisphere panels of a feather BSDF and their figure (brdf_report.hpp).
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "plumage/atomic_file.hpp"
#include "plumage/brdf_report.hpp"
#include "plumage/charts.hpp"
#include "plumage/conventions.hpp"
#include "plumage/error.hpp"
#include "plumage/image.hpp"

namespace plumage {

namespace fs = std::filesystem;

namespace {

// XYZ weights for the material's bins (spec §4.12 box bins when the bins are contiguous).
SpectralToXyz bin_weights(const FeatherMaterial& m) {
  bool contiguous = true;
  for (std::size_t w = 1; w < m.lambda_nm.size(); ++w) {
    contiguous = contiguous && std::abs(m.lambda_nm[w] - m.lambda_nm[w - 1] - m.bin_width_nm) < 1e-9;
  }
  if (contiguous) return SpectralToXyz::bins(m.lambda_nm.front(), m.bin_width_nm, m.lambda_nm.size());
  std::vector<double> centres;
  for (double l : m.lambda_nm) centres.push_back(l + 0.5 * m.bin_width_nm);
  return SpectralToXyz(centres);
}

// One panel: XYZ per pixel (NaN outside the disk). instance < 0: the mean BRDF.
std::vector<Xyz> render_panel(const FeatherBsdf& bsdf, const SpectralToXyz& to_xyz, const Direction& wi,
                              long instance, int size) {
  const FeatherMaterial& m = bsdf.material();
  const std::size_t bins = m.lambda_nm.size();
  std::vector<FeatherBsdf::Incident> incidents;
  for (std::size_t w = 0; w < bins; ++w) incidents.push_back(bsdf.incident_bin(w, wi));
  std::vector<Xyz> out(static_cast<std::size_t>(size) * size, Xyz{NAN, NAN, NAN});
  tbb::parallel_for(0, size, [&](int py) {
    std::vector<double> spectrum(bins);
    for (int px = 0; px < size; ++px) {
      const double x = 2.0 * (px + 0.5) / size - 1.0, y = 1.0 - 2.0 * (py + 0.5) / size;
      const double r2 = x * x + y * y;
      if (r2 >= 1.0) continue;
      const Direction wo{x, y, std::sqrt(1.0 - r2)};
      for (std::size_t w = 0; w < bins; ++w) {
        const double f = instance < 0 ? bsdf.eval(incidents[w], wo)
                                      : bsdf.eval(incidents[w], wo, static_cast<std::uint64_t>(instance));
        spectrum[w] = f * wo.z;  // L = f cos θ_o (spec §3)
      }
      out[static_cast<std::size_t>(py) * size + px] = to_xyz.apply(spectrum);
    }
  });
  return out;
}

}  // namespace

void check_hemisphere_plot_options(const HemispherePlotOptions& o) {
  auto refuse = [](const char* flag, const std::string& message) { throw ConfigError(SourceMark{flag, 0, 0}, "", message); };
  if (o.incidents.empty()) refuse("--incident", "no directions given");
  for (const IncidentAngles& v : o.incidents) {
    if (!(std::abs(v.theta_deg) < 90.0 && std::abs(v.phi_deg) < 90.0))
      refuse("--incident", "theta and phi must lie in (-90, 90) degrees (" + std::to_string(v.theta_deg) + ", " +
                               std::to_string(v.phi_deg) + " given)");
  }
  if (o.instances < 0 || o.instances > 16) refuse("--instances", "must be in 0..16");
  if (o.size < 16 || o.size > 2048) refuse("--size", "must be in 16..2048");
  if (!(o.exposure >= 0.0)) refuse("--exposure", "must be > 0 (or 0 for automatic)");
}

HemispherePanels hemisphere_panels(std::shared_ptr<const FeatherMaterial> material, const HemispherePlotOptions& o) {
  FeatherBsdfOptions options;
  options.transmission_albedo = 0.0;  // reflection only
  const FeatherBsdf bsdf(material, options);
  const SpectralToXyz to_xyz = bin_weights(*material);
  HemispherePanels p;
  p.size = o.size;
  p.rows = static_cast<int>(o.incidents.size());
  p.columns = 1 + o.instances;
  std::vector<double> mean_y;
  for (const IncidentAngles& inc : o.incidents) {
    const Direction wi = direction_from_angles(deg_to_rad(inc.theta_deg), deg_to_rad(inc.phi_deg));
    for (int c = 0; c < p.columns; ++c) {
      p.xyz.push_back(render_panel(bsdf, to_xyz, wi, c - 1, o.size));
      if (c == 0) {
        for (const Xyz& v : p.xyz.back()) if (std::isfinite(v.y) && v.y > 0.0) mean_y.push_back(v.y);
      }
    }
  }
  p.exposure = o.exposure;
  p.automatic_exposure = !(o.exposure > 0.0);
  if (p.automatic_exposure) {
    std::sort(mean_y.begin(), mean_y.end());
    const double q = mean_y.empty() ? 0.0 : mean_y[static_cast<std::size_t>(0.995 * (mean_y.size() - 1))];
    p.exposure = q > 0.0 ? 1.0 / q : 1.0;
  }
  return p;
}

void write_hemisphere_figure(const HemispherePanels& p, const HemispherePlotOptions& o, const FeatherMaterial& material,
                             const fs::path& png) {
  check_output_path(png);
  const fs::path dir = fs::path(png).concat(".panels.tmp");
  create_output_directory(dir);
  std::ofstream manifest(dir / "manifest.csv");
  manifest << "row,col,title,file\n";
  const Rgb8 background{48, 48, 48};
  const double e = p.exposure;
  for (int r = 0; r < p.rows; ++r) {
    for (int c = 0; c < p.columns; ++c) {
      const std::vector<Xyz>& xyz = p.xyz[static_cast<std::size_t>(r * p.columns + c)];
      Image img(p.size, p.size, background);
      for (int py = 0; py < p.size; ++py) {
        for (int px = 0; px < p.size; ++px) {
          const Xyz v = xyz[static_cast<std::size_t>(py) * p.size + px];
          if (!std::isfinite(v.y)) continue;
          img.at(px, py) = to_srgb8(Xyz{v.x * e, v.y * e, v.z * e});
        }
      }
      const std::string name = "panel_" + std::to_string(r) + "_" + std::to_string(c) + ".png";
      write_png(img, dir / name);
      std::ostringstream title;
      title << (c == 0 ? std::string("mean") : "instance " + std::to_string(c - 1)) << "  (θi, φi) = ("
            << o.incidents[static_cast<std::size_t>(r)].theta_deg << "°, " << o.incidents[static_cast<std::size_t>(r)].phi_deg
            << "°)";
      manifest << r << ',' << c << ",\"" << title.str() << "\"," << name << '\n';
    }
  }
  manifest.close();
  std::ostringstream title;
  title << material.label << " (" << material.fidelity << "): f·cos θo over (ωo,x, ωo,y), D65, exposure ×" << e
        << (p.automatic_exposure ? " (auto: 99.5th percentile of the mean panels → 1)" : "");
  std::error_code ec;
  try {
    draw_script_chart("plot_hemisphere.py", {(dir / "manifest.csv").string()}, png, title.str());
  } catch (...) {
    fs::remove_all(dir, ec);
    throw;
  }
  fs::remove_all(dir, ec);
}

}  // namespace plumage
