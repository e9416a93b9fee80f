#include "grid_parse.hpp"

#include <charconv>
#include <cmath>
#include <string>

#include "app_context.hpp"
#include "plumage/param_table.hpp"

namespace plumage::cli {

namespace {

double to_double(std::string_view s, std::string_view option, std::string_view whole) {
  double v = 0;
  auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || ptr != s.data() + s.size() || !std::isfinite(v)) {
    throw UsageError(std::string(option) + ": '" + std::string(s) + "' in '" + std::string(whole) +
                     "' is not a number");
  }
  return v;
}

}  // namespace

std::vector<double> parse_samples(std::string_view text, std::string_view option) {
  std::vector<double> out;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t comma = text.find(',', start);
    std::string_view item = text.substr(start, comma == std::string_view::npos ? text.npos : comma - start);
    if (item.empty()) throw UsageError(std::string(option) + ": empty entry in '" + std::string(text) + "'");
    std::size_t c1 = item.find(':');
    if (c1 == std::string_view::npos) {
      out.push_back(to_double(item, option, text));
    } else {
      std::size_t c2 = item.find(':', c1 + 1);
      if (c2 == std::string_view::npos) {
        throw UsageError(std::string(option) + ": a range is written from:to:step, got '" +
                         std::string(item) + "'");
      }
      double from = to_double(item.substr(0, c1), option, text);
      double to = to_double(item.substr(c1 + 1, c2 - c1 - 1), option, text);
      double step = to_double(item.substr(c2 + 1), option, text);
      if (!(step > 0) || to < from) {
        throw UsageError(std::string(option) + ": range '" + std::string(item) +
                         "' needs from <= to and step > 0");
      }
      const long n = std::lround(std::floor((to - from) / step + 1e-9));
      if (n > 1'000'000) throw UsageError(std::string(option) + ": range has too many samples");
      for (long i = 0; i <= n; ++i) out.push_back(from + static_cast<double>(i) * step);
    }
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

std::vector<double> parse_wavelengths(std::string_view text, std::string_view option) {
  std::vector<double> out = parse_samples(text, option);
  const Limits range = Limits::wavelength_nm();
  for (double l : out) {
    if (!range.admits(l)) {
      throw UsageError(std::string(option) + ": wavelength " + format_param_number(l) + " nm is out of range: must be " +
                       range.describe());
    }
  }
  return out;
}

}  // namespace plumage::cli
