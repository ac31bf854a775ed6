# rollsense_add_plugin(<name> SOURCES <files...> [LIBRARIES <targets...>])
#
# Builds a rollsense plugin: a shared library with hidden visibility (only the
# manifest symbol is exported), no undefined symbols (a missing library is a
# link error here, not a dlopen error on the robot), an RPATH that finds the
# kernel SDK next to it, and its output in the common plugin folder that the
# program searches by default.
function(rollsense_add_plugin name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBRARIES" ${ARGN})
  set(target rollsense_plugin_${name})
  add_library(${target} MODULE ${ARG_SOURCES})
  set_target_properties(${target} PROPERTIES
    OUTPUT_NAME "rollsense_${name}"
    PREFIX "lib"
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON
    LIBRARY_OUTPUT_DIRECTORY "${ROLLSENSE_PLUGIN_OUTPUT_DIR}"
    BUILD_RPATH "$ORIGIN/../.."
    INSTALL_RPATH "$ORIGIN/../..")
  target_link_options(${target} PRIVATE "LINKER:--no-undefined")
  target_link_libraries(${target} PRIVATE rollsense::sdk ${ARG_LIBRARIES})
  rollsense_warnings(${target})
  install(TARGETS ${target} LIBRARY DESTINATION ${ROLLSENSE_PLUGIN_INSTALL_DIR})
  set_property(GLOBAL APPEND PROPERTY ROLLSENSE_PLUGIN_TARGETS ${target})
endfunction()
