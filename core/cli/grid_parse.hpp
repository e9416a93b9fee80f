// Parsing of sample lists on the command line: "400:700:10" (from:to:step, inclusive) and
// "0,30,60" (explicit values), or a mix "0,10:30:10".
#pragma once

#include <string_view>
#include <string>
#include <vector>

namespace plumage::cli {

// Throws UsageError naming `option` and the offending text.
std::vector<double> parse_samples(std::string_view text, std::string_view option);
// parse_samples for wavelengths: each within the declared range of every wavelength
// (Limits::wavelength_nm, params.hpp), else a UsageError naming `option`.
std::vector<double> parse_wavelengths(std::string_view text, std::string_view option);

}  // namespace plumage::cli
