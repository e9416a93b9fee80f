// The CSV files of `plumage simulate --csv`: Eq. 10 patterns, or the 2D differential scattering
// width of a full-circle set.
#include <array>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "plumage/atomic_file.hpp"
#include "plumage/conventions.hpp"
#include "plumage/simulation.hpp"

namespace plumage {

namespace {

std::string pol_name(int p) { return p == 2 ? "mean" : std::to_string(p + 1); }

}  // namespace

// The instance mean of the 2D differential scattering width.
//   dσ/dφ_o = cos θ_i |𝓔(φ_o)|²   (nm per radian)
// is the scattered power per unit barbule length and per radian of φ_o divided by the incident
// irradiance |E_i|²/(2η0) of the unit-amplitude plane wave (far_field.hpp: cos θ_i |𝓔|²/(2η0)
// is the power per unit length per radian); it integrates over the full circle to the scattering
// width C_sca (B&H; plugins/bem/reference/cylinder_series.hpp). σ_2D = 2π dσ/dφ_o is the "echo width"
// convention, lim 2πρ |E_s|²/|E_i|² at θ_i = 0.
void write_scattering_width_csv(const FarFieldSet& set, const std::filesystem::path& file) {
  std::ostringstream out;
  out << std::setprecision(9)
      << "# 2D differential scattering width over the full circle of outgoing azimuths (1 deg steps),\n"
      << "# instance mean, for a unit-amplitude (1 V/m) incident plane wave:\n"
      << "#   dsigma_dphi_nm = cos(theta_i) |E_far(phi_o)|^2  [nm per radian of phi_o]: scattered power per unit\n"
      << "#     barbule length and per radian divided by the incident irradiance |E_i|^2/(2 eta0); its integral\n"
      << "#     over phi_o is the total scattering width C_sca [nm];\n"
      << "#   sigma_2d_nm = 2 pi dsigma_dphi_nm [nm] (= lim 2 pi rho |E_s|^2/|E_i|^2 at theta_i = 0, 'echo width').\n"
      << "# E_far: far-field amplitude, E ~ exp(i gamma0 rho) rho^(-1/2) E_far (far_field.hpp), V/m*sqrt(nm).\n"
      << "# Only meaningful for plane-wave incidence (bem: incidence: plane_wave); a solver that\n"
      << "# illuminates with a beam gives E_far for a beam of unit peak amplitude instead.\n"
      << "# phi_o from +z (the macro normal) toward +x; pol: 1, 2, or mean = (pol1 + pol2)/2.\n"
      << "lambda_nm,theta_i_deg,phi_i_deg,pol,phi_o_deg,dsigma_dphi_nm,sigma_2d_nm\n";
  for (const auto& u : set.units) {
    const auto& phi = u.instances.front().phi_o_rad;
    const double ct = std::cos(u.nominal.theta_rad);
    std::array<std::vector<double>, 2> width{std::vector<double>(phi.size(), 0.0), std::vector<double>(phi.size(), 0.0)};
    for (const auto& ff : u.instances) {
      for (int p = 0; p < 2; ++p) {
        for (std::size_t j = 0; j < phi.size(); ++j) {
          const auto& f = ff.field[p][j];
          width[p][j] += ct * (std::norm(f[0]) + std::norm(f[1]) + std::norm(f[2])) /
                         static_cast<double>(u.instances.size());
        }
      }
    }
    for (int p = 0; p < 3; ++p) {
      for (std::size_t j = 0; j < phi.size(); ++j) {
        const double v = p < 2 ? width[p][j] : 0.5 * (width[0][j] + width[1][j]);
        out << u.lambda_nm << ',' << rad_to_deg(u.nominal.theta_rad) << ',' << rad_to_deg(u.nominal.phi_rad) << ','
            << pol_name(p) << ',' << rad_to_deg(phi[j]) << ',' << v << ',' << 2.0 * kPi * v << '\n';
      }
    }
  }
  write_text_atomically(file, out.str());
}

void write_pattern_csv(const FarFieldSet& set, const std::filesystem::path& file) {
  std::ostringstream out;
  out << std::setprecision(9)
      << "# Instance-mean reflectance density per radian of phi_o (paper Eq. 10):\n"
      << "#   U = mean_n cos(theta_i) |E_far|^2 / (2 eta0 Phi_i), with Phi_i the incident power on\n"
      << "#   the lit, windowed top surface (Eq. 9); integrating U over phi_o gives the reflected\n"
      << "#   fraction. pol: 1, 2, or mean = (pol1 + pol2)/2. Pattern direction set only.\n"
      << "lambda_nm,theta_i_deg,phi_i_deg,pol,phi_o_deg,density_per_rad\n";
  for (const auto& u : set.units) {
    const auto d1 = mean_reflectance_density(u, 0), d2 = mean_reflectance_density(u, 1);
    const auto& phi = u.instances.front().phi_o_rad;
    for (int p = 0; p < 3; ++p) {
      for (std::size_t j = 0; j < u.pattern_count; ++j) {
        const double v = p == 0 ? d1[j] : p == 1 ? d2[j] : 0.5 * (d1[j] + d2[j]);
        out << u.lambda_nm << ',' << rad_to_deg(u.nominal.theta_rad) << ',' << rad_to_deg(u.nominal.phi_rad) << ','
            << pol_name(p) << ',' << rad_to_deg(phi[j]) << ',' << v << '\n';
      }
    }
  }
  write_text_atomically(file, out.str());
}

}  // namespace plumage
