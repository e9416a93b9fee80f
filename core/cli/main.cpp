// `plumage`: the command-line front end. Exit status 0 on success, 2 for bad input (config,
// plug-in, command line, an output path that would destroy something, or a job over its memory or
// work budget; nothing is written), 1
// for any other failure.
#include <iostream>

#include "commands.hpp"
#include "plumage/atomic_file.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/error.hpp"
#include "plumage/input_file.hpp"
#include "plumage/memory_budget.hpp"
#include "plumage/version.hpp"

int main(int argc, char** argv) {
  using namespace plumage::cli;
  AppContext context;
  CLI::App app{"plumage: appearance of iridescent bird feathers from their nanostructure"};
  app.set_version_flag("--version", std::string("plumage ") + plumage::kVersionString +
                                        " (plug-in ABI " + std::to_string(plumage::kAbiVersion) + ")");
  app.add_option("--plugin-path", context.plugin_dirs,
                 "Extra folder(s) searched first for plug-ins (then $PLUMAGE_PLUGIN_PATH, "
                 "beside the executable, the install prefix)");
  app.add_flag("-q,--quiet", context.quiet, "No progress or warnings on stderr");
  app.add_option("--tables", context.tables,
                 "Tables of the preparation step (crystal reflection tables): build (load or build as "
                 "configured), preview (a 4 x 5 x 5 preview table instead: a test shortcut, recorded as a "
                 "warning in every file) or never (refuse to build)")
      ->check(CLI::IsMember({"build", "preview", "never"}))
      ->capture_default_str();
  app.add_option("--max-memory", context.max_memory,
                 "Memory budget of every solver and builder, e.g. 8GiB, 512MiB, 2GB (default: what the "
                 "machine has: MemAvailable and any cgroup limit, whichever is smaller); a job whose estimated "
                 "peak is larger is refused before it starts (exit status 2)");
  // Global options may follow the subcommand (`plumage characterize ... --tables preview`).
  app.fallthrough();
  app.require_subcommand(1);
  // Warnings (plumage/diagnostics.hpp) are echoed on stderr unless --quiet.
  app.parse_complete_callback([&context] {
    if (context.quiet) plumage::diagnostics().set_echo(nullptr);
    context.apply_budget_and_progress();
  });

  add_plugins_command(app, context);
  add_check_command(app, context);
  add_multilayer_command(app, context);
  add_spectra_command(app, context);
  add_fit_command(app, context);
  add_simulate_command(app, context);
  add_bench_command(app, context);
  add_geometry_command(app, context);
  add_table_command(app, context);
  add_compare_command(app, context);
  add_characterize_command(app, context);
  add_brdf_command(app, context);
  add_merge_command(app, context);
  add_materials_command(app, context);
  add_render_command(app, context);
  // `bench` hands everything after it to the benchmark (prefix command): nothing falls through.
  app.get_subcommand("bench")->fallthrough(false);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const plumage::ConfigError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const plumage::PluginError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const plumage::InputFileError& e) {  // a damaged or wrong input file
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const plumage::OutputPathError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const plumage::MemoryBudgetError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const UsageError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
