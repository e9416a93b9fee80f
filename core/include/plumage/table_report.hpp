// What `plumage table query|plot` show of a reflection table, in the library so that the command
// stays a shell: the Jones reflection at one (λ, θ, φ_local) as text or JSON, and the overview
// chart of |r|² over λ at a few in-plane and conical angles.
#pragma once

#include <filesystem>
#include <string>

#include "plumage/reflection_table.hpp"

namespace plumage {

enum class TableQueryFormat { text, json };

// The interpolated Jones reflection (and R_s, R_p, the table's notes) at (lambda_nm, theta_deg,
// phi_deg); `file` is named in the JSON.
std::string table_query_report(const ReflectionTable& table, const std::string& file, double lambda_nm,
                               double theta_deg, double phi_deg, TableQueryFormat format);

// |r_s|², |r_p|² over the table's λ range at angles 0, 20, 40, 60, 75° in-plane (φ_local) and
// conical (θ), one panel per polarization and kind, drawn to `png`.
void draw_table_overview(const ReflectionTable& table, const std::string& title_file, const std::filesystem::path& png);

}  // namespace plumage
