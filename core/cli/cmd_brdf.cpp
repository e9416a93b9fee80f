// `plumage brdf plot FILE.plm --incident "0,0 0,-45 45,0" --out fig.png [--instances K]
//  [--size N] [--exposure E]`: projected-hemisphere plots of a feather material (paper Fig. 10):
// for each incident (θ_i, φ_i) in degrees, the mean BRDF f̄ and K instances f_k (paper Eqs. 16,
// 22) over the unit disk of (ω_o,x, ω_o,y), as sRGB colour.
//
// Pixel value: the spectrum f·cos θ_o over the material's wavelength bins (the lobe L of spec §3:
// reflected power per unit projected solid angle, so the disk integral of a panel is the
// directional albedo) → XYZ as a reflectance under D65, bin i constant on [λ_i, λ_i + width]
// (spec §4.12) → linear sRGB × exposure → clip → sRGB transfer. The exposure (stated in the
// picture's title) maps the 99.5th percentile of the mean panels' luminance to 1 unless given.
//
// `plumage brdf check FILE.plm [--transmission T]`: white furnace of the BSDF built from the
// material, at every table entry (nodes with cos θ_i, cos φ_i > 0) and cell centre of every bin:
// A_r (the fitter's accurate hemisphere integral of the lobe the BSDF evaluates) + T ≤ 1. Also
// reports the material's own albedo at the nodes before the BSDF's clamp, and how often that clamp
// (the safety net between nodes) acts at the nodes and cell centres. Exit 1 on a violation.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include <tbb/parallel_for.h>

#include "plumage/charts.hpp"
#include "commands.hpp"
#include "plumage/colour.hpp"
#include "plumage/error.hpp"
#include "plumage/feather_bsdf.hpp"
#include "plumage/feather_material.hpp"
#include "plumage/fitter.hpp"
#include "plumage/image.hpp"

namespace plumage::cli {

namespace {

namespace fs = std::filesystem;

struct PlotOptions {
  std::string file;
  std::string incident = "0,0 0,-45 45,0";
  std::string out;
  int instances = 2;
  int size = 192;
  double exposure = 0.0;  // 0: automatic
};

struct Incidence {
  double theta_deg, phi_deg;
};

std::vector<Incidence> parse_incidents(const std::string& text) {
  std::vector<Incidence> out;
  std::istringstream in(text);
  std::string item;
  while (in >> item) {
    const auto comma = item.find(',');
    Incidence v{};
    try {
      if (comma == std::string::npos) throw std::invalid_argument("no comma");
      std::size_t used = 0;
      v.theta_deg = std::stod(item.substr(0, comma), &used);
      if (used != comma) throw std::invalid_argument("theta");
      const std::string rest = item.substr(comma + 1);
      v.phi_deg = std::stod(rest, &used);
      if (used != rest.size()) throw std::invalid_argument("phi");
    } catch (const std::exception&) {
      throw UsageError("--incident: '" + item + "' is not theta,phi in degrees (e.g. \"0,0 0,-45 45,0\")");
    }
    if (!(std::abs(v.theta_deg) < 90.0 && std::abs(v.phi_deg) < 90.0)) {
      throw UsageError("--incident: '" + item + "': theta and phi must lie in (-90, 90) degrees");
    }
    out.push_back(v);
  }
  if (out.empty()) throw UsageError("--incident: no directions given");
  return out;
}

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

void plot(const AppContext& context, const PlotOptions& o) {
  if (o.instances < 0 || o.instances > 16) throw UsageError("--instances must be in 0..16");
  if (o.size < 16 || o.size > 2048) throw UsageError("--size must be in 16..2048");
  if (o.exposure < 0.0) throw UsageError("--exposure must be > 0 (or 0 for automatic)");
  const std::vector<Incidence> incidents = parse_incidents(o.incident);
  auto material = std::make_shared<const FeatherMaterial>(read_feather_material(o.file));
  FeatherBsdfOptions options;
  options.transmission_albedo = 0.0;  // reflection only
  const FeatherBsdf bsdf(material, options);
  const SpectralToXyz to_xyz = bin_weights(*material);
  const int columns = 1 + o.instances;

  std::vector<std::vector<Xyz>> panels;
  std::vector<double> mean_y;
  for (const Incidence& inc : incidents) {
    const Direction wi = direction_from_angles(deg_to_rad(inc.theta_deg), deg_to_rad(inc.phi_deg));
    for (int c = 0; c < columns; ++c) {
      panels.push_back(render_panel(bsdf, to_xyz, wi, c - 1, o.size));
      if (c == 0) {
        for (const Xyz& v : panels.back()) if (std::isfinite(v.y) && v.y > 0.0) mean_y.push_back(v.y);
      }
    }
  }
  double exposure = o.exposure;
  if (!(exposure > 0.0)) {
    std::sort(mean_y.begin(), mean_y.end());
    const double p = mean_y.empty() ? 0.0 : mean_y[static_cast<std::size_t>(0.995 * (mean_y.size() - 1))];
    exposure = p > 0.0 ? 1.0 / p : 1.0;
  }

  const fs::path out(o.out);
  const fs::path dir = fs::path(o.out).concat(".panels.tmp");
  fs::create_directories(dir);
  std::ofstream manifest(dir / "manifest.csv");
  manifest << "row,col,title,file\n";
  const Rgb8 background{48, 48, 48};
  for (std::size_t r = 0; r < incidents.size(); ++r) {
    for (int c = 0; c < columns; ++c) {
      const std::vector<Xyz>& xyz = panels[r * columns + static_cast<std::size_t>(c)];
      Image img(o.size, o.size, background);
      for (int py = 0; py < o.size; ++py) {
        for (int px = 0; px < o.size; ++px) {
          const Xyz v = xyz[static_cast<std::size_t>(py) * o.size + px];
          if (!std::isfinite(v.y)) continue;
          img.at(px, py) = to_srgb8(Xyz{v.x * exposure, v.y * exposure, v.z * exposure});
        }
      }
      const std::string name = "panel_" + std::to_string(r) + "_" + std::to_string(c) + ".png";
      write_png(img, dir / name);
      std::ostringstream title;
      title << (c == 0 ? std::string("mean") : "instance " + std::to_string(c - 1)) << "  (θi, φi) = ("
            << incidents[r].theta_deg << "°, " << incidents[r].phi_deg << "°)";
      manifest << r << ',' << c << ",\"" << title.str() << "\"," << name << '\n';
    }
  }
  manifest.close();
  std::ostringstream title;
  title << material->label << " (" << material->fidelity << "): f·cos θo over (ωo,x, ωo,y), D65, exposure ×"
        << exposure << (o.exposure > 0.0 ? "" : " (auto: 99.5th percentile of the mean panels → 1)");
  try {
    draw_script_chart("plot_hemisphere.py", {(dir / "manifest.csv").string()}, out, title.str());
  } catch (...) {
    std::error_code ec;
    fs::remove_all(dir, ec);
    throw;
  }
  std::error_code ec;
  fs::remove_all(dir, ec);
  if (!context.quiet) std::fprintf(stderr, "wrote %s (exposure %g)\n", o.out.c_str(), exposure);
}

struct CheckOptions {
  std::string file;
  double transmission = FeatherBsdfOptions{}.transmission_albedo;
};

void check(const CheckOptions& o) {
  if (!(o.transmission >= 0.0 && o.transmission <= 1.0)) throw UsageError("--transmission must be in [0, 1]");
  auto material = std::make_shared<const FeatherMaterial>(read_feather_material(o.file));
  FeatherBsdfOptions options;
  options.transmission_albedo = o.transmission;
  const FeatherBsdf bsdf(material, options);
  const int g = material->grid;
  const std::size_t bins = material->lambda_nm.size();
  struct Worst {
    double total = 0.0, raw = 0.0;
    int over_raw = 0, clamped_nodes = 0, clamped_centres = 0;
  };
  std::vector<Worst> per_bin(bins);
  tbb::parallel_for(std::size_t{0}, bins, [&](std::size_t w) {
    Worst& r = per_bin[w];
    auto visit = [&](double ct, double cp, bool node) {
      const Direction wi{ct * std::sqrt(1.0 - cp * cp), std::sqrt(1.0 - ct * ct), ct * cp};
      const FeatherBsdf::Incident in = bsdf.incident_bin(w, wi);
      const double a = in.reflects ? hemisphere_lobe_integral(in.mean, in.theta_abs) : 0.0;
      r.total = std::max(r.total, a + in.transmission);
      if (in.reflects && in.energy_scale < 1.0) ++(node ? r.clamped_nodes : r.clamped_centres);
      if (node && in.energy_scale > 0.0) {
        r.raw = std::max(r.raw, a / in.energy_scale);
        r.over_raw += a / in.energy_scale > 1.0;
      }
    };
    for (int i = 1; i <= g; ++i)
      for (int j = 1; j <= g; ++j) visit(static_cast<double>(i) / g, static_cast<double>(j) / g, true);
    for (int i = 0; i < g; ++i)
      for (int j = 0; j < g; ++j) visit((i + 0.5) / g, (j + 0.5) / g, false);
  });
  double worst = 0.0, worst_raw = 0.0;
  int over = 0, clamped_nodes = 0, clamped_centres = 0;
  std::printf("bin  lambda_nm  T_w      max(A_r+T)  material max A_r (nodes)  nodes with A_r > 1\n");
  for (std::size_t w = 0; w < bins; ++w) {
    std::printf("%3zu  %9.1f  %.4f   %.5f     %.5f                   %d\n", w, material->lambda_nm[w],
                bsdf.transmission_albedo(w), per_bin[w].total, per_bin[w].raw, per_bin[w].over_raw);
    worst = std::max(worst, per_bin[w].total);
    worst_raw = std::max(worst_raw, per_bin[w].raw);
    over += per_bin[w].over_raw;
    clamped_nodes += per_bin[w].clamped_nodes;
    clamped_centres += per_bin[w].clamped_centres;
  }
  std::printf("worst A_r + T over %zu table entries and cell centres: %.5f; material: %d nodes with A_r > 1 "
              "(worst %.5f)\n",
              bins * static_cast<std::size_t>(g * g + g * g), worst, over, worst_raw);
  std::printf("BSDF reflection clamp acts at %d of %zu nodes and %d of %zu cell centres\n", clamped_nodes,
              bins * static_cast<std::size_t>(g * g), clamped_centres, bins * static_cast<std::size_t>(g * g));
  if (worst > 1.0) throw Error(o.file + ": white furnace violated: A_r + T = " + std::to_string(worst));
}

}  // namespace

void add_brdf_command(CLI::App& app, AppContext& context) {
  auto* brdf = app.add_subcommand("brdf", "Feather BSDF (.plm materials): pictures and the white furnace");
  brdf->require_subcommand(1);
  auto p = std::make_shared<PlotOptions>();
  auto* cp = brdf->add_subcommand("plot", "Projected-hemisphere plots of the mean BRDF and of instances (paper Fig. 10)");
  cp->add_option("file", p->file, "Feather material (.plm)")->required()->check(CLI::ExistingFile);
  cp->add_option("--incident", p->incident, "Incident directions \"theta,phi ...\" in degrees")->capture_default_str();
  cp->add_option("--out", p->out, "PNG to write")->required();
  cp->add_option("--instances", p->instances, "BRDF instances per incident direction")->capture_default_str();
  cp->add_option("--size", p->size, "Pixels per panel side")->capture_default_str();
  cp->add_option("--exposure", p->exposure, "Linear exposure (0: automatic)")->capture_default_str();
  cp->callback([&context, p] { plot(context, *p); });
  auto c = std::make_shared<CheckOptions>();
  auto* cc = brdf->add_subcommand("check", "White furnace of the BSDF at every table entry (A_r + T <= 1)");
  cc->add_option("file", c->file, "Feather material (.plm)")->required()->check(CLI::ExistingFile);
  cc->add_option("--transmission", c->transmission, "Requested diffuse transmission albedo")->capture_default_str();
  cc->callback([c] { check(*c); });
}

}  // namespace plumage::cli
