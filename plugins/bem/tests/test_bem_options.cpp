// The bem solver's parameter table (src/bem_options.hpp): an empty section gives BemOptions{},
// every declared parameter is read into a field of its own, and ranges and words are checked
// with the parameter's name.
#include <catch2/catch.hpp>

#include <set>
#include <string>
#include <vector>

#include "bem_options.hpp"
#include "plumage/config_document.hpp"

using namespace plumage;
using namespace plumage::bem;

namespace {

// Every option the table may set, as numbers (the quadrature rules are not parameters).
std::vector<double> fingerprint(const BemOptions& o) {
  const HMatrixOptions& h = o.hmatrix;
  return {o.points_per_wavelength,
          o.corner_split_deg,
          static_cast<double>(o.incidence),
          static_cast<double>(o.method),
          o.window_fraction,
          static_cast<double>(o.max_dense_unknowns),
          static_cast<double>(o.max_dense_single_unknowns),
          o.gmres_tolerance,
          static_cast<double>(o.gmres_restart),
          static_cast<double>(o.gmres_max_iterations),
          h.aca_tolerance,
          h.eta,
          static_cast<double>(h.leaf_size),
          h.preconditioner_factor,
          static_cast<double>(h.preconditioner),
          o.warm_start ? 1.0 : 0.0,
          static_cast<double>(o.log_file.size()),
          o.warn_min_ppw,
          o.warn_gap_ratio,
          static_cast<double>(o.max_memory.size()),
          o.hodlr.tolerance,
          static_cast<double>(o.hodlr.leaf_size),
          static_cast<double>(o.hodlr.max_rank),
          static_cast<double>(o.gmres_block)};
}

// A value other than the default, of the parameter's type and within its range.
std::string other_value(const ParamSpec& spec) {
  if (spec.type == "number") return std::to_string(2.0 * std::stod(spec.default_value) + 1.0);
  if (spec.type == "integer") return std::to_string(std::stol(spec.default_value) + 1);
  if (spec.type == "bool") return spec.default_value == "true" ? "false" : "true";
  if (spec.type == "text") return "bem-timings.log";
  if (spec.type == "size") return "2GiB";  // max_memory
  REQUIRE(spec.type == "choice");
  for (std::size_t start = 0;;) {  // range "a | b | c"
    const std::size_t bar = spec.range.find(" | ", start);
    const std::string word = spec.range.substr(start, bar == std::string::npos ? std::string::npos : bar - start);
    if (word != spec.default_value) return word;
    REQUIRE(bar != std::string::npos);
    start = bar + 3;
  }
}

BemOptions read(const std::string& yaml) {
  const ConfigDocument doc = ConfigDocument::parse(yaml, "bem.yaml");
  BemOptions o = bem_options_table().read(doc.root());
  doc.root().finish();
  return o;
}

}  // namespace

TEST_CASE("bem parameter table: an empty section gives the defaults of BemOptions") {
  CHECK(fingerprint(read("{}")) == fingerprint(BemOptions{}));
  CHECK(fingerprint(bem_options_table().defaults()) == fingerprint(BemOptions{}));
  // The documented defaults are the ones that apply.
  for (const ParamSpec& spec : bem_options_table().specs()) {
    if (spec.name == "points_per_wavelength") CHECK(spec.default_value == "30");
    if (spec.name == "method") CHECK(spec.default_value == "dense");
    if (spec.name == "gmres_tolerance") CHECK(spec.default_value == "1e-08");
    if (spec.name == "aca_tolerance") CHECK(spec.default_value == "1e-06");
    if (spec.name == "preconditioner") CHECK(spec.range == "near_field | dense_single | hodlr");
  }
}

TEST_CASE("bem parameter table: each declared parameter is read into its own field") {
  const std::vector<double> base = fingerprint(BemOptions{});
  std::set<std::size_t> fields;
  const auto specs = bem_options_table().specs();
  REQUIRE(specs.size() == 24);
  for (const ParamSpec& spec : specs) {
    const std::string yaml = spec.name + ": " + other_value(spec);
    INFO(yaml);
    const std::vector<double> got = fingerprint(read(yaml));
    std::vector<std::size_t> changed;
    for (std::size_t k = 0; k < got.size(); ++k)
      if (got[k] != base[k]) changed.push_back(k);
    REQUIRE(changed.size() == 1);
    CHECK(fields.insert(changed.front()).second);  // no two parameters share a field
  }
  CHECK(fields.size() == base.size());  // and every field has its parameter
}

TEST_CASE("bem parameter table: ranges, words and unknown keys are errors naming the parameter") {
  const auto error_of = [](const std::string& yaml) -> std::string {
    try {
      read(yaml);
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "no error";
  };
  CHECK_THAT(error_of("points_per_wavelength: 0"), Catch::Contains("points_per_wavelength"));
  CHECK_THAT(error_of("leaf_size: -3"), Catch::Contains("leaf_size"));
  CHECK_THAT(error_of("method: hmatrx"), Catch::Contains("did you mean 'hmatrix'?"));
  CHECK_THAT(error_of("preconditioner: block_jacobi"), Catch::Contains("preconditioner"));
  CHECK_THAT(error_of("ppw: 12"), Catch::Contains("unknown key 'ppw'"));
}
