# plumage_add_plugin(<name> SOURCES <files...> [LIBRARIES <targets...>])
#
# Builds libplumage_<name>.so as a run-time-loaded module against plumage::core, with hidden
# symbols (only the two aliases of PLUMAGE_PLUGIN are exported). Used both in this tree and by
# out-of-tree plug-ins through find_package(plumage).
function(plumage_add_plugin name)
  cmake_parse_arguments(P "" "" "SOURCES;LIBRARIES" ${ARGN})
  set(target plumage_${name})
  add_library(${target} MODULE ${P_SOURCES})
  target_link_libraries(${target} PRIVATE plumage::core ${P_LIBRARIES})
  set_target_properties(${target} PROPERTIES
    PREFIX "lib"
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON
    INSTALL_RPATH "$ORIGIN/../..")
  if(DEFINED PLUMAGE_PLUGIN_OUTPUT_DIR)
    set_target_properties(${target} PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${PLUMAGE_PLUGIN_OUTPUT_DIR})
    target_compile_options(${target} PRIVATE ${PLUMAGE_WARNINGS})
  endif()
  if(PLUMAGE_IN_TREE)
    install(TARGETS ${target} LIBRARY DESTINATION ${PLUMAGE_INSTALL_PLUGINDIR})
  endif()
endfunction()
