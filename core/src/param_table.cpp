// Text of parameter defaults for the declarations of param_table.hpp.
#include "plumage/param_table.hpp"

#include <charconv>
#include <cmath>

namespace plumage {

std::string format_param_number(double value) {
  char buffer[64];
  // Whole numbers in full (100000, not the shorter 1e+05), others in shortest round-trip form.
  if (std::abs(value) < 1e15 && value == std::trunc(value)) {
    const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, static_cast<long long>(value));
    return ec == std::errc() ? std::string(buffer, end) : std::string("?");
  }
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return ec == std::errc() ? std::string(buffer, end) : std::string("?");
}

std::string format_param_interval(std::pair<double, double> value) {
  // Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) on "[" + std::string.
  std::string out = "[";
  out += format_param_number(value.first);
  out += ", ";
  out += format_param_number(value.second);
  return out += "]";
}

std::string format_param_numbers(const std::vector<double>& values) {
  std::string out = "[";
  for (std::size_t k = 0; k < values.size(); ++k) out += (k ? ", " : "") + format_param_number(values[k]);
  return out + "]";
}

}  // namespace plumage
