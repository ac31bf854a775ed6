# The SDK as an installable CMake package (docs/writing-a-sensor-plugin.md):
#   cmake --install build --prefix P [--component sdk]
# gives P/lib/cmake/rollsense/rollsenseConfig.cmake, so a plugin outside this
# tree builds with find_package(rollsense) + rollsense_add_plugin(...).
# Included once, from the top-level CMakeLists.txt, after every layer.
#
# The `sdk` install component is everything a plugin author needs and nothing
# of the runtime: the SDK, data, features and HAL (i2c, gpio) libraries and
# headers, the conformance suites, and the package files. A plain
# `cmake --install` installs it too.
include(CMakePackageConfigHelpers)

set(ROLLSENSE_PACKAGE_INSTALL_DIR "${CMAKE_INSTALL_LIBDIR}/cmake/rollsense")

# The SDK links Boost.DLL's settings (BOOST_DLL_USE_STD_FS, libdl) publicly, so
# the interface target that carries them is part of the export.
set_target_properties(rollsense_boost_dll PROPERTIES EXPORT_NAME boost_dll)
install(TARGETS rollsense_boost_dll EXPORT rollsenseTargets COMPONENT sdk)
install(EXPORT rollsenseTargets NAMESPACE rollsense:: DESTINATION "${ROLLSENSE_PACKAGE_INSTALL_DIR}"
        COMPONENT sdk)

# Conformance suites, header-only (Catch2 2.x), the same files the in-tree
# tests include as "rollsense/testing/<suite>.hpp": every header of the folder.
install(DIRECTORY "${PROJECT_SOURCE_DIR}/tests/support/rollsense/testing/"
        DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/rollsense/testing" COMPONENT sdk
        FILES_MATCHING PATTERN "*.hpp")

configure_package_config_file("${CMAKE_CURRENT_LIST_DIR}/package/rollsenseConfig.cmake.in"
  "${PROJECT_BINARY_DIR}/package/rollsenseConfig.cmake"
  INSTALL_DESTINATION "${ROLLSENSE_PACKAGE_INSTALL_DIR}"
  PATH_VARS CMAKE_INSTALL_INCLUDEDIR CMAKE_INSTALL_LIBDIR)
# rollsense is 0.x: a minor release may change the SDK (the plugin ABI
# version in each manifest changes with it), so only the same major.minor is
# compatible — 0.1.x satisfies find_package(rollsense 0.1), 0.2 does not.
# SameMajorVersion would call every 0.y compatible with every other.
write_basic_package_version_file("${PROJECT_BINARY_DIR}/package/rollsenseConfigVersion.cmake"
  VERSION "${PROJECT_VERSION}" COMPATIBILITY SameMinorVersion)
install(FILES
  "${PROJECT_BINARY_DIR}/package/rollsenseConfig.cmake"
  "${PROJECT_BINARY_DIR}/package/rollsenseConfigVersion.cmake"
  "${CMAKE_CURRENT_LIST_DIR}/RollsensePlugin.cmake"
  "${CMAKE_CURRENT_LIST_DIR}/RollsenseWarnings.cmake"
  DESTINATION "${ROLLSENSE_PACKAGE_INSTALL_DIR}" COMPONENT sdk)
