// Internal helpers of the periodic FDTD engine (not part of the public API).
#pragma once
#include "fdtd_periodic.hpp"

#include <functional>
#include <utility>
#include <vector>

namespace plumage::fdtd {

// Fitted Lorentz pole shapes (1/µm), see materials.cpp / NOTES.md.
inline constexpr double kKeratinW0 = 56.5;
inline constexpr double kMelaninW0a = 18.0;
inline constexpr double kMelaninGa = 12.4457;
inline constexpr double kMelaninW0b = 25.7132;
inline constexpr double kMelaninGb = 2.0;

namespace detail {
FitReport fit_lorentz(const std::string& name, const std::function<cplx(double)>& index,
                      const std::vector<std::pair<double, double>>& shapes, double lam_min,
                      double lam_max);
}  // namespace detail
}  // namespace plumage::fdtd
