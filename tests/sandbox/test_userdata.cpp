// Item 2 of issue 22: a script cannot reach the metatable of a userdata the
// kernel hands it (joints, devices, classifiers), so it cannot call __gc on a
// live object nor rewrite its methods.
#include <catch2/catch.hpp>

#include "limited_child.hpp"
#include "rollsense/nearest_centroid/nearest_centroid.hpp"

using namespace rollsense;

namespace {

// A small trained nearest-centroid model on disk.
void save_model(const kt::fs::path& file) {
    FeatureTable t;
    t.feature_names = {"x", "constant"};
    t.class_names = {"A", "B"};
    for (double x : {0.0, 2.0, 4.0, 6.0}) {
        t.x.push_back(x);
        t.x.push_back(5.0);
        t.y.push_back(x < 3 ? 0 : 1);
        ++t.rows;
    }
    nearest_centroid::NearestCentroid c;
    REQUIRE(c.train(t).ok());
    REQUIRE(c.save(file).ok());
}

}  // namespace

TEST_CASE("a classifier's __gc cannot be called from a script", "[sandbox][userdata]") {
    kt::TempDir dir;
    save_model(dir / "m.rsm");
    auto r = sandbox_test::run_script_limited(dir, R"(local rs = require 'rollsense'
local clf = rs.classifier{ model = ')" + (dir / "m.rsm").string() + R"(', classifier = 'nearest_centroid' }
local mt = getmetatable(clf)
if type(mt) == 'table' and mt.__gc then mt.__gc(clf) end
assert(type(mt) == 'string', 'the metatable of a classifier is reachable')
assert(#clf:classes() == 2)
)");
    INFO(r.text);
    REQUIRE(r.exited);  // not SIGSEGV
    CHECK(r.text == "ok");
}

TEST_CASE("joint and device metatables are protected", "[sandbox][userdata]") {
    kt::TempDir dir;
    auto r = sandbox_test::run_script_limited(dir, R"(local rs = require 'rollsense'
local j, d = rs.joint('finger'), rs.device('hand')
assert(type(getmetatable(j)) == 'string', 'joint metatable reachable')
assert(type(getmetatable(d)) == 'string', 'device metatable reachable')
local ok, err = pcall(setmetatable, j, {})
assert(not ok)
assert(j:name() == 'finger')
)");
    INFO(r.text);
    REQUIRE(r.exited);
    CHECK(r.text == "ok");
}
