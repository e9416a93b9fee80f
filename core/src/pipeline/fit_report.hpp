// Private to the pipeline: the fit diagnostics of `characterize --diagnostics` (fit_report.cpp).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "work_groups.hpp"

namespace plumage {

// Four units of the bin nearest 550 nm: (G, G), (G, G/2), (G/2, G), (G/4, G/4).
std::vector<FitDiagnostic> fit_diagnostic_units(const CharacterizeSettings& s);
// fit-patterns.csv, fit-summary.txt and fit-patterns.png (simulated mean pattern U vs the fit) in `dir`.
void write_fit_diagnostics(const std::filesystem::path& dir, const CharacterizeSettings& s,
                           const std::vector<FitDiagnostic>& units, const std::string& summary);

}  // namespace plumage
