// Subcommands of the `plumage` executable; each file cmd_<name>.cpp adds one.
#pragma once

#include <CLI/CLI.hpp>

#include "app_context.hpp"

namespace plumage::cli {

void add_plugins_command(CLI::App& app, AppContext& context);
void add_check_command(CLI::App& app, AppContext& context);
void add_multilayer_command(CLI::App& app, AppContext& context);
void add_spectra_command(CLI::App& app, AppContext& context);
void add_bench_command(CLI::App& app, AppContext& context);
void add_simulate_command(CLI::App& app, AppContext& context);
void add_geometry_command(CLI::App& app, AppContext& context);
void add_table_command(CLI::App& app, AppContext& context);  // cmd_table.cpp
// `bench geometry` (bench_geometry.cpp), added under the `bench` subcommand.
void add_bench_geometry_command(CLI::App& bench, AppContext& context);
void add_bench_fdtd_command(CLI::App& bench, AppContext& context);  // bench_fdtd.cpp

}  // namespace plumage::cli
