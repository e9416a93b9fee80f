// Characterisation settings: the material key and the fingerprint that heads journals and shard
// files (characterize_settings.hpp).
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>

#include "plumage/characterize_settings.hpp"
#include "plumage/config_document.hpp"
#include "plumage/error.hpp"
#include "plumage/fitter.hpp"

namespace plumage {

namespace {

std::string hexfloat(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%a", v);
  return b;
}

// The numbers of the settings, exact: the same text in the key and the fingerprint.
std::string numbers(const CharacterizeSettings& s) {
  std::ostringstream o;
  o << "instances=" << s.instances << " grid=" << s.grid << " lambda_nm=";
  for (std::size_t k = 0; k < s.lambda_nm.size(); ++k) o << (k ? "," : "") << hexfloat(s.lambda_nm[k]);
  o << " bin_width_nm=" << hexfloat(s.bin_width_nm) << " pattern=" << s.pattern_samples
    << " projected=" << s.projected_samples << " jitter_deg=" << hexfloat(s.jitter_deg) << " sigma=" << hexfloat(s.sigma)
    << " noise_functions=" << s.noise_functions;
  return o.str();
}

}  // namespace

std::string CharacterizeSettings::key_text() const {
  std::ostringstream o;
  o << "plumage material key 1\nlabel " << label << "\n" << inputs << "fit_revision " << kFitRevision << "\nfidelity "
    << fidelity << "\nsettings " << numbers(*this) << "\n";
  return o.str();
}

std::string CharacterizeSettings::key() const { return fnv1a_hex(key_text()); }

std::string CharacterizeSettings::fingerprint() const {
  return "fit_revision=" + std::to_string(kFitRevision) + " label=" + label + " key=" + key() + " variant=" + variant +
         " fidelity=" + fidelity + " " + numbers(*this);
}

CharacterizeSettings CharacterizeSettings::from_fingerprint(const std::string& line, const std::string& config_hash,
                                                            const std::string& inputs) {
  std::map<std::string, std::string> kv;
  std::istringstream in(line);
  std::string token;
  while (in >> token) {
    const auto eq = token.find('=');
    if (eq == std::string::npos) throw Error("characterisation header: bad field '" + token + "'");
    kv[token.substr(0, eq)] = token.substr(eq + 1);
  }
  auto field = [&](const char* k) -> const std::string& {
    auto it = kv.find(k);
    if (it == kv.end()) throw Error(std::string("characterisation header: missing field ") + k);
    return it->second;
  };
  auto num = [&](const char* k) { return std::strtod(field(k).c_str(), nullptr); };
  // A damaged header is refused with the field named, not with std::stoi's bare "stoi" (an
  // uncaught std::invalid_argument, found by fuzz/fuzz_merge); the key and round-trip checks
  // below catch the rest.
  auto integer = [&](const char* k) {
    const std::string& v = field(k);
    int value = 0;
    const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), value);
    if (v.empty() || ec != std::errc() || end != v.data() + v.size())
      throw Error(std::string("characterisation header: field ") + k + ": '" + v + "' is not an integer");
    return value;
  };
  CharacterizeSettings s;
  if (field("fit_revision") != std::to_string(kFitRevision))
    throw Error("characterisation records of fit revision " + field("fit_revision") + ", this build writes " +
                std::to_string(kFitRevision) + ": recompute them");
  s.label = field("label");
  s.config_hash = config_hash;
  s.variant = field("variant");
  s.inputs = inputs;
  s.fidelity = field("fidelity");
  s.instances = integer("instances");
  s.grid = integer("grid");
  std::istringstream l(field("lambda_nm"));
  for (std::string v; std::getline(l, v, ',');) s.lambda_nm.push_back(std::strtod(v.c_str(), nullptr));
  s.bin_width_nm = num("bin_width_nm");
  s.pattern_samples = integer("pattern");
  s.projected_samples = integer("projected");
  s.jitter_deg = num("jitter_deg");
  s.sigma = num("sigma");
  s.noise_functions = integer("noise_functions");
  if (s.key() != field("key")) throw Error("characterisation header: its key does not match its inputs and settings");
  if (s.fingerprint() != line) throw Error("characterisation header does not round-trip: " + line);
  return s;
}

}  // namespace plumage
