// Private to core: a config subtree as one line of YAML (yaml-cpp's emitter in flow style, every
// scalar double-quoted, null as `null`), e.g. {"type": "approximate", "currents": "reflected"}.
// What a comparison records of a method's solver section, and the text of a structure override
// handed to ConfigDocument::derive.
#pragma once

#include <string>

#include "plumage/params.hpp"

namespace plumage::detail {

std::string flow_yaml_text(const ParamView& view);

}  // namespace plumage::detail
