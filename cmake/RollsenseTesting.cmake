# rollsense_add_test(<name> SOURCES <files...> [LIBRARIES <targets...>] [DEPENDS <targets...>])
#
# A Catch2 test executable registered with CTest through catch_discover_tests.
# Discovery runs the binary at build time without LD_LIBRARY_PATH, so paths it
# needs are compile definitions and libraries are found through RPATH:
#   ROLLSENSE_SOURCE_DIR, ROLLSENSE_BINARY_DIR, ROLLSENSE_PLUGIN_DIR,
#   ROLLSENSE_SHARE_DIR, ROLLSENSE_BIN_DIR.
function(rollsense_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBRARIES;DEPENDS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  # rollsense_hands: the controllers the stock E-TRoll profiles name, as the program has them.
  target_link_libraries(${name} PRIVATE Catch2::Catch2WithMain rollsense_test_support rollsense_hands ${ARG_LIBRARIES})
  rollsense_warnings(${name})
  if(ARG_DEPENDS)
    add_dependencies(${name} ${ARG_DEPENDS})
  endif()
  catch_discover_tests(${name} TEST_PREFIX "${name}: " PROPERTIES TIMEOUT 300)
endfunction()
