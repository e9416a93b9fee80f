#include "segment_config.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <fstream>
#include <regex>
#include <sstream>

#include "commands.hpp"

namespace plumage::cli {

std::filesystem::path segment_config(const std::string& file, double width_um, const std::string& who) {
  std::ifstream in(file);
  if (!in) throw UsageError(who + ": cannot read " + file);
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  const auto outline = s.find("\n  outline:");
  if (outline == std::string::npos) throw UsageError(who + ": " + file + " has no structure.outline");
  std::string head = s.substr(0, outline), tail = s.substr(outline);
  tail = std::regex_replace(tail, std::regex("(\n    width_um:)[^\n]*"), "$1 " + std::to_string(width_um),
                            std::regex_constants::format_first_only);
  const double corner = std::min(1.0, 0.1 * width_um);
  tail = std::regex_replace(tail, std::regex("(\n    corner_um:)[^\n]*"), "$1 " + std::to_string(corner),
                            std::regex_constants::format_first_only);
  // The config has no relative references, so its copy may live anywhere; unique per call.
  static std::atomic<int> counter{0};
  const auto path = std::filesystem::temp_directory_path() /
                    ("plumage-segment-" + std::to_string(getpid()) + "-" + std::to_string(counter++) + ".yaml");
  std::ofstream(path) << head << tail;
  return path;
}

}  // namespace plumage::cli
