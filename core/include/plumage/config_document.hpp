// A configuration file (species, crystal, scene...) parsed into a ParamView tree.
#pragma once

#include <filesystem>
#include <string>

#include "plumage/params.hpp"

namespace plumage {

class ConfigDocument {
 public:
  // Reads and parses a YAML file. A missing file or a syntax error throws ConfigError.
  static ConfigDocument load(const std::filesystem::path& file);
  // Parses YAML text held in memory; `name` stands for the file name in messages.
  static ConfigDocument parse(const std::string& text, const std::string& name);

  ParamView root() const { return root_; }
  const std::filesystem::path& path() const { return path_; }
  // Folder against which relative file names inside the document are resolved.
  std::filesystem::path directory() const;
  // Hex digest of the file's bytes: part of every cache key derived from this config.
  const std::string& content_hash() const { return hash_; }

 private:
  std::filesystem::path path_;
  std::string hash_;
  ParamView root_;
};

// Stable 64-bit FNV-1a digest, as 16 hex digits. Used for cache keys and file checksums.
std::string fnv1a_hex(std::string_view bytes);

}  // namespace plumage
