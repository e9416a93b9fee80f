#include "plumage/materials.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace plumage {

namespace {

std::string trim(std::string_view s) {
  std::size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  return std::string(s.substr(a, b - a));
}

std::string format_complex(Complex n) {
  std::ostringstream os;
  os << n.real();
  if (n.imag() != 0.0) os << "+" << n.imag() << "i";
  return os.str();
}

std::optional<Material> named_material(std::string_view name) {
  if (name == "air") return Material::air();
  if (name == "keratin") return Material::keratin();
  if (name == "melanin") return Material::melanin();
  return std::nullopt;
}

bool parse_double(std::string_view s, double& out) {
  const char* first = s.data();
  const char* last = s.data() + s.size();
  auto [ptr, ec] = std::from_chars(first, last, out);
  return ec == std::errc() && ptr == last;
}

}  // namespace

Material::Material() = default;

Material Material::air() { return Material(); }

Material Material::keratin() {
  Material m;
  m.kind_ = Kind::keratin;
  return m;
}

Material Material::melanin() {
  Material m;
  m.kind_ = Kind::melanin;
  return m;
}

Material Material::constant(Complex index) {
  if (!(index.real() > 0.0) || index.imag() < 0.0 || !std::isfinite(index.real()) ||
      !std::isfinite(index.imag())) {
    throw std::invalid_argument("refractive index " + format_complex(index) +
                                " is not a passive medium (need Re n > 0 and Im n >= 0)");
  }
  Material m;
  m.kind_ = Kind::constant;
  m.value_ = index;
  return m;
}

Material Material::mixture(const Material& host, const Material& guest, double guest_fraction) {
  if (!(guest_fraction >= 0.0 && guest_fraction <= 1.0)) {
    throw std::invalid_argument("mixture fraction must be in [0, 1]");
  }
  Material m;
  m.kind_ = Kind::mixture;
  m.fraction_ = guest_fraction;
  m.parts_ = std::make_shared<const std::vector<Material>>(std::vector<Material>{host, guest});
  return m;
}

Complex Material::index(double lambda_nm) const {
  switch (kind_) {
    case Kind::air:
      return {1.0, 0.0};
    case Kind::keratin:  // paper Eq. 1
      return {1.532 + 5890.0 / (lambda_nm * lambda_nm), 0.0};
    case Kind::melanin:  // paper Eq. 1
      return {1.648 + 23700.0 / (lambda_nm * lambda_nm), 0.56 * std::exp(-lambda_nm / 270.0)};
    case Kind::constant:
      return value_;
    case Kind::mixture:
      return (1.0 - fraction_) * (*parts_)[0].index(lambda_nm) +
             fraction_ * (*parts_)[1].index(lambda_nm);
  }
  return {1.0, 0.0};
}

std::string Material::name() const {
  switch (kind_) {
    case Kind::air:
      return "air";
    case Kind::keratin:
      return "keratin";
    case Kind::melanin:
      return "melanin";
    case Kind::constant:
      return format_complex(value_);
    case Kind::mixture: {
      std::ostringstream os;
      os << "mix(" << (*parts_)[0].name() << ", " << (*parts_)[1].name() << ", " << fraction_
         << ")";
      return os.str();
    }
  }
  return "?";
}

Material Material::with_fraction(double guest_fraction) const {
  if (kind_ != Kind::mixture) throw std::logic_error("with_fraction on a material that is not a mixture");
  return mixture((*parts_)[0], (*parts_)[1], guest_fraction);
}

std::vector<std::string> material_names() { return {"air", "keratin", "melanin"}; }

Material parse_material(const ParamView& node) {
  if (node.is_scalar()) {
    std::string word = node.scalar_text();
    if (auto m = named_material(word)) return *m;
    std::string msg = "unknown material '" + word + "'";
    auto names = material_names();
    if (auto near = nearest_name(word, names)) msg += " (did you mean '" + *near + "'?)";
    msg += "; use air, keratin, melanin, {n: .., k: ..} or {mix: [a, b], fraction: f}";
    node.fail_here(msg);
  }
  if (!node.is_map()) node.fail_here("expected a material name or map");
  if (node.has("mix")) {
    auto parts = node.items("mix");
    if (parts.size() != 2) node.fail("mix", "expected two materials [host, guest]");
    Material host = parse_material(parts[0]);
    Material guest = parse_material(parts[1]);
    double f = node.number("fraction", Limits::unit_interval());
    node.finish();
    return Material::mixture(host, guest, f);
  }
  double n = node.number("n", Limits::positive());
  double k = node.number_or("k", 0.0, Limits::non_negative());
  node.finish();
  return Material::constant({n, k});
}

Material parse_material(const ParamView& parent, std::string_view key) {
  return parse_material(parent.node(key));
}

Material parse_material_text(std::string_view raw) {
  const std::string text = trim(raw);
  if (text.empty()) throw std::invalid_argument("empty material");
  if (auto m = named_material(text)) return *m;
  if (text.rfind("mix(", 0) == 0 && text.back() == ')') {
    std::string inner = text.substr(4, text.size() - 5);
    std::vector<std::string> parts;
    std::stringstream ss(inner);
    for (std::string p; std::getline(ss, p, ',');) parts.push_back(trim(p));
    if (parts.size() != 3) {
      throw std::invalid_argument("'" + text + "': expected mix(host, guest, fraction)");
    }
    double f = 0;
    if (!parse_double(parts[2], f)) {
      throw std::invalid_argument("'" + text + "': fraction '" + parts[2] + "' is not a number");
    }
    return Material::mixture(parse_material_text(parts[0]), parse_material_text(parts[1]), f);
  }
  // "1.5", "1.5+0.01i", "1.5-0.01i" (the last is refused as gain by Material::constant).
  double re = 0, im = 0;
  if (parse_double(text, re)) return Material::constant({re, 0.0});
  if (text.back() == 'i' || text.back() == 'j') {
    std::string body = text.substr(0, text.size() - 1);
    auto split = body.find_first_of("+-", 1);
    while (split != std::string::npos && (body[split - 1] == 'e' || body[split - 1] == 'E')) {
      split = body.find_first_of("+-", split + 1);
    }
    if (split != std::string::npos && parse_double(body.substr(0, split), re)) {
      std::string imag = body.substr(body[split] == '+' ? split + 1 : split);
      if (parse_double(imag, im)) return Material::constant({re, im});
    }
  }
  std::string msg = "unknown material '" + text + "'";
  auto names = material_names();
  if (auto near = nearest_name(text, names)) msg += " (did you mean '" + *near + "'?)";
  throw std::invalid_argument(msg + "; use air, keratin, melanin, 1.5+0.01i or mix(a,b,f)");
}

}  // namespace plumage
