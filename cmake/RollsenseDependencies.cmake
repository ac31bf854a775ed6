# Every dependency comes from a Debian 12 package (see README: apt-get line).
find_package(PkgConfig REQUIRED)
find_package(Threads REQUIRED)

# Lua 5.4 compiled as C++ (liblua5.4-dev ships both builds): a Lua error raised
# inside a C++ binding then unwinds C++ destructors instead of longjmp-ing past them.
pkg_check_modules(LUA REQUIRED IMPORTED_TARGET lua5.4-c++)
pkg_check_modules(GPIOD REQUIRED IMPORTED_TARGET libgpiod)
pkg_check_modules(MODBUS REQUIRED IMPORTED_TARGET libmodbus)
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
# Boost.DLL is header-only when it uses std::filesystem (BOOST_DLL_USE_STD_FS).
# The version is also what the installed package asks for (rollsenseConfig.cmake).
set(ROLLSENSE_BOOST_MIN_VERSION 1.74)
find_package(Boost ${ROLLSENSE_BOOST_MIN_VERSION} REQUIRED)
add_library(rollsense_boost_dll INTERFACE)
target_link_libraries(rollsense_boost_dll INTERFACE Boost::boost ${CMAKE_DL_LIBS})
target_compile_definitions(rollsense_boost_dll INTERFACE BOOST_DLL_USE_STD_FS)

if(ROLLSENSE_BUILD_TESTS)
  find_package(Catch2 2.13 REQUIRED)
  include(Catch)
endif()
