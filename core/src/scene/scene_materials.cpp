// A scene's `materials:` map (scene_sections.hpp): one parameter table for the three kinds.
#include <filesystem>

#include "scene_sections.hpp"

namespace plumage::scene_detail {

namespace {

namespace fs = std::filesystem;
using Kind = SceneMaterial::Kind;

struct MaterialKeys {
  fs::path directory;  // the scene file's folder: relative file names resolve against it
  Kind kind = Kind::diffuse;
  bool has_species = false, has_file = false;
  fs::path species, file;
  std::string variant, fidelity = "preview";
  double transmission_albedo = 0.02;
  TabulatedSpectrum albedo{{550.0}, {0.5}};
  double ior = 1.5;
};

bool is_feather(const MaterialKeys& k) { return k.kind == Kind::feather; }

// A number (constant) or {lambda_nm: [...], value: [...]} (strictly ascending, values in [0, 1]).
TabulatedSpectrum read_spectrum(const ParamView& m, std::string_view key) {
  TabulatedSpectrum s;
  const ParamView v = m.node(key);
  if (v.is_scalar()) {
    s.value = {v.scalar_number(Limits::unit_interval())};
    s.lambda_nm = {550.0};
    return s;
  }
  if (!v.is_map()) m.fail(key, "expected a number or {lambda_nm: [...], value: [...]}");
  s.lambda_nm = v.numbers("lambda_nm", Limits::wavelength_nm());
  s.value = v.numbers("value", Limits::unit_interval());
  if (s.lambda_nm.size() != s.value.size() || s.value.empty())
    v.fail("value", "needs as many entries as lambda_nm (" + std::to_string(s.lambda_nm.size()) + ")");
  for (std::size_t k = 1; k < s.lambda_nm.size(); ++k)
    if (s.lambda_nm[k] <= s.lambda_nm[k - 1]) v.fail("lambda_nm", "must be strictly ascending");
  return s;
}

// An existing file named relative to the scene's folder.
template <bool MaterialKeys::*Given, fs::path MaterialKeys::*Field>
ParamTable<MaterialKeys>::Reader file_reader(std::string key, std::string what) {
  return [key, what](const ParamView& p, MaterialKeys& k) {
    k.*Given = p.has(key);
    if (!(k.*Given)) return;
    k.*Field = k.directory / p.text(key);
    if (!fs::exists(k.*Field)) p.fail(key, "no such " + what + ": " + (k.*Field).string());
  };
}

const ParamTable<MaterialKeys>& material_table() {
  static const auto table =
      ParamTable<MaterialKeys>{}
          .choice("type", &MaterialKeys::kind,
                  std::vector<std::pair<std::string_view, Kind>>{
                      {"feather", Kind::feather}, {"diffuse", Kind::diffuse}, {"dielectric", Kind::dielectric}},
                  required,
                  "feather (a characterised FeatherBsdf) | diffuse (Lambertian) | dielectric (smooth interface)")
          .custom("species", "file", "-", "one of species, file",
                  "species config (relative to the scene's folder): its material is looked up or characterised",
                  file_reader<&MaterialKeys::has_species, &MaterialKeys::species>("species", "species config"))
          .only_if(is_feather, "type: feather")
          .custom("file", "file", "-", "one of species, file", "a characterised material file (.plm)",
                  file_reader<&MaterialKeys::has_file, &MaterialKeys::file>("file", "material file"))
          .only_if(is_feather, "type: feather")
          .text("variant", &MaterialKeys::variant, "", "variant of the species file (empty: its default)")
          .only_if(is_feather, "type: feather")
          .choice("fidelity", &MaterialKeys::fidelity,
                  {{"preview", std::string("preview")}, {"production", std::string("production")}}, std::string("preview"),
                  "characterisation fidelity of a species material")
          .only_if(is_feather, "type: feather")
          .number("transmission_albedo", &MaterialKeys::transmission_albedo, "1", 0.02, Limits::unit_interval(),
                  "diffuse transmission of the feather BSDF")
          .only_if(is_feather, "type: feather")
          .custom("albedo", "spectrum", "1", "0.5", "Lambertian reflectance: a number or {lambda_nm: [...], value: [...]}",
                  [](const ParamView& p, MaterialKeys& k) {
                    if (p.has("albedo")) k.albedo = read_spectrum(p, "albedo");
                  })
          .only_if([](const MaterialKeys& k) { return k.kind == Kind::diffuse; }, "type: diffuse")
          .number("ior", &MaterialKeys::ior, "1", 1.5, Limits{1.0, 4.0, false, false}, "real refractive index")
          .only_if([](const MaterialKeys& k) { return k.kind == Kind::dielectric; }, "type: dielectric");
  return table;
}

}  // namespace

void read_materials(const ParamView& mats, const fs::path& directory, SceneConfig& c) {
  for (const std::string& name : mats.keys()) {
    const ParamView m = mats.child(name);
    MaterialKeys k = material_table().defaults();
    k.directory = directory;
    material_table().read_into(m, k);
    SceneMaterial mat;
    mat.name = name;
    mat.kind = k.kind;
    std::optional<FeatherMaterialRequest> request;
    if (k.kind == Kind::feather) {
      if (k.has_file == k.has_species)
        m.fail_here("a feather material needs exactly one of 'species' (a species config) or 'file' (a .plm)");
      FeatherMaterialRequest q;
      q.where = m.mark();
      if (k.has_file) q.file = k.file;
      else q.species_config = k.species;
      q.variant = k.variant;
      q.fidelity = k.fidelity;
      q.transmission_albedo = k.transmission_albedo;
      request = q;
    } else if (k.kind == Kind::diffuse) {
      mat.albedo = k.albedo;
    } else {
      mat.ior = k.ior;
    }
    c.materials.push_back(std::move(mat));
    c.feather_requests.push_back(std::move(request));
  }
}

std::vector<ParamSpec> material_specs() { return material_table().specs(); }

}  // namespace plumage::scene_detail
