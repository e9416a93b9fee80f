// Bit-identical geometry on every machine: no fused multiply-add contraction (-march=native
// would otherwise decide per machine).
#pragma GCC optimize("fp-contract=off")
#include "plumage/cross_section_io.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <ostream>
#include <sstream>

#include "plumage/geometry.hpp"

namespace plumage {

namespace {

// Numbers in their shortest form that reads back to the same double (std::to_chars), so that
// read_cross_section_text(write_cross_section_text(cs)) == cs exactly (issue 25: an imported
// section must give the procedural instance's far field to rounding).
struct Exact {
  double v;
};
std::ostream& operator<<(std::ostream& out, Exact e) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, e.v);
  return out.write(buf, r.ptr - buf);
}

// Material::name() prints a constant index and a mixture's fraction with 6 digits (it names
// materials in messages and keys); the file needs every bit, in the same syntax
// (parse_material_text reads both).
std::string exact_name(const Material& m) {
  std::ostringstream os;
  switch (m.kind()) {
    case Material::Kind::constant: {
      const Complex n = m.index(550.0);
      os << Exact{n.real()};
      if (n.imag() != 0.0) os << '+' << Exact{n.imag()} << 'i';
      return os.str();
    }
    case Material::Kind::mixture:
      os << "mix(" << exact_name(m.host()) << ", " << exact_name(m.guest()) << ", " << Exact{m.fraction()} << ')';
      return os.str();
    default:
      return m.name();
  }
}

void points(std::ostream& out, const Polyline& p) {
  for (const Vec2& v : p) out << Exact{v.x} << ' ' << Exact{v.z} << '\n';
}

}  // namespace

void write_cross_section_text(std::ostream& out, const CrossSection& cs) {
  out << "plumage-cross-section 1\n";
  out << "label " << cs.label << "\n";
  out << "generator " << cs.generator << "\n";
  out << "instance " << cs.instance << "\n";
  out << "seed " << cs.seed << "\n";
  out << "units nm\n";
  out << "top " << cs.top.size() << "\n";
  points(out, cs.top);
  out << "top_roughness " << cs.top_roughness_nm.size() << "\n";
  for (double r : cs.top_roughness_nm) out << Exact{r} << '\n';
  out << "bottom " << cs.bottom.size() << "\n";
  points(out, cs.bottom);
  out << "regions " << cs.regions.size() << "\n";
  for (std::size_t i = 0; i < cs.regions.size(); ++i) {
    const Region& r = cs.regions[i];
    out << "region " << i << " " << role_name(r.role) << " parent " << r.parent << " layer " << r.layer
        << " members " << r.members << " size_nm " << Exact{r.size_nm} << " vertices " << r.outline.size()
        << " material " << exact_name(r.material) << "\n";
    points(out, r.outline);
  }
  if (cs.layered) {
    out << "layered " << cs.layered->boundaries.size() << " below_top " << exact_name(cs.layered->below_top) << "\n";
    for (std::size_t i = 0; i < cs.layered->boundaries.size(); ++i) {
      const LayerBoundary& b = cs.layered->boundaries[i];
      const bool f = !b.fraction.empty();
      out << "boundary " << i << " closes " << b.closes << " points " << b.points.size()
          << " fraction " << (f ? 1 : 0) << " below " << exact_name(b.below) << "\n";
      for (std::size_t k = 0; k < b.points.size(); ++k) {
        out << Exact{b.points[k].x} << ' ' << Exact{b.points[k].z};
        if (f) out << ' ' << Exact{b.fraction[k]};
        out << '\n';
      }
    }
  }
  if (cs.crystal) {
    out << "crystal " << cs.crystal->crystal_name << " " << cs.crystal->regularity.size() << " "
        << cs.crystal->crystal << "\n";
    for (double q : cs.crystal->regularity) out << Exact{q} << '\n';
  }
  out << "melanosomes " << cs.melanosomes.size() << "\n";
  for (const Disc& d : cs.melanosomes) {
    out << Exact{d.center.x} << ' ' << Exact{d.center.z} << ' ' << Exact{d.diameter_nm} << ' ' << d.row << '\n';
  }
  out << "end\n";
}

// ---------------------------------------------------------------------------------------------
// SVG

namespace {

// Grey level of a material (0 black .. 255 white): air white, keratin grey, melanin black.
int grey_of(const Material& m) {
  switch (m.kind()) {
    case Material::Kind::air: return 255;
    case Material::Kind::keratin: return 170;
    case Material::Kind::melanin: return 0;
    case Material::Kind::constant: {
      const double n = m.index(550.0).real();
      return std::clamp(static_cast<int>(255 - (n - 1.0) / 0.8 * 255), 0, 255);
    }
    case Material::Kind::mixture: {
      // Interpolate by the guest fraction between host and guest greys (guess the parts from the
      // index at 550 nm, which is linear in the fraction).
      const double f = m.fraction();
      const Material h = m.with_fraction(0.0), g = m.with_fraction(1.0);
      auto grey_index = [](Complex n) {
        if (n.imag() > 0.01) return 0.0;
        if (std::abs(n.real() - 1.0) < 1e-6) return 255.0;
        return 170.0;
      };
      const double v = (1.0 - f) * grey_index(h.index(550.0)) + f * grey_index(g.index(550.0));
      return static_cast<int>(std::lround(v));
    }
  }
  return 128;
}

std::string colour(const Material& m) {
  char buf[16];
  const int g = grey_of(m);
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", g, g, g);
  return buf;
}

}  // namespace

namespace {

// The drawn window of a picture, shared by the SVG and the PNG: x range (the whole section or
// the requested window), z range of the outline inside it, and the panel layout.
struct PictureFrame {
  double x0, x1, zmin, zmax, margin, panel;
  int panels;
};

PictureFrame picture_frame(const CrossSection& cs, const SvgOptions& o) {
  double x0 = cs.top.front().x, x1 = cs.top.back().x;
  for (const Vec2& p : cs.bottom) { x0 = std::min(x0, p.x); x1 = std::max(x1, p.x); }
  if (o.window_nm) { x0 = o.window_nm->first; x1 = o.window_nm->second; }
  double zmax = -1e300, zmin = 1e300;
  for (const Vec2& p : cs.regions.empty() ? cs.top : cs.regions[0].outline) {
    if (p.x < x0 || p.x > x1) continue;
    zmax = std::max(zmax, p.z);
    zmin = std::min(zmin, p.z);
  }
  const double margin_nm = 0.05 * (zmax - zmin) + 100.0;
  const double panel = zmax - zmin + 2.0 * margin_nm;
  const int panels = (o.exact ? 1 : 0) + (o.reduced ? 1 : 0);
  return {x0, x1, zmin, zmax, margin_nm, panel, panels};
}

}  // namespace

void write_cross_section_svg(std::ostream& out, const CrossSection& cs, const SvgOptions& o) {
  const auto [x0, x1, zmin, zmax, margin, panel, panels] = picture_frame(cs, o);
  const double s = o.pixels_per_um / 1000.0;  // px per nm
  const double width_px = (x1 - x0) * s, height_px = panel * panels * s;
  out << std::fixed << std::setprecision(1);
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width_px << "\" height=\"" << height_px
      << "\" viewBox=\"" << x0 << " 0 " << (x1 - x0) << " " << panel * panels << "\">\n";
  out << "<title>" << cs.label << " instance " << cs.instance << " (" << cs.generator
      << "): exact regions above, reduced model below</title>\n";
  out << "<rect x=\"" << x0 << "\" y=\"0\" width=\"" << (x1 - x0) << "\" height=\"" << panel * panels
      << "\" fill=\"#ffffff\"/>\n";
  auto path = [&](const Polygon& poly, double y_off, const std::string& fill) {
    out << "<path fill=\"" << fill << "\" d=\"";
    for (std::size_t i = 0; i < poly.size(); ++i) {
      out << (i == 0 ? 'M' : 'L') << poly[i].x << ' ' << (y_off + zmax + margin - poly[i].z);
    }
    out << "Z\"/>\n";
  };
  auto visible = [&](const Polygon& poly) {
    double a = 1e300, b = -1e300;
    for (const Vec2& p : poly) { a = std::min(a, p.x); b = std::max(b, p.x); }
    return b >= x0 && a <= x1;
  };
  double y = 0.0;
  if (o.exact) {
    for (const Region& r : cs.regions) {
      if (visible(r.outline)) path(r.outline, y, colour(r.material));
    }
    y += panel;
  }
  if (o.reduced && cs.layered) {
    // Columns: the layer stack along the normal of every k-th top vertex.
    std::size_t first = 0, last = cs.top.size() - 1;
    while (first < last && cs.top[first].x < x0) ++first;
    while (last > first && cs.top[last].x > x1) --last;
    const std::size_t count = last - first + 1;
    const std::size_t stride = std::max<std::size_t>(1, (count + static_cast<std::size_t>(o.max_columns) - 1) /
                                                          static_cast<std::size_t>(o.max_columns));
    const auto normals = vertex_normals(cs.top);
    double spacing = (cs.top.back().x - cs.top.front().x) / static_cast<double>(cs.top.size() - 1);
    out << "<g stroke-width=\"" << spacing * static_cast<double>(stride) * 1.05 << "\">\n";
    for (std::size_t i = first; i <= last; i += stride) {
      const LayerProfile prof = layer_profile_at(cs, i);
      Vec2 p = cs.top[i];
      const Vec2 n = normals[i];
      auto seg = [&](Vec2 a, Vec2 b, const std::string& c) {
        out << "<line stroke=\"" << c << "\" x1=\"" << a.x << "\" y1=\"" << (y + zmax + margin - a.z)
            << "\" x2=\"" << b.x << "\" y2=\"" << (y + zmax + margin - b.z) << "\"/>\n";
      };
      // Merge neighbouring layers of one colour.
      std::string current;
      Vec2 start = p;
      for (const Layer& l : prof.layers) {
        const std::string c = colour(l.material);
        if (c != current && !current.empty()) {
          if (current != "#ffffff") seg(start, p, current);
          start = p;
        }
        current = c;
        p = p - l.thickness_nm * n;
      }
      if (!current.empty() && current != "#ffffff") seg(start, p, current);
    }
    out << "</g>\n";
  } else if (o.reduced && cs.crystal) {
    // Crystal types: the body, and the regularity as a bar under the top (black = 1).
    if (!cs.regions.empty()) path(cs.regions[0].outline, y, colour(cs.regions[0].material));
    out << "<text x=\"" << x0 + 200 << "\" y=\"" << y + panel - margin * 0.3 << "\" font-size=\""
        << margin * 0.6 << "\">crystal " << cs.crystal->crystal_name << "</text>\n";
  }
  out << "</svg>\n";
}

namespace {

// Fills a polygon (even-odd rule at pixel centres) through a world → pixel map.
template <class Map>
void fill_polygon(Image& img, const Polygon& poly, Rgb8 c, Map to_px) {
  if (poly.size() < 3) return;
  std::vector<std::pair<double, double>> pts(poly.size());
  double y0 = 1e300, y1 = -1e300;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    pts[i] = to_px(poly[i]);
    y0 = std::min(y0, pts[i].second);
    y1 = std::max(y1, pts[i].second);
  }
  const int r0 = std::max(0, static_cast<int>(std::floor(y0))), r1 = std::min(img.height() - 1, static_cast<int>(std::ceil(y1)));
  std::vector<double> xs;
  for (int row = r0; row <= r1; ++row) {
    const double y = row + 0.5;
    xs.clear();
    for (std::size_t i = 0, j = pts.size() - 1; i < pts.size(); j = i++) {
      const auto [xa, ya] = pts[j];
      const auto [xb, yb] = pts[i];
      if ((ya > y) != (yb > y)) xs.push_back(xa + (y - ya) / (yb - ya) * (xb - xa));
    }
    std::sort(xs.begin(), xs.end());
    for (std::size_t k = 0; k + 1 < xs.size(); k += 2) {
      const int a = std::max(0, static_cast<int>(std::ceil(xs[k] - 0.5)));
      const int b = std::min(img.width() - 1, static_cast<int>(std::floor(xs[k + 1] - 0.5)));
      for (int x = a; x <= b; ++x) img.at(x, row) = c;
    }
  }
}

Rgb8 rgb_of(const Material& m) {
  const auto g = static_cast<std::uint8_t>(grey_of(m));
  return {g, g, g};
}

}  // namespace

MemoryEstimate estimate_picture_memory(const CrossSection& cs, const SvgOptions& o) {
  const auto [x0, x1, zmin, zmax, margin, panel, panels] = picture_frame(cs, o);
  const double s = o.pixels_per_um / 1000.0;
  const double w = std::max(1.0, (x1 - x0) * s), h = std::max(1.0, panel * panels * s);
  MemoryEstimate e;
  e.job = "PNG picture of " + cs.label + ": " + std::to_string(std::lround(std::min(w, 1e18))) + " x " +
          std::to_string(std::lround(std::min(h, 1e18))) + " pixels";
  // The raster, write_png's RGB copy, and the encoded bytes (at most about the raw size).
  e.add("RGB raster, its copy and the encoded PNG", 3.0 * 3.0 * w * h);
  e.lower_with = {"--pixels-per-um", "--window-um", "--no-png"};
  return e;
}

// libpng's simplified writer (png_image_write_to_memory) refuses a raster of more than 2^32 − 1
// bytes ("memory image too large"), after the whole picture has been drawn: a 2 mm wide barbule at
// 50 px/um (100 000 x 30 000 pixels, the arc's height grows with the width) took 108 s and 10.8 GB
// to fail so. Checked before drawing, with the scale that would fit.
void check_picture_size(const CrossSection& cs, const SvgOptions& o) {
  constexpr double kMaxRasterBytes = 4294967295.0;
  const auto [x0, x1, zmin, zmax, margin, panel, panels] = picture_frame(cs, o);
  const double s = o.pixels_per_um / 1000.0;
  const double w = std::max(1.0, (x1 - x0) * s), h = std::max(1.0, panel * panels * s);
  if (3.0 * w * h <= kMaxRasterBytes) return;
  char text[400];
  std::snprintf(text, sizeof text,
                "PNG picture of %s: %.0f x %.0f pixels at %g px/um is over the PNG writer's limit of 4 GiB of "
                "raster; lower it with --pixels-per-um (at most %.3g here), --window-um, or --no-png",
                cs.label.c_str(), std::min(w, 1e18), std::min(h, 1e18), o.pixels_per_um,
                0.99 * o.pixels_per_um * std::sqrt(kMaxRasterBytes / (3.0 * w * h)));
  throw MemoryBudgetError(text);
}

Image render_cross_section(const CrossSection& cs, const SvgOptions& o) {
  check_picture_size(cs, o);
  check_memory(estimate_picture_memory(cs, o));
  const auto [x0, x1, zmin, zmax, margin, panel, panels] = picture_frame(cs, o);
  const double s = o.pixels_per_um / 1000.0;
  const int w = std::max(1, static_cast<int>(std::lround((x1 - x0) * s)));
  const int h = std::max(1, static_cast<int>(std::lround(panel * panels * s)));
  Image img(w, h, Rgb8{255, 255, 255});
  double y_off = 0.0;
  auto map = [&](double off) {
    return [&, off](Vec2 p) { return std::make_pair((p.x - x0) * s, (off + zmax + margin - p.z) * s); };
  };
  if (o.exact) {
    for (const Region& r : cs.regions) fill_polygon(img, r.outline, rgb_of(r.material), map(y_off));
    y_off += panel;
  }
  if (o.reduced) {
    if (cs.layered) {
      const auto normals = vertex_normals(cs.top);
      const double step = 0.5 / s;
      for (std::size_t i = 0; i < cs.top.size(); ++i) {
        if (cs.top[i].x < x0 || cs.top[i].x > x1) continue;
        const LayerProfile prof = layer_profile_at(cs, i);
        // A strip as wide as the vertex's share of the top.
        const Vec2 a = cs.top[i == 0 ? 0 : i - 1], b = cs.top[i + 1 == cs.top.size() ? i : i + 1];
        const double half = 0.5 * norm(b - a) + step;  // overlaps neighbours where normals spread
        const Vec2 tg{normals[i].z, -normals[i].x};
        Vec2 p = cs.top[i];
        for (const Layer& l : prof.layers) {
          const Rgb8 c = rgb_of(l.material);
          for (double t = 0.0; t < l.thickness_nm; t += step) {
            for (double u = -half; u <= half; u += step) {
              const Vec2 q = p - t * normals[i] + u * tg;
              const auto [px, py] = map(y_off)(q);
              const int ix = static_cast<int>(px), iy = static_cast<int>(py);
              if (ix >= 0 && ix < w && iy >= 0 && iy < h) img.at(ix, iy) = c;
            }
          }
          p = p - l.thickness_nm * normals[i];
        }
      }
    } else if (!cs.regions.empty()) {
      fill_polygon(img, cs.regions[0].outline, rgb_of(cs.regions[0].material), map(y_off));
    }
  }
  return img;
}

}  // namespace plumage
