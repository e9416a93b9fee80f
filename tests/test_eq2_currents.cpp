// The two paths of the Eq. 2 currents (eq2_currents.cpp) on the same inputs: whole nodes go
// through the four-lane vector code, sub-sampled reflection through the scalar point_currents.
// With K = 2 sub-samples per segment, node m's samples are the midpoints 2m, 2m + 2 and its own
// vertex 2m + 1. Facing the midpoints away from the light leaves the node's own sample alone in
// its tent-weighted mean, so the scalar path must reproduce the vector path's currents at every
// node: lit and unlit lanes, a partly filled last block, both current variants, the lossless
// reference columns.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <vector>

#include "plumage/far_field.hpp"
#include "solver/eq2_currents.hpp"

using namespace plumage;

namespace {

struct Eq2Inputs {
  std::vector<Vec2> normals;
  std::vector<double> window, node_length, regularity, segment_length;
  std::vector<JonesReflection> jones;
  std::vector<Vec2> sample_normals;        // K = 2: 2·(nodes + 1) − 1 fine interior vertices
  std::vector<JonesReflection> sample_jones;
};

// 11 nodes (two full blocks of four and a tail of three), tilted normals, two of them facing
// away from the light (unlit), different Jones matrices per node.
Eq2Inputs make_inputs(const std::array<double, 3>& w_i) {
  Eq2Inputs in;
  const int nodes = 11;
  for (int m = 0; m < nodes; ++m) {
    const double tilt = m == 3 || m == 9 ? 2.5 + 0.1 * m : 0.35 * std::sin(1.7 * m);  // nodes 3, 9: back-facing
    in.normals.push_back({std::sin(tilt), std::cos(tilt)});
    in.window.push_back(std::exp(-0.02 * (m - 5) * (m - 5)));
    in.node_length.push_back(10.0 + m);
    in.regularity.push_back(0.8 + 0.02 * m);
    const double t = 0.3 * m;
    in.jones.push_back({std::polar(0.3 + 0.05 * m, t), std::polar(0.04, 2 * t + 0.1), std::polar(0.03, -t),
                        std::polar(0.5 - 0.02 * m, 1.3 - t)});
  }
  for (int k = 0; k <= nodes; ++k) in.segment_length.push_back(9.0 + 0.5 * k);
  // Away from the light: n̂ = −(ω_i projected on xz), so ω_i·n̂ < 0.
  const double len = std::hypot(w_i[0], w_i[2]);
  const Vec2 away{-w_i[0] / len, -w_i[2] / len};
  for (int f = 0; f < 2 * (nodes + 1) - 1; ++f) {
    const bool own_vertex = f % 2 == 1;
    const auto m = static_cast<std::size_t>(f / 2);
    in.sample_normals.push_back(own_vertex ? in.normals[m] : away);
    in.sample_jones.push_back(own_vertex ? in.jones[m] : JonesReflection{{9.0, 9.0}, {9.0, 0}, {0, 9.0}, {9.0, 9.0}});
  }
  return in;
}

}  // namespace

TEST_CASE("Eq. 2 currents: the vector node path equals the scalar sub-sampled path", "[solver][eq2]") {
  const IncidentDirection incident{0.6, 0.4};
  const double ct = std::cos(incident.theta_rad);
  const std::array<double, 3> w_i{ct * std::sin(incident.phi_rad), std::sin(incident.theta_rad),
                                  ct * std::cos(incident.phi_rad)};
  const Eq2Inputs in = make_inputs(w_i);
  const detail::CurrentNodes nodes{in.normals, in.window, in.node_length, in.regularity, in.segment_length, 1, {}};
  const detail::CurrentNodes sampled{in.normals, in.window, in.node_length, in.regularity, in.segment_length, 2,
                                     in.sample_normals};
  for (const bool with_incident : {false, true}) {
    for (const int columns : {12, 24}) {
      CAPTURE(with_incident, columns);
      Eigen::MatrixXcd vec = Eigen::MatrixXcd::Constant(11, columns, Complex(7.0, 7.0));  // every entry overwritten
      Eigen::MatrixXcd sca = Eigen::MatrixXcd::Constant(11, columns, Complex(-7.0, 7.0));
      std::array<double, 2> power_vec{}, power_sca{};
      detail::fill_amplitudes(nodes, incident, w_i, in.jones, with_incident, vec, power_vec);
      detail::fill_amplitudes(sampled, incident, w_i, in.sample_jones, with_incident, sca, power_sca);
      CHECK(power_vec == power_sca);
      for (const Eigen::Index m : {3, 9}) {  // back-facing nodes: exact zeros in both paths
        CHECK(vec.row(m).cwiseAbs().maxCoeff() == 0.0);
        CHECK(sca.row(m).cwiseAbs().maxCoeff() == 0.0);
      }
      // Lit nodes carry current; the two paths differ only by rounding (FMA contraction).
      for (Eigen::Index m = 0; m < 11; ++m) {
        if (m != 3 && m != 9) CHECK(vec.row(m).cwiseAbs().maxCoeff() > 1e-3);
      }
      const double scale = vec.cwiseAbs().maxCoeff();
      CHECK((vec - sca).cwiseAbs().maxCoeff() <= 1e-13 * scale);
    }
  }
}
