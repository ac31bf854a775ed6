// The fake GPIO chip: shared by name, levels, active-low, edges, one consumer per line.
#include <catch2/catch.hpp>

#include <thread>

#include "rollsense/hal/gpio.hpp"

using namespace rollsense;
using namespace rollsense::hal;
using namespace std::chrono_literals;

TEST_CASE("fake chips are shared process-wide by name", "[gpio][fake]") {
    auto a = FakeGpioChip::get("shared");
    auto b = FakeGpioChip::get("shared");
    CHECK(a == b);
    CHECK(a != FakeGpioChip::get("other"));
}

TEST_CASE("an input reads the logical level, honouring active_low", "[gpio][fake]") {
    auto chip = FakeGpioChip::get("levels");
    chip->reset();
    auto high_active = open_gpio_input({"fake:levels", 3, false, "test"});
    REQUIRE(high_active.ok());
    auto low_active = open_gpio_input({"fake:levels", 4, true, "test"});
    REQUIRE(low_active.ok());

    chip->set_input_level(3, true);
    chip->set_input_level(4, true);
    CHECK(high_active.value()->is_active().value());
    CHECK_FALSE(low_active.value()->is_active().value());  // pulled high = released e-stop
    chip->set_input_level(4, false);
    CHECK(low_active.value()->is_active().value());
    CHECK(chip->consumer(3) == "test");
}

TEST_CASE("edges are queued from the request on and consumed by wait_for_edge", "[gpio][fake]") {
    auto chip = FakeGpioChip::get("edges");
    chip->reset();
    chip->set_input_level(5, true);  // before the request: not reported
    auto in = open_gpio_input({"fake:edges", 5, false, "estop"});
    REQUIRE(in.ok());
    auto& line = *in.value();
    CHECK_FALSE(line.wait_for_edge(0ms).value());

    chip->set_input_level(5, false);  // falling
    chip->set_input_level(5, false);  // no change, no edge
    chip->set_input_level(5, true);   // rising
    CHECK(line.wait_for_edge(0ms).value());
    CHECK(line.wait_for_edge(0ms).value());
    CHECK_FALSE(line.wait_for_edge(0ms).value());

    // An edge from another thread wakes a waiter (the waiter's timeout is only a bound).
    std::thread presser([&] { chip->set_input_level(5, false); });
    CHECK(line.wait_for_edge(10s).value());
    presser.join();
}

TEST_CASE("an output drives the physical level and records its history", "[gpio][fake]") {
    auto chip = FakeGpioChip::get("outputs");
    chip->reset();
    {
        auto out = open_gpio_output({"fake:outputs", 7, false, "trigger"}, false);
        REQUIRE(out.ok());
        CHECK_FALSE(chip->output_level(7));
        REQUIRE(out.value()->set_active(true).ok());
        CHECK(chip->output_level(7));
        REQUIRE(out.value()->set_active(false).ok());
    }
    {
        auto inv = open_gpio_output({"fake:outputs", 8, true, "trigger"}, true);  // active = low
        REQUIRE(inv.ok());
        CHECK_FALSE(chip->output_level(8));
        REQUIRE(inv.value()->set_active(false).ok());
        CHECK(chip->output_level(8));
    }
    using H = std::vector<std::pair<unsigned, bool>>;
    CHECK(chip->output_history() == H{{7, false}, {7, true}, {7, false}, {8, false}, {8, true}});
}

TEST_CASE("a line has one consumer at a time, releasing frees it", "[gpio][fake]") {
    auto chip = FakeGpioChip::get("busy");
    chip->reset();
    auto first = open_gpio_input({"fake:busy", 1, false, "kernel-estop"});
    REQUIRE(first.ok());
    auto second = open_gpio_output({"fake:busy", 1, false, "other"}, false);
    REQUIRE_FALSE(second.ok());
    CHECK(second.error().code == ErrorCode::io_error);
    CHECK_THAT(second.error().message, Catch::Contains("fake:busy line 1") && Catch::Contains("kernel-estop"));
    first.value().reset();
    CHECK(chip->consumer(1).empty());
    CHECK(open_gpio_output({"fake:busy", 1, false, "other"}, false).ok());
}

TEST_CASE("bad fake specs are clear errors", "[gpio][fake]") {
    auto no_name = open_gpio_input({"fake:", 0, false, "x"});
    REQUIRE_FALSE(no_name.ok());
    CHECK(no_name.error().code == ErrorCode::invalid_argument);
    auto no_line = open_gpio_input({"fake:small", 999, false, "x"});
    REQUIRE_FALSE(no_line.ok());
    CHECK(no_line.error().code == ErrorCode::not_found);
    CHECK_THAT(no_line.error().message, Catch::Contains("no line 999"));
}
