// One declaration per parameter (param_table.hpp): the same table reads, checks, defaults and
// documents; derived documents (ConfigDocument::derive) keep file positions; canonical text ignores
// comments and key order.
#include <catch2/catch.hpp>

#include "plumage/config_document.hpp"
#include "plumage/param_table.hpp"

using namespace plumage;

namespace {

enum class Model { film, rods };

struct Inner {
  double width_um = 0;
};

struct Options {
  double ppw = 0;
  int leaf = 0;
  bool warm = false;
  std::string log;
  Model model = Model::film;
  double film_nm = 0;
  std::pair<double, double> range{0, 0};
  std::vector<double> list;
  std::optional<double> step;
  Inner inner;
};

const ParamTable<Inner>& inner_table() {
  static const auto t = ParamTable<Inner>{}.number("width_um", &Inner::width_um, "um", 40.0, Limits::positive(),
                                                   "barbule width");
  return t;
}

const ParamTable<Options>& table() {
  static const auto t =
      ParamTable<Options>{}
          .number("ppw", &Options::ppw, "1", 30.0, Limits::positive(), "points per wavelength")
          .integer("leaf", &Options::leaf, "1", 24, Limits::closed(1, 1000), "leaf size")
          .boolean("warm", &Options::warm, true, "warm start")
          .text("log", &Options::log, "", "log file")
          .choice("model", &Options::model, {{"film", Model::film}, {"rods", Model::rods}}, Model::film, "interior")
          .number("film_nm", &Options::film_nm, "nm", required, Limits::positive(), "film thickness")
          .only_if([](const Options& o) { return o.model == Model::film; }, "model: film")
          .interval("range", &Options::range, "nm", {400, 700}, Limits::positive(), "wavelengths")
          .numbers("list", &Options::list, "-", {0.9, 0.95}, {}, "spacers")
          .optional_number("step", &Options::step, "nm", "by fidelity", Limits::positive(), "grid step")
          .section("inner", &Options::inner, inner_table(), "nested");
  return t;
}

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

TEST_CASE("a parameter table supplies defaults and reads what is given", "[param-table]") {
  const Options d = table().defaults();
  CHECK(d.ppw == 30.0);
  CHECK(d.leaf == 24);
  CHECK(d.warm);
  CHECK(d.range == std::pair<double, double>{400, 700});
  CHECK(d.list == std::vector<double>{0.9, 0.95});
  CHECK(!d.step);
  CHECK(d.inner.width_um == 40.0);

  auto doc = ConfigDocument::parse("ppw: 12\nleaf: 3\nwarm: false\nlog: x.txt\nfilm_nm: 250\nrange: [450, 650]\n"
                                   "list: [1, 2, 3]\nstep: 5\ninner: {width_um: 10}\n",
                                   "cfg.yaml");
  const Options o = table().read(doc.root());
  doc.root().finish();
  CHECK(o.ppw == 12.0);
  CHECK(o.leaf == 3);
  CHECK(!o.warm);
  CHECK(o.log == "x.txt");
  CHECK(o.film_nm == 250.0);
  CHECK(o.range == std::pair<double, double>{450, 650});
  CHECK(o.list == std::vector<double>{1, 2, 3});
  CHECK(o.step == 5.0);
  CHECK(o.inner.width_um == 10.0);
}

TEST_CASE("a parameter table checks ranges and requirements with file positions", "[param-table]") {
  CHECK_THAT(error_of("ppw: -1\nfilm_nm: 3\n", [](const ParamView& r) { table().read(r); }),
             Catch::StartsWith("cfg.yaml:1:6: ppw: value -1 is out of range: must be > 0"));
  CHECK_THAT(error_of("ppw: 1\n", [](const ParamView& r) { table().read(r); }),
             Catch::Contains("film_nm: missing required key 'film_nm'"));
  CHECK_THAT(error_of("model: rodz\n", [](const ParamView& r) { table().read(r); }),
             Catch::Contains("did you mean 'rods'?"));
  CHECK_THAT(error_of("film_nm: 3\ninner: {width_um: 0}\n", [](const ParamView& r) { table().read(r); }),
             Catch::Contains("inner.width_um: value 0 is out of range"));
}

TEST_CASE("a conditional parameter is not read when it does not apply", "[param-table]") {
  // film_nm applies to model: film only; given with rods it is an unknown key.
  auto doc = ConfigDocument::parse("model: rods\n", "cfg.yaml");
  const Options o = table().read(doc.root());
  CHECK(o.model == Model::rods);
  CHECK_NOTHROW(doc.root().finish());
  CHECK_THAT(error_of("model: rods\nfilm_nm: 3\n",
                      [](const ParamView& r) {
                        table().read(r);
                        r.finish();
                      }),
             Catch::Contains("unknown key 'film_nm'"));
}

TEST_CASE("a parameter table documents each row once", "[param-table]") {
  const auto specs = table().specs();
  REQUIRE(specs.size() == 11);  // 10 entries + the nested row inner.width_um
  CHECK(specs[0].name == "ppw");
  CHECK(specs[0].default_value == "30");
  CHECK(specs[0].range == "> 0");
  CHECK(specs[4].type == "choice");
  CHECK(specs[4].range == "film | rods");
  CHECK(specs[5].default_value == "required");
  CHECK(specs[5].condition == "model: film");
  CHECK(specs[6].default_value == "[400, 700]");
  CHECK(specs[7].default_value == "[0.9, 0.95]");
  CHECK(specs[8].default_value == "by fidelity");
  CHECK(specs[9].type == "map");
  CHECK(specs[10].name == "inner.width_um");
  CHECK(format_param_number(1e-8) == "1e-08");
  CHECK(format_param_number(0.25) == "0.25");
}

TEST_CASE("a derived document replaces values as nodes and keeps file positions", "[config]") {
  auto doc = ConfigDocument::parse("structure:\n  outline: {width_um: 40, corner_um: 1}\n  cortex_nm: -3\n", "s.yaml");
  const ConfigDocument d = ConfigDocument::derive(doc.root(), {{"structure.outline.width_um", "10"}}, "/tmp", "derived");
  const ParamView outline = d.root().child("structure").child("outline");
  CHECK(outline.number("width_um") == 10.0);
  CHECK(outline.number("corner_um") == 1.0);
  CHECK(d.directory() == "/tmp");
  // An untouched value still points into the original file.
  CHECK_THAT(error_of("x: 1\n",
                      [&](const ParamView&) { d.root().child("structure").number("cortex_nm", Limits::positive()); }),
             Catch::StartsWith("s.yaml:3:14: structure.cortex_nm: value -3 is out of range"));
  // The original document is unchanged.
  CHECK(doc.root().child("structure").child("outline").number("width_um") == 40.0);
  CHECK_THROWS_AS(ConfigDocument::derive(doc.root(), {{"structure.outline.widht_um", "10"}}, "/tmp", "derived"),
                  ConfigError);
  const ConfigDocument c =
      ConfigDocument::derive(doc.root(), {{"solver.type", "bem", true}}, "/tmp", "derived");
  CHECK(c.root().child("solver").text("type") == "bem");
  // A replaced value that is then refused names the override's source.
  const ConfigDocument bad = ConfigDocument::derive(
      doc.root(), {{"structure.outline.width_um", "-2", false, "command line --width-um"}}, "/tmp", "derived");
  CHECK_THAT(error_of("x: 1\n",
                      [&](const ParamView&) {
                        bad.root().child("structure").child("outline").number("width_um", Limits::positive());
                      }),
             Catch::StartsWith("command line --width-um: structure.outline.width_um: value -2 is out of range"));
}

TEST_CASE("canonical text ignores comments, layout and key order, not values", "[config]") {
  auto a = ConfigDocument::parse("b: 2   # two\na: {x: 1, y: [1, 2]}\n", "a.yaml");
  auto b = ConfigDocument::parse("a:\n  y:\n    - 1\n    - 2\n  x: '1'\nb: 2\n", "b.yaml");
  auto c = ConfigDocument::parse("a: {x: 1, y: [1, 2]}\nb: 3\n", "c.yaml");
  CHECK(canonical_text(a.root()) == canonical_text(b.root()));
  CHECK(canonical_text(a.root()) != canonical_text(c.root()));
}
