// Private to core: the shared state behind a ParamView (yaml-cpp never leaks into the SDK).
#pragma once

#include <yaml-cpp/yaml.h>

#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "plumage/params.hpp"
#include "plumage/plugin.hpp"

namespace plumage {

struct ParamView::State {
  YAML::Node node;
  std::string file;
  std::string path;
  std::set<std::string> known;
  std::vector<std::shared_ptr<State>> children;                // every view handed out
  std::map<std::string, std::shared_ptr<State>> child_by_key;  // one state per key
  std::vector<std::shared_ptr<State>> item_states;             // sequence items
  bool items_made = false;
  // The declarations read here, in reading order (ParamView::note); a key noted twice keeps its last row.
  std::vector<std::pair<ParamSpec, bool>> notes;
  // Values replaced in a derived document (ConfigDocument::derive) and where they came from, shared
  // by every view of that document: messages about them name their source, not a file position.
  std::shared_ptr<std::vector<std::pair<YAML::Node, std::string>>> overrides;

  std::shared_ptr<State> make_child(const YAML::Node& child_node, std::string child_path);
};

// A root view over a parsed document.
ParamView make_root_view(const YAML::Node& node, const std::string& file);

}  // namespace plumage
