// `plumage fit SPEC --out DIR`: fit nanostructure parameters of a species or crystal file to a
// measured spectrum or target reflectances (plumage/structure_fit.hpp).
#include <iostream>

#include "commands.hpp"
#include "plumage/structure_fit.hpp"

namespace plumage::cli {

namespace {

struct Options {
  std::string spec;
  std::string out;
  bool no_plot = false;
};

void run(AppContext& context, const Options& o) {
  // The spec, its model's file and its targets are all checked before any fitting.
  const FitSpec spec = load_fit_spec(o.spec, context.registry());
  const auto model = make_forward_model(spec, context.registry());
  if (!context.quiet) std::cerr << "fit: " << model->description() << ", " << spec.starts << " start(s)\n";
  const FitResult result = fit_structure(spec, *model, [&](std::size_t done, std::size_t total) {
    if (!context.quiet) std::cerr << "fit: start " << done << "/" << total << " done\n";
  });
  const std::vector<std::string> written = write_fit_outputs(spec, *model, result, o.out, !o.no_plot);
  std::cout << fit_summary_text(spec, *model, result);
  std::string list;
  for (const std::string& f : written) list += (list.empty() ? "" : ",") + f;
  if (!context.quiet) std::cerr << "wrote " << o.out << "/{" << list << "}\n";
}

}  // namespace

void add_fit_command(CLI::App& app, AppContext& context) {
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("fit", "Fit nanostructure parameters to a measured spectrum (fit spec YAML)");
  cmd->add_option("spec", o->spec, "Fit spec YAML (docs/formats.md, \"Fit spec\")")->required();
  cmd->add_option("--out", o->out, "Output folder (fit.txt, fit.csv, fit.png, fitted.yaml, ...)")->required();
  cmd->add_flag("--no-plot", o->no_plot, "Do not draw fit.png");
  cmd->callback([&context, o] { run(context, *o); });
}

}  // namespace plumage::cli
