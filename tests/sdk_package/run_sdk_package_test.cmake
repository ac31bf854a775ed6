# cmake -P driver of the sdk_package test (tests/sdk_package/CMakeLists.txt
# passes the -D variables). Each step stops the test with a message naming
# the step, the command and its output.
#   1. install the `sdk` component of the build into WORK_DIR/prefix
#   2. probe the package: targets, version rule, conformance headers compile,
#      a program calling the installed features and HAL libraries links
#   3. copy example_bump as example_bump_oot (a manifest name of its own, so
#      it cannot be mistaken for, or shadowed by, the in-tree plugin) beside
#      out_of_tree/CMakeLists.txt; configure and build it against the prefix
#   4. check the flags rollsense_add_plugin promises reached the compile and
#      link lines, and the RUNPATH of the built and the installed module
#   5. `rollsense plugins --plugin-path <its build folder> --params --check`
#      loads it and lists its manifest and parameters
#   6. the conformance snippet of docs/writing-a-sensor-plugin.md §5, taken
#      from the page, compiled with example_bump as MySensor (docs_snippet/):
#      it passes; the suite on the same sensor offered no joint fails, naming
#      the frame, its time and its reason
cmake_minimum_required(VERSION 3.25)

foreach(var ROLLSENSE_SOURCE_DIR ROLLSENSE_BINARY_DIR ROLLSENSE_PROGRAM ROLLSENSE_VERSION WORK_DIR CXX_COMPILER
            GENERATOR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_sdk_package_test.cmake: -D${var}=... is missing (see tests/sdk_package/CMakeLists.txt)")
  endif()
endforeach()
set(here "${CMAKE_CURRENT_LIST_DIR}")
set(prefix "${WORK_DIR}/prefix")

# run(<step> <command...>): run a command, fail the test with its output if it fails.
function(run step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(last_output "${out}${err}" PARENT_SCOPE)
  if(NOT rc EQUAL 0)
    string(JOIN " " cmd ${ARGN})
    message(FATAL_ERROR "sdk_package: ${step} failed (exit ${rc}):\n  ${cmd}\n${out}${err}")
  endif()
endfunction()

# require(<what> <haystack> <needle>)
function(require what haystack needle)
  string(FIND "${haystack}" "${needle}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "sdk_package: ${what}: '${needle}' not found in:\n${haystack}")
  endif()
endfunction()

file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

# The nested builds use the same compiler (and ccache) as this build; nothing
# from the environment may point them at another rollsense.
set(configure_args -G "${GENERATOR}" -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_BUILD_TYPE=RelWithDebInfo
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_EXPORT_COMPILE_COMMANDS=ON)
if(CXX_LAUNCHER)
  list(APPEND configure_args -DCMAKE_CXX_COMPILER_LAUNCHER=${CXX_LAUNCHER})
endif()
unset(ENV{ROLLSENSE_PLUGIN_PATH})
unset(ENV{rollsense_DIR})
unset(ENV{rollsense_ROOT})

# 1. install
run("installing the sdk component" "${CMAKE_COMMAND}" --install "${ROLLSENSE_BINARY_DIR}" --prefix "${prefix}"
    --component sdk)
file(GLOB_RECURSE config_files "${prefix}/*/rollsenseConfig.cmake")
list(LENGTH config_files n)
if(NOT n EQUAL 1)
  message(FATAL_ERROR "sdk_package: expected one rollsenseConfig.cmake under ${prefix}, found ${n}: ${config_files}")
endif()
get_filename_component(config_dir "${config_files}" DIRECTORY)

# 2. probe
run("configuring the package probe (tests/sdk_package/probe)" "${CMAKE_COMMAND}" -S "${here}/probe"
    -B "${WORK_DIR}/probe" ${configure_args} -DEXPECT_VERSION=${ROLLSENSE_VERSION})
run("building the package probe (conformance headers, installed libraries)" "${CMAKE_COMMAND}" --build "${WORK_DIR}/probe")

# 3. the out-of-tree plugin
set(src "${WORK_DIR}/src")
file(MAKE_DIRECTORY "${src}")
file(COPY "${here}/out_of_tree/CMakeLists.txt" DESTINATION "${src}")
set(example "${ROLLSENSE_SOURCE_DIR}/plugins/sensors/example_bump/example_bump.cpp")
file(READ "${example}" code)
set(manifest_name "ROLLSENSE_PLUGIN(ExampleBump, sensor, \"example_bump\",")
require("${example}: the manifest to rename" "${code}" "${manifest_name}")
string(REPLACE "${manifest_name}" "ROLLSENSE_PLUGIN(ExampleBump, sensor, \"example_bump_oot\"," code "${code}")
file(WRITE "${src}/example_bump.cpp" "${code}")
set(build "${WORK_DIR}/build")
run("configuring the out-of-tree plugin" "${CMAKE_COMMAND}" -S "${src}" -B "${build}" ${configure_args})
file(STRINGS "${build}/CMakeCache.txt" found_dir REGEX "^rollsense_DIR:")
require("the out-of-tree build's rollsense package" "${found_dir}" "${config_dir}")
run("building the out-of-tree plugin" "${CMAKE_COMMAND}" --build "${build}")
set(module "${build}/plugins/librollsense_example_bump_oot.so")
if(NOT EXISTS "${module}")
  message(FATAL_ERROR "sdk_package: the out-of-tree build made no ${module} (rollsense_add_plugin's output folder)")
endif()

# 4. flags and RUNPATH
file(READ "${build}/compile_commands.json" compile_commands)
foreach(flag -ffp-contract=off -DBOOST_DLL_USE_STD_FS -fvisibility=hidden -fvisibility-inlines-hidden -std=c++20)
  require("compile line of the out-of-tree plugin" "${compile_commands}" "${flag}")
endforeach()
file(GLOB_RECURSE link_files "${build}/build.ninja" "${build}/*/link.txt")
set(link_lines "")
foreach(f IN LISTS link_files)
  file(READ "${f}" text)
  string(APPEND link_lines "${text}")
endforeach()
require("link line of the out-of-tree plugin (${link_files})" "${link_lines}" "--no-undefined")
file(READ_ELF "${module}" RUNPATH built_runpath)
require("RUNPATH of the built ${module}" "${built_runpath}" "${prefix}/")
run("installing the out-of-tree plugin" "${CMAKE_COMMAND}" --install "${build}" --prefix "${WORK_DIR}/oot-prefix")
file(GLOB_RECURSE installed_module "${WORK_DIR}/oot-prefix/*/librollsense_example_bump_oot.so")
if(NOT installed_module)
  message(FATAL_ERROR "sdk_package: `cmake --install` of the out-of-tree build installed no plugin under ${WORK_DIR}/oot-prefix")
endif()
file(READ_ELF "${installed_module}" RUNPATH installed_runpath)
require("RUNPATH of the installed ${installed_module}" "${installed_runpath}" "$ORIGIN/../..")
require("RUNPATH of the installed ${installed_module}" "${installed_runpath}" "${prefix}/")

# 5. load it
run("rollsense plugins on the out-of-tree plugin" "${ROLLSENSE_PROGRAM}" plugins --plugin-path "${build}/plugins"
    --params --check)
set(listing "${last_output}")
require("rollsense plugins listing" "${listing}" "${module}")
string(REGEX MATCH "sensor +example_bump_oot +1\\.0\\.0 +[^\n]*librollsense_example_bump_oot\\.so" loaded "${listing}")
if(NOT loaded)
  message(FATAL_ERROR "sdk_package: rollsense plugins did not load example_bump_oot as a sensor:\n${listing}")
endif()
# Its entry: the manifest line, then lines indented further (description, parameters).
string(FIND "${listing}" "${loaded}" at)
string(SUBSTRING "${listing}" ${at} -1 entry)
string(REGEX MATCH "^[^\n]*\n(      [^\n]*\n)*" entry "${entry}")
foreach(param joint cell_angles width amplitude noise)
  require("parameters of example_bump_oot" "${entry}" "      ${param} ")
endforeach()
message(STATUS "sdk_package: example_bump_oot built against ${config_dir} and loaded")

# 6. the documented conformance snippet
set(page "${ROLLSENSE_SOURCE_DIR}/docs/writing-a-sensor-plugin.md")
file(READ "${page}" doc)
string(FIND "${doc}" "\n## 5. " at)
if(at EQUAL -1)
  message(FATAL_ERROR "sdk_package: ${page} has no section '## 5.' (the conformance snippet)")
endif()
string(SUBSTRING "${doc}" ${at} -1 doc)
string(REGEX MATCH "```cpp\n(#include \"rollsense/testing/conformance.hpp\"[^`]*check_sensor_conformance[^`]*)```" _
       "${doc}")
if(NOT CMAKE_MATCH_1)
  message(FATAL_ERROR "sdk_package: ${page} §5 has no cpp block including rollsense/testing/conformance.hpp and "
                      "calling check_sensor_conformance")
endif()
set(snippet "${CMAKE_MATCH_1}")
string(REGEX MATCHALL "#include [^\n]*\n" SNIPPET_INCLUDES "${snippet}")
string(REPLACE ";" "" SNIPPET_INCLUDES "${SNIPPET_INCLUDES}")
string(REGEX REPLACE "#include [^\n]*\n" "" SNIPPET_BODY "${snippet}")
set(snippet_src "${WORK_DIR}/docs_snippet_src")
file(COPY "${here}/docs_snippet/CMakeLists.txt" "${src}/example_bump.cpp" DESTINATION "${snippet_src}")
configure_file("${here}/docs_snippet/docs_snippet_test.cpp.in" "${snippet_src}/docs_snippet_test.cpp" @ONLY)
run("configuring the docs snippet test (tests/sdk_package/docs_snippet)" "${CMAKE_COMMAND}" -S "${snippet_src}"
    -B "${WORK_DIR}/docs_snippet" ${configure_args})
run("building the docs snippet test (${snippet_src}/docs_snippet_test.cpp)" "${CMAKE_COMMAND}" --build
    "${WORK_DIR}/docs_snippet")
set(snippet_test "${WORK_DIR}/docs_snippet/docs_snippet_test")
run("running the conformance snippet of ${page} §5" "${snippet_test}")
execute_process(COMMAND "${snippet_test}" "[without_joints]" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0)
  message(FATAL_ERROR "sdk_package: the conformance suite passed a sensor offered no joint:\n${out}${err}")
endif()
require("the failed frame's message" "${out}${err}"
        "frame 0 (t = 0 s): invalid, reason: no joint 'sensing_finger' in this profile")
message(STATUS "sdk_package: the conformance snippet of ${page} §5 passes out of the tree")
