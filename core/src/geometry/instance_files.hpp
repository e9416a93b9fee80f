// The files of imported instances (structure generators xsec_file and svg_file): a pattern in
// which {index} stands for the instance index, a single file for every instance, or a list whose
// n-th file is instance n; relative to the config's folder.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "plumage/error.hpp"
#include "plumage/params.hpp"

namespace plumage {

// The config's `files` (a text or a list of texts), refused by name when absent, empty or naming
// an empty file; `what` says which files ("the .xsec files").
inline std::vector<std::string> read_file_names(const ParamView& p, const std::string& what) {
  if (!p.has("files")) p.fail("files", "required: " + what + " of the instances");
  std::vector<std::string> out;
  const ParamView v = p.node("files");
  if (v.is_sequence()) {
    for (const ParamView& item : v.items()) out.push_back(item.scalar_text());
    if (out.empty()) p.fail("files", "the list of " + what + " is empty");
  } else {
    out.push_back(v.scalar_text());
  }
  for (const std::string& f : out) {
    if (f.empty()) p.fail("files", "an empty file name");
  }
  return out;
}

class InstanceFiles {
 public:
  InstanceFiles() = default;
  InstanceFiles(const std::vector<std::string>& names, const std::filesystem::path& config_dir, std::string generator)
      : generator_(std::move(generator)) {
    for (const std::string& f : names) files_.push_back(config_dir / f);
    // A name in a list stands for itself; a single name without {index} is every instance.
    pattern_ = files_.size() == 1 && names.front().find(kIndexField) != std::string::npos;
  }

  // The files to check when the config is read (the first of a pattern, every listed one).
  std::size_t checked_count() const { return pattern_ ? 1 : files_.size(); }

  std::filesystem::path of(std::uint64_t index) const {
    if (!pattern_) {
      if (files_.size() == 1) return files_.front();
      if (index >= files_.size()) {
        throw Error(generator_ + ": instance " + std::to_string(index) + " asked for, but `files` lists " +
                    std::to_string(files_.size()) + " (ask for at most that many instances)");
      }
      return files_[index];
    }
    std::string name = files_.front().string();
    for (std::size_t at = name.find(kIndexField); at != std::string::npos; at = name.find(kIndexField, at)) {
      const std::string n = std::to_string(index);
      name.replace(at, kIndexField.size(), n);
      at += n.size();
    }
    return name;
  }

 private:
  static constexpr std::string_view kIndexField = "{index}";
  std::vector<std::filesystem::path> files_;
  std::string generator_;
  bool pattern_ = false;
};

}  // namespace plumage
