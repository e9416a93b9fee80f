// Config errors name file:line:column, the field, and the nearest valid name.
#include <catch2/catch.hpp>

#include "plumage/config_document.hpp"
#include "plumage/params.hpp"

using namespace plumage;

namespace {

// Runs `read` on a document and returns the ConfigError message it must throw.
template <class F>
std::string error_of(const std::string& yaml, F read) {
  auto doc = ConfigDocument::parse(yaml, "cfg.yaml");
  try {
    read(doc.root());
  } catch (const ConfigError& e) {
    return e.what();
  }
  FAIL("no ConfigError thrown");
  return {};
}

}  // namespace

TEST_CASE("unknown keys are reported with file:line and the nearest name", "[config]") {
  const std::string yaml = "structure:\n  width_um: 40\n  widht_um: 3\n";
  auto msg = error_of(yaml, [](const ParamView& root) {
    auto s = root.child("structure");
    s.number("width_um");
    root.finish();
  });
  CHECK_THAT(msg, Catch::StartsWith("cfg.yaml:3:3: structure.widht_um: unknown key 'widht_um'"));
  CHECK_THAT(msg, Catch::Contains("did you mean 'width_um'?"));
}

TEST_CASE("wrong types are reported with file:line", "[config]") {
  auto msg = error_of("a:\n  b: forty\n", [](const ParamView& root) {
    root.child("a").number("b");
  });
  CHECK_THAT(msg, Catch::StartsWith("cfg.yaml:2:6: a.b: expected a number, got 'forty'"));
  msg = error_of("n: 2.5\n", [](const ParamView& root) { root.integer("n"); });
  CHECK_THAT(msg, Catch::StartsWith("cfg.yaml:1:4: n: expected an integer"));
  msg = error_of("m: [1, 2]\n", [](const ParamView& root) { root.child("m"); });
  CHECK_THAT(msg, Catch::StartsWith("cfg.yaml:1:4: m: expected a map"));
}

TEST_CASE("out-of-range values are reported with the admissible range", "[config]") {
  auto msg = error_of("thickness_nm: -3\n", [](const ParamView& root) {
    root.number("thickness_nm", Limits::non_negative());
  });
  CHECK_THAT(msg, Catch::StartsWith("cfg.yaml:1:15: thickness_nm: value -3 is out of range: must be >= 0"));
  msg = error_of("range_um: [0.3, -0.3]\n", [](const ParamView& root) { root.interval("range_um"); });
  CHECK_THAT(msg, Catch::StartsWith("cfg.yaml:1:11: range_um: interval is inverted"));
  msg = error_of("f: .nan\n", [](const ParamView& root) { root.number("f"); });
  CHECK_THAT(msg, Catch::Contains("out of range"));
}

TEST_CASE("missing keys, missing files and YAML syntax errors are located", "[config]") {
  auto msg = error_of("a: {}\n", [](const ParamView& root) { root.child("a").number("b"); });
  CHECK_THAT(msg, Catch::StartsWith("cfg.yaml:1:4: a.b: missing required key 'b'"));
  try {
    ConfigDocument::load("/nonexistent/dir/species.yaml");
    FAIL("no error");
  } catch (const ConfigError& e) {
    CHECK_THAT(e.what(), Catch::StartsWith("/nonexistent/dir/species.yaml: no such file"));
  }
  try {
    ConfigDocument::parse("a: [1, 2\nb: 3\n", "bad.yaml");
    FAIL("no error");
  } catch (const ConfigError& e) {
    CHECK_THAT(e.what(), Catch::Matches("bad\\.yaml:\\d+:\\d+: YAML syntax error.*"));
  }
}

TEST_CASE("choices suggest the nearest allowed word", "[config]") {
  static constexpr std::string_view allowed[] = {"preview", "production", "reference"};
  auto msg = error_of("fidelity: prodution\n", [](const ParamView& root) { root.choice("fidelity", allowed); });
  CHECK_THAT(msg, Catch::Contains("did you mean 'production'?"));
  auto doc = ConfigDocument::parse("fidelity: preview\n", "ok.yaml");
  CHECK(doc.root().choice("fidelity", allowed) == "preview");
}

TEST_CASE("reads are recorded, so finish() accepts every key that was read", "[config]") {
  auto doc = ConfigDocument::parse("a: 1\nb: {c: [1, 2], d: true}\nlist: [{x: 1}, {x: 2}]\n", "ok.yaml");
  auto root = doc.root();
  CHECK(root.number("a") == 1.0);
  auto b = root.child("b");
  CHECK(b.numbers("c") == std::vector<double>{1.0, 2.0});
  CHECK(b.boolean_or("d", false));
  for (const auto& item : root.items("list")) CHECK(item.number("x") > 0);
  CHECK_NOTHROW(root.finish());
  // A key in a list item nobody read is caught through the recursion.
  auto doc2 = ConfigDocument::parse("list: [{x: 1}, {x: 2, y: 3}]\n", "l.yaml");
  for (const auto& item : doc2.root().items("list")) item.number("x");
  CHECK_THROWS_WITH(doc2.root().finish(), Catch::StartsWith("l.yaml:1:23: list[1].y: unknown key 'y'"));
}
