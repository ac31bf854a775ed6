// `rollsense report DATASET` end to end, then the page opened in headless
// Chromium: the screenshot must exist and show a rendered page (many colours,
// a fair share of non-background pixels), not a blank or single-colour image.
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <set>
#include <unistd.h>

#include "png_image.hpp"
#include "run_command.hpp"
#include "synthetic_dataset.hpp"

namespace fs = std::filesystem;

namespace {

using rollsense::testing::run_command;

}  // namespace

TEST_CASE("rollsense report writes a page that headless Chromium renders", "[report][browser]") {
    const fs::path chromium = "/usr/bin/chromium";
    if (!fs::exists(chromium))
        FAIL("/usr/bin/chromium is missing: install Debian's browser with 'apt-get install -y chromium' "
             "(tools/bootstrap.sh lists it) to run the report's rendering test");

    const fs::path root = fs::temp_directory_path() / ("rollsense-test-report-browser-" + std::to_string(::getpid()));
    fs::remove_all(root);
    rollsense::test::write_synthetic_dataset(root / "dataset");
    const fs::path page = root / "out" / "page.html";
    fs::create_directories(page.parent_path());
    auto r = run_command(std::string(ROLLSENSE_BIN_DIR) + "/rollsense report " + (root / "dataset").string() + " -o " +
                  page.string() + " --folds 3 --repeats 1 --set learners=10");
    INFO(r.output);
    REQUIRE(r.status == 0);
    CHECK_THAT(r.output, Catch::Contains("report: " + page.string()) && Catch::Contains("accuracy"));
    REQUIRE(fs::exists(page));

    const fs::path shot = root / "screenshot.png";
    r = run_command(chromium.string() +
              " --headless --no-sandbox --disable-gpu --disable-background-networking --disable-component-update"
              " --disable-sync --no-first-run --user-data-dir=" + (root / "chromium-profile").string() +
              " --screenshot=" + shot.string() + " --window-size=1200,2000 file://" + page.string());
    INFO(r.output);
    REQUIRE(fs::exists(shot));
    REQUIRE(fs::file_size(shot) > 0);
    const auto img = rollsense::test::read_png(shot);
    CHECK(img.width == 1200);
    CHECK(img.height == 2000);
    std::set<std::uint32_t> colours;
    std::size_t non_white = 0;
    for (std::size_t i = 0; i + 2 < img.rgb.size(); i += 3) {
        const std::uint32_t c = (std::uint32_t{img.rgb[i]} << 16) | (std::uint32_t{img.rgb[i + 1]} << 8) | img.rgb[i + 2];
        colours.insert(c);
        non_white += c != 0xffffffu;
    }
    INFO("distinct colours " << colours.size() << ", non-white pixels " << non_white);
    // Text (anti-aliased), the blue shading of the matrix and the rules give
    // hundreds of colours; a failed render is one colour (white or black).
    CHECK(colours.size() > 50);
    CHECK(non_white > img.rgb.size() / 3 / 50);
    fs::remove_all(root);
}
