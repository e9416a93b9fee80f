// A configuration file (species, crystal, scene...) parsed into a ParamView tree.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "plumage/params.hpp"

namespace plumage {

class ConfigDocument {
 public:
  // Reads and parses a YAML file. A missing file or a syntax error throws ConfigError.
  static ConfigDocument load(const std::filesystem::path& file);
  // Parses YAML text held in memory; `name` stands for the file name in messages.
  static ConfigDocument parse(const std::string& text, const std::string& name);
  // A document made from `base` (a view into another document) with values replaced: each
  // override is (dotted path below `base`, YAML text of the new value). Built from yaml-cpp nodes,
  // not text: untouched values are the original nodes, so messages about them keep their file,
  // line and column; messages about a replaced value name the override's `source` instead.
  // A path must name an existing key unless `create` is set (then missing maps are made); a
  // missing one is a ConfigError naming the path. Relative file names resolve against `directory`.
  struct Override {
    std::string path;                  // "outline.width_um"
    std::string yaml;                  // "10", "{a: 1}", "[1, 2]"
    bool create = false;               // add the key (and any missing maps on the way) if absent
    std::string source = "override";   // where the value came from, e.g. "command line --width-um"
  };
  static ConfigDocument derive(const ParamView& base, const std::vector<Override>& overrides,
                               const std::filesystem::path& directory, const std::string& name);

  ParamView root() const { return root_; }
  const std::filesystem::path& path() const { return path_; }
  // Folder against which relative file names inside the document are resolved.
  std::filesystem::path directory() const;
  // Hex digest of the file's bytes: part of every cache key derived from this config.
  const std::string& content_hash() const { return hash_; }

 private:
  std::filesystem::path path_;
  std::filesystem::path directory_;  // set for derived documents
  std::string hash_;
  ParamView root_;
};

// Stable 64-bit FNV-1a digest, as 16 hex digits. Used for cache keys and file checksums.
std::string fnv1a_hex(std::string_view bytes);

// The meaning of a config subtree as one line of text, independent of comments, layout, quoting
// style and map key order (keys sorted): what a cache key hashes. "a: 1 # x" and "{a: '1'}" agree.
std::string canonical_text(const ParamView& view);

}  // namespace plumage
