#include "flow_yaml.hpp"

#include <yaml-cpp/yaml.h>

#include "yaml_state.hpp"

namespace plumage::detail {

std::string flow_yaml_text(const ParamView& view) {
  YAML::Emitter out;
  out.SetMapFormat(YAML::Flow);
  out.SetSeqFormat(YAML::Flow);
  out.SetStringFormat(YAML::DoubleQuoted);
  out.SetNullFormat(YAML::LowerNull);
  out << view.state()->node;
  return out.c_str();
}

}  // namespace plumage::detail
