# rollsense_add_discovered(<glob relative to the current source dir>)
#
# Adds every folder whose CMakeLists.txt matches the glob, in sorted order, so
# new plugins, HAL kinds, tests and benches need no edit of a parent list.
# ROLLSENSE_ONLY (a list of folders relative to the source root) restricts
# discovery to those folders: handy to build one area while another is being
# rewritten, e.g. -DROLLSENSE_ONLY="plugins/actuators/mock;tests/kernel".
set(ROLLSENSE_ONLY "" CACHE STRING "Only add these discovered folders (relative to the source root); empty = all")

# Pass ALWAYS for infrastructure (the HAL) that ROLLSENSE_ONLY must not filter.
function(rollsense_add_discovered pattern)
  cmake_parse_arguments(ARG "ALWAYS" "" "" ${ARGN})
  file(GLOB lists LIST_DIRECTORIES false CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/${pattern}")
  list(SORT lists)
  foreach(list_file IN LISTS lists)
    get_filename_component(dir "${list_file}" DIRECTORY)
    file(RELATIVE_PATH rel "${PROJECT_SOURCE_DIR}" "${dir}")
    if(ROLLSENSE_ONLY AND NOT ARG_ALWAYS AND NOT rel IN_LIST ROLLSENSE_ONLY)
      continue()
    endif()
    add_subdirectory("${dir}")
  endforeach()
endfunction()
