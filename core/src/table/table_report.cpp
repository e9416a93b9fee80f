// table_query_report and draw_table_overview (plumage/table_report.hpp).
#include "plumage/table_report.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "plumage/charts.hpp"
#include "plumage/conventions.hpp"
#include "plumage/local_reflection.hpp"

namespace plumage {

namespace {

// The table's notes (warnings included) inside a JSON string.
std::string json_escape(const std::string& text) {
  std::string out;
  for (char ch : text) {
    if (ch == '"' || ch == '\\') out += '\\';
    if (static_cast<unsigned char>(ch) < 0x20) {
      out += ' ';
      continue;
    }
    out += ch;
  }
  return out;
}

std::string complex_pair(Complex z) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.9g, %.9g", z.real(), z.imag());
  return buf;
}

}  // namespace

std::string table_query_report(const ReflectionTable& t, const std::string& file, double lambda_nm, double theta_deg,
                               double phi_deg, TableQueryFormat format) {
  const JonesReflection r = t.query(lambda_nm, deg_to_rad(theta_deg), deg_to_rad(phi_deg));
  const double Rs = reflectance_s(r), Rp = reflectance_p(r);
  const auto c = complex_pair;
  std::ostringstream o;
  if (format == TableQueryFormat::json) {
    o << "{\"file\": \"" << file << "\", \"crystal\": \"" << t.metadata().crystal << "\", \"lambda_nm\": " << lambda_nm
      << ", \"theta_deg\": " << theta_deg << ", \"phi_deg\": " << phi_deg << ", \"jones\": {\"ss\": [" << c(r.ss)
      << "], \"sp\": [" << c(r.sp) << "], \"ps\": [" << c(r.ps) << "], \"pp\": [" << c(r.pp) << "]}, \"R_s\": " << Rs
      << ", \"R_p\": " << Rp << ", \"notes\": \"" << json_escape(t.metadata().notes) << "\"}\n";
  } else {
    o << t.metadata().crystal << " at " << lambda_nm << " nm, theta " << theta_deg << " deg, phi_local " << phi_deg
      << " deg (Jones, (s, p) basis)\n"
      << "  ss = " << c(r.ss) << "\n  sp = " << c(r.sp) << "\n  ps = " << c(r.ps) << "\n  pp = " << c(r.pp)
      << "\n  R_s = " << Rs << "  R_p = " << Rp << "\n"
      << "  notes: " << t.metadata().notes << "\n";
  }
  return o.str();
}

void draw_table_overview(const ReflectionTable& t, const std::string& title_file, const std::filesystem::path& png) {
  const auto& L = t.grid().lambda_nm;
  LineChart chart;
  chart.title = t.metadata().crystal + " reflection table (" + title_file + ")";
  chart.x_label = "wavelength (nm)";
  chart.y_label = "|r|^2";
  const double lo = L.front(), hi = L.back();
  const int n = std::max<int>(2, static_cast<int>(L.size()) * 4);
  for (int pol = 0; pol < 2; ++pol) {
    const std::string name = pol == 0 ? "s" : "p";
    for (double a : {0.0, 20.0, 40.0, 60.0, 75.0}) {
      char series[64];
      std::snprintf(series, sizeof series, "%g deg", a);
      for (int k = 0; k < n; ++k) {
        const double lam = L.size() == 1 ? lo : lo + (hi - lo) * k / (n - 1);
        const JonesReflection rp = t.query(lam, 0.0, deg_to_rad(a));  // in-plane (phi_local)
        const JonesReflection rt = t.query(lam, deg_to_rad(a), 0.0);  // conical (theta)
        chart.points.push_back({name + "-pol, theta = 0, angle = phi_local", series, lam,
                                pol == 0 ? reflectance_s(rp) : reflectance_p(rp)});
        chart.points.push_back({name + "-pol, phi_local = 0, angle = theta", series, lam,
                                pol == 0 ? reflectance_s(rt) : reflectance_p(rt)});
      }
    }
  }
  draw_line_chart(chart, png);
}

}  // namespace plumage
