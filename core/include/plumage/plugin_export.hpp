// Include in exactly one source file of a plug-in, then write
//   PLUMAGE_PLUGIN(my_register_function)
// where my_register_function is `void(plumage::Registrar&)`. This exports the only two symbols
// the host looks for (the rest of the library stays hidden with -fvisibility=hidden).
#pragma once

#include <boost/dll/alias.hpp>

#include "plumage/plugin.hpp"
#include "plumage/version.hpp"

#define PLUMAGE_PLUGIN(register_function)                                        \
  namespace plumage_plugin_exports {                                             \
  const int abi_version = ::plumage::kAbiVersion;                                \
  void register_plugin(::plumage::Registrar& registrar) {                        \
    register_function(registrar);                                                \
  }                                                                              \
  }                                                                              \
  BOOST_DLL_ALIAS(plumage_plugin_exports::abi_version, plumage_abi_version)      \
  BOOST_DLL_ALIAS(plumage_plugin_exports::register_plugin, plumage_register)
