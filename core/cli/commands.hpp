// Subcommands of the `plumage` executable; each file cmd_<name>.cpp adds one.
#pragma once

#include <CLI/CLI.hpp>

#include "app_context.hpp"

namespace plumage::cli {

void add_plugins_command(CLI::App& app, AppContext& context);
void add_check_command(CLI::App& app, AppContext& context);
void add_multilayer_command(CLI::App& app, AppContext& context);
void add_spectra_command(CLI::App& app, AppContext& context);
void add_fit_command(CLI::App& app, AppContext& context);  // cmd_fit.cpp (issue 25 part 3)
void add_bench_command(CLI::App& app, AppContext& context);
void add_simulate_command(CLI::App& app, AppContext& context);
void add_geometry_command(CLI::App& app, AppContext& context);
void add_table_command(CLI::App& app, AppContext& context);  // cmd_table.cpp
void add_compare_command(CLI::App& app, AppContext& context);       // cmd_compare.cpp
void add_characterize_command(CLI::App& app, AppContext& context);  // cmd_characterize.cpp
void add_merge_command(CLI::App& app, AppContext& context);         // cmd_merge.cpp
void add_brdf_command(CLI::App& app, AppContext& context);          // cmd_brdf.cpp
void add_materials_command(CLI::App& app, AppContext& context);     // cmd_materials.cpp (issue 26)
void add_render_command(CLI::App& app, AppContext& context);        // cmd_render.cpp (issue 8)

}  // namespace plumage::cli
