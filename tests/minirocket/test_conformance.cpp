// minirocket against the classifier contract every plugin meets (on the
// suite's separable table of prepared series).
#include <catch2/catch.hpp>

#include "rollsense/bagged_trees/bagged_trees.hpp"
#include "rollsense/minirocket/minirocket.hpp"
#include "rollsense/testing/classifier_conformance.hpp"
#include "temp_dir.hpp"

TEST_CASE("minirocket passes the classifier conformance suite", "[minirocket][conformance]") {
    rollsense::testing::TempDir dir("minirocket-conformance");
    rollsense::testing::ClassifierConformance c;
    c.name = "minirocket";
    c.make = [] { return std::make_unique<rollsense::minirocket::MiniRocket>(); };
    c.schema = rollsense::minirocket::minirocket_schema();
    c.params = {{"num_features", std::int64_t{840}}, {"seed", std::int64_t{3}}, {"threads", std::int64_t{2}}};
    c.scratch = dir.path();
    c.others = {[] { return std::make_unique<rollsense::bagged_trees::BaggedTrees>(); }};
    rollsense::testing::check_classifier_conformance(c);
}
