#include "param_flags.hpp"

#include <algorithm>
#include <map>
#include <sstream>

#include "app_context.hpp"
#include "plumage/params.hpp"

namespace plumage::cli {

namespace {

std::string yaml_quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

std::string flag_of(const std::string& name) {
  std::string f = name;
  std::replace(f.begin(), f.end(), '_', '-');
  return "--" + f;
}

std::string list_of(const std::string& value) {
  std::string out = "[";
  std::size_t start = 0;
  for (bool first = true;; first = false) {
    const std::size_t comma = value.find(',', start);
    out += (first ? "" : ", ") + yaml_quoted(value.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out + "]";
}

}  // namespace

std::string flags_to_yaml(const std::vector<ParamSpec>& specs, const std::vector<std::string>& args) {
  std::map<std::string, const ParamSpec*> by_flag;
  std::vector<std::string> flags;
  for (const ParamSpec& p : specs) {
    if (p.name.find('.') != std::string::npos) continue;  // nested rows are set through their map
    by_flag[flag_of(p.name)] = &p;
    flags.push_back(flag_of(p.name));
  }
  std::map<std::string, std::string> scalars;                        // name -> YAML value
  std::map<std::string, std::vector<std::pair<std::string, std::string>>> maps;  // name -> key=value
  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string flag = args[i], value;
    bool has_value = false;
    if (const auto eq = flag.find('='); eq != std::string::npos && flag.rfind("--", 0) == 0) {
      value = flag.substr(eq + 1);
      flag = flag.substr(0, eq);
      has_value = true;
    }
    const auto it = by_flag.find(flag);
    if (it == by_flag.end()) {
      std::string msg = "unknown option '" + flag + "'";
      if (auto near = nearest_name(flag, flags)) msg += " (did you mean '" + *near + "'?)";
      throw UsageError(msg);
    }
    const ParamSpec& p = *it->second;
    if (p.type == "bool" && !has_value) {
      scalars[p.name] = "true";
      continue;
    }
    if (!has_value) {
      if (i + 1 >= args.size()) throw UsageError(flag + ": needs a value");
      value = args[++i];
    }
    if (p.type == "map") {
      const auto eq = value.find('=');
      if (eq == std::string::npos || eq == 0) throw UsageError(flag + ": expected key=value, got '" + value + "'");
      maps[p.name].emplace_back(value.substr(0, eq), value.substr(eq + 1));
    } else if (p.type == "list" || p.type == "interval") {
      scalars[p.name] = list_of(value);
    } else {
      scalars[p.name] = yaml_quoted(value);
    }
  }
  std::ostringstream yaml;
  yaml << "{";
  bool first = true;
  for (const auto& [name, value] : scalars) {
    yaml << (first ? "" : ", ") << name << ": " << value;
    first = false;
  }
  for (const auto& [name, entries] : maps) {
    yaml << (first ? "" : ", ") << name << ": {";
    for (std::size_t k = 0; k < entries.size(); ++k)
      yaml << (k ? ", " : "") << yaml_quoted(entries[k].first) << ": " << yaml_quoted(entries[k].second);
    yaml << "}";
    first = false;
  }
  yaml << "}";
  return yaml.str();
}

std::string flags_help(const std::vector<ParamSpec>& specs) {
  std::ostringstream out;
  for (const ParamSpec& p : specs) {
    if (p.name.find('.') != std::string::npos) continue;
    out << "  " << flag_of(p.name) << (p.type == "bool" ? "" : p.type == "map" ? " KEY=VALUE" : " VALUE") << "  ("
        << p.type;
    if (!p.unit.empty() && p.unit != "-" && p.unit != "1") out << ", " << p.unit;
    out << ", default " << p.default_value;
    if (!p.range.empty()) out << ", " << p.range;
    out << ")\n      " << p.meaning << "\n";
  }
  return out.str();
}

}  // namespace plumage::cli
