// The Python types of the material area, shared by bind_material.cpp and bind_characterize.cpp
// (characterize() returns the material it wrote).
#pragma once

#include <filesystem>
#include <memory>

#include "plumage/feather_bsdf.hpp"
#include "plumage/feather_material.hpp"
#include "py_common.hpp"

namespace plumage::python {

// plumage.Material: a feather material (.plm) read once, shared by every BSDF made from it.
struct Material {
  std::shared_ptr<const FeatherMaterial> data;
  std::filesystem::path file;  // where it was read from
};
using MaterialPtr = std::shared_ptr<Material>;

// read_feather_material(file) with the GIL released (a production material is tens of MB).
MaterialPtr load_material(const std::filesystem::path& file);

// plumage.Bsdf: FeatherBsdf over a Material (which it keeps alive).
struct Bsdf {
  MaterialPtr material;
  std::shared_ptr<const FeatherBsdf> bsdf;
};

// The BSDF area's classes and functions (bind_bsdf.cpp), called by bind_material.
void bind_bsdf(py::module_& m);

}  // namespace plumage::python
