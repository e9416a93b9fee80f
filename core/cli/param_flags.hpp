// Plug-in parameters from command-line flags (issue 22): a flag per row of the plug-in's own
// parameter table, so the table's defaults, ranges and docs hold on the command line too.
//   --width-um 5,10        width_um: [5, 10]        (type list or interval: comma-separated)
//   --bem ppw=12 --bem method=gmres   bem: {ppw: 12, method: gmres}   (type map: key=value, repeatable)
//   --quick                quick: true              (type bool, no value)
//   --lambda-nm=550        lambda_nm: 550
#pragma once

#include <string>
#include <vector>

#include "plumage/plugin.hpp"

namespace plumage::cli {

// The YAML map of the flags in `args` (all of them must name a parameter of `specs`; an unknown
// flag is a UsageError with the nearest name). Values are passed as quoted YAML scalars, so the
// table's reader checks and converts them and its errors name the parameter.
std::string flags_to_yaml(const std::vector<ParamSpec>& specs, const std::vector<std::string>& args);

// "  --name VALUE  (unit, default D, range R) meaning" per parameter, for --help.
std::string flags_help(const std::vector<ParamSpec>& specs);

}  // namespace plumage::cli
