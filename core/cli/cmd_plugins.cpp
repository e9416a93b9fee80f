// `plumage plugins` and `plumage plugins describe <type>`.
#include <iomanip>
#include <iostream>

#include "commands.hpp"
#include "plumage/atomic_file.hpp"
#include "plumage/config_sections.hpp"

namespace plumage::cli {

namespace {

void list_plugins(AppContext& context) {
  const auto& registry = context.registry();
  std::cout << std::left << std::setw(20) << "KIND" << std::setw(20) << "TYPE" << std::setw(10)
            << "VERSION" << "LIBRARY\n";
  for (const auto& e : registry.entries()) {
    std::cout << std::setw(20) << e.info.kind << std::setw(20) << e.info.type << std::setw(10)
              << e.info.version << (e.library.empty() ? "(core)" : e.library.string()) << "\n";
  }
  if (registry.entries().empty()) std::cout << "(no plug-ins found)\n";
  std::cout << "\nsearched:\n";
  for (const auto& d : PluginRegistry::search_path(context.plugin_dirs)) {
    std::cout << "  " << d.string() << "\n";
  }
  for (const auto& p : registry.problems()) std::cout << "problem: " << p.message << "\n";
}

void describe_plugin(AppContext& context, const std::string& type) {
  const auto& registry = context.registry();
  const auto* entry = registry.find_any_kind(type);
  if (!entry) {
    std::vector<std::string> all;
    for (const auto& e : registry.entries()) all.push_back(e.info.type);
    std::string msg = "no plug-in type '" + type + "'";
    if (auto near = nearest_name(type, all)) msg += " (did you mean '" + *near + "'?)";
    throw UsageError(msg + "; see `plumage plugins`");
  }
  const auto& info = entry->info;
  std::cout << info.type << " (" << info.kind << ", version " << info.version << ")\n"
            << "  " << info.summary << "\n"
            << "  library: " << (entry->library.empty() ? "(core)" : entry->library.string())
            << "\n\n";
  if (info.params.empty()) {
    std::cout << "  no parameters\n";
    return;
  }
  std::size_t wn = 4, wt = 4, wu = 4, wd = 7, wr = 5;
  for (const auto& p : info.params) {
    wn = std::max(wn, p.name.size());
    wt = std::max(wt, p.type.size());
    wu = std::max(wu, p.unit.size());
    wd = std::max(wd, p.default_value.size());
    wr = std::max(wr, p.range.size());
  }
  auto row = [&](const std::string& a, const std::string& b, const std::string& c, const std::string& d,
                 const std::string& r, const std::string& e) {
    std::cout << "  " << std::left << std::setw(static_cast<int>(wn + 2)) << a << std::setw(static_cast<int>(wt + 2))
              << b << std::setw(static_cast<int>(wu + 2)) << c << std::setw(static_cast<int>(wd + 2)) << d
              << std::setw(static_cast<int>(wr + 2)) << r << e << "\n";
  };
  row("NAME", "TYPE", "UNIT", "DEFAULT", "RANGE", "MEANING");
  for (const auto& p : info.params)
    row(p.name, p.type, p.unit, p.default_value, p.range, p.condition.empty() ? p.meaning : "(" + p.condition + ") " + p.meaning);
}

}  // namespace

void add_plugins_command(CLI::App& app, AppContext& context) {
  auto* cmd = app.add_subcommand("plugins", "List the plug-ins found (kind, type, version, library)");
  auto* describe = cmd->add_subcommand("describe", "Print a plug-in's parameter table (or all of them as markdown)");
  auto type = std::make_shared<std::string>();
  auto markdown = std::make_shared<bool>(false);
  auto out = std::make_shared<std::string>();
  describe->add_option("type", *type, "Plug-in type name, e.g. multilayer");
  describe->add_flag("--markdown", *markdown,
                     "Every config section and plug-in type as markdown (docs/parameters.md)");
  describe->add_option("--out", *out, "With --markdown: write this file instead of stdout");
  describe->callback([&context, type, markdown, out] {
    if (*markdown) {
      if (!type->empty()) throw UsageError("--markdown describes every type; give no type with it");
      check_output_flag("--out", *out);
      const std::string text = parameters_markdown(context.registry());
      if (out->empty()) std::cout << text;
      else write_text_atomically(*out, text);
      return;
    }
    if (type->empty()) throw UsageError("describe: give a plug-in type (see `plumage plugins`) or --markdown");
    describe_plugin(context, *type);
  });
  cmd->callback([&context, cmd] {
    if (cmd->get_subcommands().empty()) list_plugins(context);
  });
}

}  // namespace plumage::cli
