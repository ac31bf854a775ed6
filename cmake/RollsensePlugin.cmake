# rollsense_add_plugin(<name> SOURCES <files...> [LIBRARIES <targets...>])
#
# Builds a rollsense plugin: the module librollsense_<name>.so, target
# rollsense_plugin_<name>. This one file serves both the plugins in this tree
# and plugins built against an installed rollsense (find_package(rollsense),
# which installs this file next to rollsenseConfig.cmake). Only these
# variables differ between the two, set by the caller before the first call:
#   ROLLSENSE_PLUGIN_OUTPUT_DIR   folder the module is built into (one folder
#                                 of plugins, so `--plugin-path` can point at it)
#   ROLLSENSE_PLUGIN_INSTALL_DIR  where it installs, relative to the prefix: the
#                                 folder the program searches next to itself
#   ROLLSENSE_SDK_LIBDIR          where librollsense_sdk installs, relative to
#                                 the same prefix
#   ROLLSENSE_SDK_RPATH           (installed package only) the absolute folder
#                                 of the installed SDK, for plugins installed
#                                 under another prefix
#
# What a plugin needs, and why:
#   hidden visibility      only the manifest (ROLLSENSE_PLUGIN, marked
#                          ROLLSENSE_API) is exported: two plugins with the same
#                          internal class name cannot collide in the process.
#   -Wl,--no-undefined     a missing library is a link error here, not a
#                          dlopen error on the robot.
#   C++20, no extensions   the SDK headers are C++20.
#   RPATH                  $ORIGIN-relative to the SDK, so an installed tree
#                          can be moved; plus ROLLSENSE_SDK_RPATH if set.
#   rollsense::sdk         brings, as its interface, -ffp-contract=off (the
#                          same floating-point bits on every machine, as the
#                          SDK and the features promise) and BOOST_DLL_USE_STD_FS
#                          (Boost.DLL header-only on std::filesystem: the
#                          manifest's types must match the kernel's loader).
function(rollsense_add_plugin name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBRARIES" ${ARGN})
  if(ARG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "rollsense_add_plugin(${name}): unexpected arguments '${ARG_UNPARSED_ARGUMENTS}'; "
                        "usage: rollsense_add_plugin(<name> SOURCES <files...> [LIBRARIES <targets...>])")
  endif()
  if(NOT ARG_SOURCES)
    message(FATAL_ERROR "rollsense_add_plugin(${name}): no SOURCES given")
  endif()
  foreach(var ROLLSENSE_PLUGIN_OUTPUT_DIR ROLLSENSE_PLUGIN_INSTALL_DIR ROLLSENSE_SDK_LIBDIR)
    if(NOT DEFINED ${var})
      message(FATAL_ERROR "rollsense_add_plugin(${name}): ${var} is not set; call find_package(rollsense) "
                          "before rollsense_add_plugin (cmake/RollsensePlugin.cmake lists what it needs)")
    endif()
  endforeach()

  set(target rollsense_plugin_${name})
  add_library(${target} MODULE ${ARG_SOURCES})
  file(RELATIVE_PATH to_sdk "/${ROLLSENSE_PLUGIN_INSTALL_DIR}" "/${ROLLSENSE_SDK_LIBDIR}")
  string(REGEX REPLACE "/$" "" to_sdk "${to_sdk}")
  set(rpath "$ORIGIN/${to_sdk}")
  if(ROLLSENSE_SDK_RPATH)
    list(APPEND rpath "${ROLLSENSE_SDK_RPATH}")
  endif()
  set_target_properties(${target} PROPERTIES
    OUTPUT_NAME "rollsense_${name}"
    PREFIX "lib"
    CXX_EXTENSIONS OFF
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON
    LIBRARY_OUTPUT_DIRECTORY "${ROLLSENSE_PLUGIN_OUTPUT_DIR}"
    BUILD_RPATH_USE_ORIGIN ON
    INSTALL_RPATH "${rpath}")
  target_compile_features(${target} PRIVATE cxx_std_20)
  target_link_options(${target} PRIVATE "LINKER:--no-undefined")
  target_link_libraries(${target} PRIVATE rollsense::sdk ${ARG_LIBRARIES})
  if(COMMAND rollsense_warnings)
    rollsense_warnings(${target})
  endif()
  install(TARGETS ${target} LIBRARY DESTINATION "${ROLLSENSE_PLUGIN_INSTALL_DIR}")
  set_property(GLOBAL APPEND PROPERTY ROLLSENSE_PLUGIN_TARGETS ${target})
endfunction()
