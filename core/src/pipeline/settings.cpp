// Characterisation settings: presets and the fingerprint that heads journals and shard files
// (characterize_settings.hpp).
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>

#include "plumage/characterize_settings.hpp"
#include "plumage/error.hpp"
#include "plumage/fitter.hpp"

namespace plumage {

namespace {

std::string hexfloat(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%a", v);
  return b;
}

}  // namespace

std::string CharacterizeSettings::fingerprint() const {
  std::ostringstream o;
  o << "fit_revision=" << kFitRevision << " label=" << label << " config_hash=" << config_hash << " variant=" << variant << " fidelity=" << fidelity
    << " instances=" << instances << " grid=" << grid << " lambda_nm=";
  for (std::size_t k = 0; k < lambda_nm.size(); ++k) o << (k ? "," : "") << hexfloat(lambda_nm[k]);
  o << " bin_width_nm=" << hexfloat(bin_width_nm) << " pattern=" << pattern_samples << " projected=" << projected_samples
    << " jitter_deg=" << hexfloat(jitter_deg) << " sigma=" << hexfloat(sigma) << " noise_functions=" << noise_functions;
  return o.str();
}

CharacterizeSettings CharacterizeSettings::from_fingerprint(const std::string& line) {
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
  CharacterizeSettings s;
  if (field("fit_revision") != std::to_string(kFitRevision))
    throw Error("characterisation records of fit revision " + field("fit_revision") + ", this build writes " +
                std::to_string(kFitRevision) + ": recompute them");
  s.label = field("label");
  s.config_hash = field("config_hash");
  s.variant = field("variant");
  s.fidelity = field("fidelity");
  s.instances = std::stoi(field("instances"));
  s.grid = std::stoi(field("grid"));
  std::istringstream l(field("lambda_nm"));
  for (std::string v; std::getline(l, v, ',');) s.lambda_nm.push_back(std::strtod(v.c_str(), nullptr));
  s.bin_width_nm = num("bin_width_nm");
  s.pattern_samples = std::stoi(field("pattern"));
  s.projected_samples = std::stoi(field("projected"));
  s.jitter_deg = num("jitter_deg");
  s.sigma = num("sigma");
  s.noise_functions = std::stoi(field("noise_functions"));
  if (s.fingerprint() != line) throw Error("characterisation header does not round-trip: " + line);
  return s;
}

}  // namespace plumage
