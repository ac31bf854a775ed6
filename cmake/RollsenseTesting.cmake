# rollsense_add_test(<name> SOURCES <files...> [LIBRARIES <targets...>] [DEPENDS <targets...>])
#
# A Catch2 test executable registered with CTest through catch_discover_tests.
# Discovery runs the binary at build time without LD_LIBRARY_PATH, so paths it
# needs are compile definitions and libraries are found through RPATH:
#   ROLLSENSE_SOURCE_DIR, ROLLSENSE_BINARY_DIR, ROLLSENSE_PLUGIN_DIR,
#   ROLLSENSE_SHARE_DIR, ROLLSENSE_BIN_DIR.
function(rollsense_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBRARIES;DEPENDS" ${ARGN})
  # A test name starting with '-' reaches Catch as an option ("-o NAME" names
  # its report file), so ctest would run every test of the binary as that one.
  foreach(src IN LISTS ARG_SOURCES)
    get_filename_component(path "${src}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
    file(STRINGS "${path}" dashed REGEX "TEST_CASE\\(\"-")
    if(dashed)
      message(FATAL_ERROR "${path}: a TEST_CASE name starts with '-' (${dashed}): Catch reads it as an option; "
                          "start the name with a word")
    endif()
    # A ';' splits the name where catch_discover_tests registers it: ctest then runs a name that matches no test
    # case, which Catch reports as passed (27 test cases never ran that way).
    file(STRINGS "${path}" semicolon REGEX "TEST_CASE\\(\"[^\"]*;")
    if(semicolon)
      message(FATAL_ERROR "${path}: a TEST_CASE name has a ';': ctest would never run it; use ',' instead")
    endif()
  endforeach()
  add_executable(${name} ${ARG_SOURCES})
  rollsense_test_flags(${name})
  target_link_libraries(${name} PRIVATE ${ARG_LIBRARIES})
  # Catch's header, parsed once for every test (rollsense_test_pch): it was about 0.9 s of each test file's compile.
  target_precompile_headers(${name} REUSE_FROM rollsense_test_pch)
  if(ARG_DEPENDS)
    add_dependencies(${name} ${ARG_DEPENDS})
  endif()
  # -w NoTests: a name that matches no test case fails instead of passing having run nothing.
  catch_discover_tests(${name} TEST_PREFIX "${name}: " EXTRA_ARGS -w NoTests PROPERTIES TIMEOUT 300)
endfunction()

# What every test file is compiled with. The precompiled header is valid only for files compiled as it was, so
# rollsense_test_pch is built with these flags too.
function(rollsense_test_flags target)
  # rollsense_hands: the controllers the stock E-TRoll profiles name, as the program has them.
  target_link_libraries(${target} PRIVATE Catch2::Catch2WithMain rollsense_test_support rollsense_hands)
  rollsense_warnings(${target})
  # The tests' own code for debugging (-Og), the code they test as built: Catch's assertion macros at -O2 were half
  # of the whole build's compile time, and no result changes (SSE arithmetic, -ffp-contract=off from rollsense::sdk).
  target_compile_options(${target} PRIVATE -Og)
  if(ROLLSENSE_TESTS_UNINSTRUMENTED)
    if(NOT CMAKE_CXX_FLAGS MATCHES "-fsanitize=[^ ]*address")
      message(FATAL_ERROR "ROLLSENSE_TESTS_UNINSTRUMENTED is for an AddressSanitizer build (tools/sanitize.sh): "
                          "CMAKE_CXX_FLAGS has no -fsanitize=address")
    endif()
    # Instrumentation made each test file take 60 % longer to compile; the libraries and plugins they load keep
    # theirs, and the sanitizer runtime is still linked (what a test file compiles itself, header-inline and template
    # code included, is not checked). __SANITIZE_ADDRESS__ stays defined, as where the code is instrumented: headers
    # decide layouts by it (Eigen's aligned allocation: a matrix allocated by a test and freed in the library read
    # outside its block), and the tests that behave differently under AddressSanitizer read it.
    target_compile_options(${target} PRIVATE -fno-sanitize=all)
    target_compile_definitions(${target} PRIVATE __SANITIZE_ADDRESS__=1)
  endif()
endfunction()

# The target that owns Catch's precompiled header (one empty source file); every test reuses it.
function(rollsense_add_test_pch)
  add_library(rollsense_test_pch OBJECT "${PROJECT_SOURCE_DIR}/tests/support/catch_pch.cpp")
  rollsense_test_flags(rollsense_test_pch)
  target_precompile_headers(rollsense_test_pch PRIVATE <catch2/catch.hpp>)
endfunction()
