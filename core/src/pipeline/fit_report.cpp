// Reports of a characterisation: the fit-quality summary, the fit diagnostics and the benchmark
// record (characterize.hpp, fit_report.hpp).
#include "fit_report.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "plumage/atomic_file.hpp"
#include "plumage/bench_record.hpp"
#include "plumage/charts.hpp"
#include "plumage/conventions.hpp"

namespace plumage {

std::string fit_quality_summary(const CharacterizeSettings& s, const std::vector<GroupRecord>& records) {
  std::vector<double> eff, sta;
  double wsum = 0, werr = 0;
  for (const GroupRecord& r : records) {
    for (const UnitRecord& u : r.units) {
      eff.push_back(u.rel_l2_eff);
      sta.push_back(u.rel_l2_sta);
      werr += u.energy * u.rel_l2_eff;
      wsum += u.energy;
    }
  }
  if (eff.empty()) return "no units";
  auto q = [](std::vector<double> v, double p) {
    std::sort(v.begin(), v.end());
    return v[static_cast<std::size_t>(p * static_cast<double>(v.size() - 1))];
  };
  std::ostringstream o;
  o.precision(3);
  o << s.label << " (" << s.fidelity << ", " << eff.size() << " units): relative L2 of the mean-lobe fit on the cone: median "
    << q(eff, 0.5) << ", 90th percentile " << q(eff, 0.9) << ", max " << q(eff, 1.0) << ", energy-weighted mean "
    << (wsum > 0 ? werr / wsum : 0.0) << "; statistics lobe: median " << q(sta, 0.5) << ", 90th percentile " << q(sta, 0.9);
  return o.str();
}

std::vector<FitDiagnostic> fit_diagnostic_units(const CharacterizeSettings& s) {
  std::uint32_t w = 0;
  for (std::size_t k = 0; k < s.lambda_nm.size(); ++k)
    if (std::abs(s.lambda_nm[k] - 550) < std::abs(s.lambda_nm[w] - 550)) w = static_cast<std::uint32_t>(k);
  const auto G = static_cast<std::uint32_t>(s.grid), h = std::max<std::uint32_t>(1, G / 2), q = std::max<std::uint32_t>(1, G / 4);
  return {{w, G, G, {}, {}, {}, 0}, {w, G, h, {}, {}, {}, 0}, {w, h, G, {}, {}, {}, 0}, {w, q, q, {}, {}, {}, 0}};
}

void write_fit_diagnostics(const std::filesystem::path& dir, const CharacterizeSettings& s,
                           const std::vector<FitDiagnostic>& units, const std::string& summary) {
  create_output_directory(dir);
  LineChart chart;
  chart.title = s.label + ": simulated mean pattern U vs GGX fit on the cone (" + s.fidelity + ")";
  chart.x_label = "phi_o (deg)";
  chart.y_label = "reflectance density per rad";
  std::ostringstream csv;
  csv << std::setprecision(9) << "lambda_nm,cos_theta_i,cos_phi_i,phi_o_deg,mean_U,fit\n";
  for (const auto& d : units) {
    if (d.u.empty()) continue;  // computed by an earlier (resumed) run or another shard
    std::ostringstream panel;
    panel << std::setprecision(3) << s.lambda_nm[d.w] << " nm, cos th_i " << double(d.a) / s.grid << ", cos ph_i "
          << double(d.b) / s.grid << " (rel. L2 " << d.rel_l2 << ")";
    for (std::size_t k = 0; k < d.u.size(); ++k) {
      chart.points.push_back({panel.str(), "simulated U", rad_to_deg(d.phi_o[k]), d.u[k]});
      chart.points.push_back({panel.str(), "GGX fit", rad_to_deg(d.phi_o[k]), d.fit[k]});
      csv << s.lambda_nm[d.w] << ',' << double(d.a) / s.grid << ',' << double(d.b) / s.grid << ','
          << rad_to_deg(d.phi_o[k]) << ',' << d.u[k] << ',' << d.fit[k] << '\n';
    }
  }
  write_text_atomically(dir / "fit-patterns.csv", csv.str());
  write_text_atomically(dir / "fit-summary.txt", summary + "\n");
  if (!chart.points.empty()) draw_line_chart(chart, dir / "fit-patterns.png");
}

Benchmark::Report characterize_benchmark(const SpeciesConfig& config, const CharacterizeSettings& s,
                                         const CharacterizeResult& r, const std::string& command,
                                         std::uintmax_t file_bytes) {
  std::ostringstream md;
  md << std::fixed << "## characterize " << s.label << " (" << s.fidelity << ")\n\n"
     << s.lambda_nm.size() << " wavelengths x " << s.grid << " x " << s.grid << " incident nodes, " << s.instances
     << " instances, " << s.pattern_samples << " pattern + " << s.projected_samples << " projected directions.\n\n"
     << "| machine | command | date | wall | CPU | groups computed | file size |\n|---|---|---|---|---|---|---|\n"
     << "| " << machine_description() << " | `" << command << "` | " << today_iso() << " | " << std::setprecision(0)
     << r.wall_s << " s | " << r.cpu_s << " s | " << r.plan.todo << " of " << s.group_count() << " | "
     << std::setprecision(2) << static_cast<double>(file_bytes) / 1e6 << " MB |\n\n" << r.fit_summary << "\n";
  return {"characterize:" + config.species + "-" + config.variant + ":" + s.fidelity, md.str()};
}

}  // namespace plumage
