// Probe: GMRES convergence on a cylinder with no, block-Jacobi and near-field preconditioners
// (development tool, not a test).
#include <cstdio>
#include <cstdlib>

#include "bem_test_support.hpp"

using namespace plumage;
using namespace plumage::bem;

namespace {

// Block-Jacobi preconditioner, for comparison with the near field (NOTES.md §5, "Method gmres":
// 2583 iterations on the coated cylinder where the near field needs 67, so the solver does not
// offer it): the unknowns of `group` consecutive mesh vertices (all four families) form one
// diagonal block of Z, inverted by LU.
class BlockJacobi {
 public:
  BlockJacobi(const Mesh& mesh, const Eigen::MatrixXcd& Z, int group);
  void apply(const Eigen::VectorXcd& in, Eigen::VectorXcd& out) const;

 private:
  std::vector<std::vector<int>> blocks_;
  std::vector<Eigen::PartialPivLU<Eigen::MatrixXcd>> lu_;
};

BlockJacobi::BlockJacobi(const Mesh& mesh, const Eigen::MatrixXcd& Z, int group) {
  const int ngroups = (mesh.n_t + group - 1) / group;
  blocks_.assign(ngroups, {});
  for (int v = 0; v < mesh.n_t; ++v) {
    blocks_[v / group].push_back(mesh.jt(v));
    blocks_[v / group].push_back(mesh.mt(v));
  }
  for (int z = 0; z < mesh.n_z; ++z) {
    const int v = mesh.z_vertex[z];
    blocks_[v / group].push_back(mesh.jz(z));
    blocks_[v / group].push_back(mesh.mz(z));
  }
  for (const auto& idx : blocks_) {
    const int n = static_cast<int>(idx.size());
    Eigen::MatrixXcd B(n, n);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) B(i, j) = Z(idx[i], idx[j]);
    }
    lu_.emplace_back(B);
  }
}

void BlockJacobi::apply(const Eigen::VectorXcd& in, Eigen::VectorXcd& out) const {
  out.resize(in.size());
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    const auto& idx = blocks_[b];
    Eigen::VectorXcd v(idx.size());
    for (std::size_t i = 0; i < idx.size(); ++i) v[i] = in[idx[i]];
    const Eigen::VectorXcd s = lu_[b].solve(v);
    for (std::size_t i = 0; i < idx.size(); ++i) out[idx[i]] = s[i];
  }
}

}  // namespace

int main(int argc, char** argv) {
  const double ppw = argc > 1 ? atof(argv[1]) : 20, tol = argc > 2 ? atof(argv[2]) : 1e-6;
  const int group = argc > 3 ? atoi(argv[3]) : 16, restart = argc > 4 ? atoi(argv[4]) : 200;
  const double lambda = 500;
  auto cs = testing::layered_cylinder({250.0, 350.0}, {Material::keratin(), Material::melanin()}, lambda, ppw);
  if (argc > 6) {  // a lossless junction body (as in test_bem_solver)
    cs = CrossSection{};
    auto rect = [](double x0, double z0, double x1, double z1) {
      return Polygon{{x0, z0}, {x1, z0}, {x1, z1}, {x0, z1}};
    };
    cs.regions.push_back({rect(-200, -150, 0, 150), Material::constant(1.55), RegionRole::body});
    cs.regions.push_back({rect(0, -150, 160, 150), Material::constant({1.9, 0.0}), RegionRole::body});
    cs.regions.push_back({rect(-80, 150, 60, 230), Material::constant(1.3), RegionRole::film});
  }
  BemOptions o;
  o.points_per_wavelength = ppw;
  const auto prep = prepare_geometry(cs);
  const auto sys = build_system(prep->geometry, lambda, 0.5, o);
  const Eigen::MatrixXcd Z = assemble_dense(sys->mesh, sys->media, sys->k0, sys->beta, o.quadrature);
  Eigen::VectorXcd b(sys->mesh.unknowns());
  fill_rhs(sys->mesh, sys->k0, plane_wave(0.5, 0.7, 0), b);
  const Eigen::VectorXcd xref = sys->lu->solve(b);
  const Op A = [&](const Eigen::VectorXcd& in, Eigen::VectorXcd& out) { out.noalias() = Z * in; };
  BlockJacobi bj(sys->mesh, Z, group);
  const Op M = [&](const Eigen::VectorXcd& in, Eigen::VectorXcd& out) { bj.apply(in, out); };
  const Op I = [&](const Eigen::VectorXcd& in, Eigen::VectorXcd& out) { out = in; };
  const double nf = argc > 5 ? atof(argv[5]) : 2.0;
  NearFieldLU near(sys->mesh, Z, nf);
  std::printf("near field: %ld non-zeros (%.1f per row)\n", near.nonzeros(), double(near.nonzeros()) / b.size());
  const Op NF = [&](const Eigen::VectorXcd& in, Eigen::VectorXcd& out) { near.apply(in, out); };
  for (int pre = 0; pre < 3; ++pre) {
    Eigen::VectorXcd x = Eigen::VectorXcd::Zero(b.size());
    const auto r = gmres(A, pre == 0 ? I : pre == 1 ? M : NF, b, x, tol, restart, 3000);
    std::printf("N %d precond %d: iterations %d residual %.2e converged %d, |x - x_lu|/|x_lu| %.2e\n",
                sys->mesh.unknowns(), pre, r.iterations, r.relative_residual, r.converged,
                (x - xref).norm() / xref.norm());
  }
}
