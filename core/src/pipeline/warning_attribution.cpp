// Warning codes per work group and the material's warnings (warning_attribution.hpp).
#include "warning_attribution.hpp"

#include <sstream>
#include <utility>

#include "plumage/diagnostics.hpp"

namespace plumage {

RaiseCounts raise_counts() {
  RaiseCounts counts;
  for (const Warning& w : diagnostics().warnings()) counts[w.code] = w.count;
  return counts;
}

std::set<std::string> raised_since(const RaiseCounts& before) {
  std::set<std::string> codes;
  for (const auto& [code, count] : raise_counts()) {
    const auto it = before.find(code);
    if (it == before.end() || it->second < count) codes.insert(code);
  }
  return codes;
}

// The messages with their numbers went to the computing processes' stderr; the material keeps
// where each code was raised.
std::string material_warnings(const CharacterizeSettings& s, const std::vector<const GroupRecord*>& groups) {
  std::map<std::string, std::pair<std::size_t, const GroupRecord*>> by_code;
  for (const GroupRecord* r : groups) {
    for (const std::string& code : r->warnings) {
      auto& [count, first] = by_code[code];
      ++count;
      if (!first || std::make_pair(r->w, r->a) < std::make_pair(first->w, first->a)) first = r;
    }
  }
  std::ostringstream out;
  for (const auto& [code, entry] : by_code) {
    out << code << ": raised while computing " << entry.first << " of " << groups.size()
        << " work groups, first at lambda = " << s.lambda_nm[entry.second->w] << " nm, cos theta_i = "
        << entry.second->a << "/" << s.grid << "\n";
  }
  return out.str();
}

void relay_rank_warnings(int rank, const std::string& summary) {
  std::istringstream lines(summary);
  for (std::string line; std::getline(lines, line);) {
    const auto colon = line.find(": ");
    if (colon == std::string::npos) continue;
    warn(line.substr(0, colon), "rank " + std::to_string(rank) + ": " + line.substr(colon + 2));
  }
}

}  // namespace plumage
