// The Linux i2c-dev backend on a machine without /dev/i2c-*: clear errors,
// no crash. Hardware tests are hidden ([.hw]); run them on a rig with
//   ROLLSENSE_TEST_I2C_BUS=/dev/i2c-1 test_hal_i2c "[.hw]"
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>

#include "rollsense/hal/i2c.hpp"
#include "rollsense/hal/takkstrip.hpp"

using namespace rollsense;
using namespace rollsense::hal;

TEST_CASE("a missing /dev/i2c-N is 'not found' with the way out", "[i2c][linux]") {
    const std::string path = "/dev/i2c-247";
    if (std::filesystem::exists(path)) {
        WARN(path << " exists on this machine; skipping the missing-node check");
        return;
    }
    auto r = open_i2c_bus(path);
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().code == ErrorCode::not_found);
    CHECK_THAT(r.error().message, Catch::Contains(path) && Catch::Contains("modprobe i2c-dev") &&
                                      Catch::Contains("i2cdetect -l"));
    // "N" is the same bus.
    auto n = open_i2c_bus("247");
    REQUIRE_FALSE(n.ok());
    CHECK(n.error().code == ErrorCode::not_found);
    CHECK_THAT(n.error().message, Catch::Contains(path));
}

TEST_CASE("a device node that is not an i2c adapter is refused at open", "[i2c][linux]") {
    auto r = open_i2c_bus("/dev/null");
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().code == ErrorCode::io_error);
    CHECK_THAT(r.error().message, Catch::Contains("/dev/null") && Catch::Contains("not an i2c-dev"));
}

TEST_CASE("permission denied names the node and the group to join", "[i2c][linux]") {
    if (::geteuid() == 0) {
        WARN("running as root: file permissions do not apply, skipping");
        return;
    }
    const auto path = std::filesystem::temp_directory_path() / ("rollsense-i2c-perm-" + std::to_string(::getpid()));
    { std::FILE* f = std::fopen(path.c_str(), "w"); REQUIRE(f); std::fclose(f); }
    std::filesystem::permissions(path, std::filesystem::perms::none);
    auto r = open_i2c_bus(path.string());
    std::filesystem::remove(path);
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().code == ErrorCode::io_error);
    CHECK_THAT(r.error().message, Catch::Contains("permission denied") && Catch::Contains("'i2c' group"));
}

TEST_CASE("probe a real TakkStrip", "[.hw][i2c][linux]") {
    const char* bus_spec = std::getenv("ROLLSENSE_TEST_I2C_BUS");
    REQUIRE(bus_spec);  // e.g. /dev/i2c-1 with a TakkStrip (strip 0) attached
    auto bus = open_i2c_bus(bus_spec);
    INFO((bus.ok() ? std::string() : bus.error().message));
    REQUIRE(bus.ok());
    CHECK(bus.value()->functionality().smbus_quick);
    takkstrip::Host host(bus.value());
    auto report = takkstrip::probe_strips(host, {0});
    REQUIRE(report.ok());
    CHECK(report->all_strips_address_acked);
    REQUIRE_FALSE(report->sensors.empty());
    for (const auto& p : report->sensors) {
        INFO(takkstrip::describe_select(p.select_address) << ": " << p.chip.message());
        CHECK(p.chip.ok());
        REQUIRE(p.coefficients);
        REQUIRE(p.reading);
        const double kpa = mpl115a::pressure_kpa(*p.coefficients, *p.reading);
        CHECK(kpa > 80.0);  // room air anywhere a robot lab is likely to be
        CHECK(kpa < 110.0);
    }
}
