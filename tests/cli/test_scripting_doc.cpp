// docs/scripting.md's API tables name every call a script can make: the keys
// of the `rs` table as a script sees them (so nothing registered from any
// layer is missed), and the methods of the handles, read from the C++
// registration tables.
#include <catch2/catch.hpp>

#include <regex>
#include <set>
#include <sstream>

#include "cli_helpers.hpp"

namespace {
using namespace rollsense::testing;
namespace fs = std::filesystem;

// The "## The API" section of docs/scripting.md, up to the next "## " heading.
std::string api_section() {
    const std::string doc = read_file(fs::path(ROLLSENSE_SOURCE_DIR) / "docs" / "scripting.md");
    const auto start = doc.find("\n## The API");
    REQUIRE(start != std::string::npos);
    const auto end = doc.find("\n## ", start + 1);
    return doc.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

// Documented means in a table row, written as a call: `rs.name(` or `rs.name{`.
bool documents_call(const std::string& section, const std::string& prefix, const std::string& name) {
    std::istringstream in(section);
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("|", 0) != 0) continue;
        for (const char open : {'(', '{'})
            if (line.find(prefix + name + open) != std::string::npos) return true;
    }
    return false;
}

// Method names of every `methods[]` luaL_Reg table in a source file.
std::set<std::string> registered_methods(const fs::path& file) {
    const std::string src = read_file(file);
    std::set<std::string> out;
    const auto at = src.find("luaL_Reg methods[]");
    if (at == std::string::npos) return out;
    const auto end = src.find("{nullptr, nullptr}", at);
    const std::string table = src.substr(at, end - at);
    const std::regex entry(R"re(\{"(\w+)",)re");
    for (std::sregex_iterator it(table.begin(), table.end(), entry), stop; it != stop; ++it) out.insert((*it)[1]);
    return out;
}

}  // namespace

TEST_CASE("docs/scripting.md lists every rs.* call a script can make") {
    TempDir dir("rollsense-cli-rs-keys");
    write_file(dir / "keys.lua",
               "local rs = require 'rollsense'\n"
               "local names = {}\n"
               "for k in pairs(rs) do names[#names + 1] = k end\n"
               "table.sort(names)\n"
               "rs.write_output('rs-keys.txt', table.concat(names, '\\n') .. '\\n')\n");
    const auto r = run_rollsense("run " + shell_quoted(dir / "keys.lua") + " --profile mock --out " + shell_quoted(dir / "out"));
    INFO(r.output);
    REQUIRE(r.status == 0);
    std::istringstream keys(read_file(dir / "out" / "rs-keys.txt"));
    const std::string section = api_section();
    std::size_t n = 0;
    for (std::string key; std::getline(keys, key);) {
        if (key.empty()) continue;
        ++n;
        INFO("rs." << key << " is registered but docs/scripting.md's API table does not list it as `rs." << key
                   << "(...)` or `rs." << key << "{...}`");
        CHECK(documents_call(section, "rs.", key));
    }
    CHECK(n >= 30);  // the enumeration itself worked: the API has more than thirty calls
}

TEST_CASE("docs/scripting.md lists every method of the joint, device and classifier handles") {
    const fs::path src(ROLLSENSE_SOURCE_DIR);
    const std::string section = api_section();
    for (const auto& file : {src / "kernel/src/runtime/lua/api_joint.cpp", src / "kernel/src/runtime/lua/api_device.cpp",
                             src / "analysis/src/analysis/lua/api_learn.cpp"}) {
        const auto methods = registered_methods(file);
        INFO(file.string());
        CHECK(!methods.empty());
        for (const auto& m : methods) {
            INFO(":" << m << " is registered in " << file.filename().string() << " but not documented");
            CHECK(documents_call(section, ":", m));
        }
    }
}
