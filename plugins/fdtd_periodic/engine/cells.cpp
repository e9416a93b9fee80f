// Geometry: cell painting and the 14 reference cells of photonic-crystals.md.
#include "fdtd_periodic.hpp"

#include <cmath>
#include <map>

namespace plumage::fdtd {

int Cell::material_at(double x, double z) const {
    if (z < 0.0) return ambient;
    int m = substrate;
    for (const auto& s : slabs)
        if (z >= s.z0 && z < s.z1) m = s.material;
    for (const auto& c : circles) {
        double dx = x - c.x;
        dx -= ax * std::floor(dx / ax + 0.5);   // nearest periodic image
        double dz = z - c.z;
        if (dx * dx + dz * dz < c.r * c.r) m = c.material;
    }
    return m;
}

namespace {
struct CellSpec {
    bool hexagonal;   // else rectangular (peacock)
    double ax, az, D, d;
    int rows;
    double cortex;
    char kind;        // 'S' solid melanin, 'H' hollow (air core d), 'P' peacock (air channel d)
};

const std::map<std::string, CellSpec>& table() {
    static const std::map<std::string, CellSpec> t = {
        {"mallard-lime", {true, 0.200, 0.1732, 0.160, 0.0, 6, 0.130, 'S'}},
        {"mallard-green", {true, 0.190, 0.1645, 0.152, 0.0, 6, 0.1235, 'S'}},
        {"mallard-cyan", {true, 0.180, 0.1559, 0.144, 0.0, 6, 0.117, 'S'}},
        {"mallard-blue", {true, 0.170, 0.1472, 0.136, 0.0, 6, 0.1105, 'S'}},
        {"magpie-forest", {true, 0.16, 0.190, 0.144, 0.1008, 4, 0.05, 'H'}},
        {"magpie-lime", {true, 0.17, 0.200, 0.153, 0.1071, 4, 0.05, 'H'}},
        {"magpie-yellow", {true, 0.18, 0.205, 0.162, 0.1134, 4, 0.05, 'H'}},
        {"magpie-rose", {true, 0.18, 0.250, 0.162, 0.1134, 4, 0.05, 'H'}},
        {"magpie-purple", {true, 0.18, 0.262, 0.162, 0.1134, 4, 0.05, 'H'}},
        {"magpie-violet", {true, 0.18, 0.145, 0.162, 0.1134, 4, 0.05, 'H'}},
        {"magpie-blue", {true, 0.19, 0.1645, 0.171, 0.1197, 4, 0.05, 'H'}},
        {"magpie-teal", {true, 0.20, 0.1732, 0.180, 0.1260, 4, 0.05, 'H'}},
        {"peacock-cyan", {false, 0.16, 0.160, 0.110, 0.033, 9, 0.10, 'P'}},
        {"peacock-yellow", {false, 0.16, 0.195, 0.120, 0.055, 5, 0.13, 'P'}},
    };
    return t;
}
}  // namespace

std::vector<std::string> spec_cell_names() {
    std::vector<std::string> v;
    for (const auto& [k, _] : table()) v.push_back(k);
    return v;
}

Cell spec_cell(const std::string& variant, MaterialMode mode, double lambda_ref_um) {
    auto it = table().find(variant);
    if (it == table().end()) throw std::invalid_argument("spec_cell: unknown variant '" + variant + "'");
    const CellSpec& s = it->second;
    Cell c;
    c.ax = s.ax;
    if (mode == MaterialMode::Broadband) {
        c.materials = {air_model(), keratin_fit().model, melanin_fit().model};
    } else {
        cplx nk = keratin_index(lambda_ref_um), nm = melanin_index(lambda_ref_um);
        c.materials = {air_model(), constant_model("keratin", nk * nk, lambda_ref_um),
                       constant_model("melanin", nm * nm, lambda_ref_um)};
    }
    c.ambient = 0;
    c.substrate = 1;
    double deepest = 0.0;
    for (int j = 0; j < s.rows; ++j) {
        double zj = s.cortex + s.D / 2 + j * s.az;
        double xj = (s.hexagonal && (j % 2 == 1)) ? s.ax / 2 : 0.0;
        c.circles.push_back({xj, zj, s.D / 2, 2});
        if (s.kind == 'H') c.circles.push_back({xj, zj, s.d / 2, 0});
        deepest = std::max(deepest, zj + s.D / 2);
        if (s.kind == 'P') {
            c.circles.push_back({s.ax / 2, zj + s.az / 2, s.d / 2, 0});
            deepest = std::max(deepest, zj + s.az / 2 + s.d / 2);
        }
    }
    c.structure_depth = deepest;
    return c;
}

}  // namespace plumage::fdtd
