// bagged_trees against the classifier contract every plugin meets.
#include <catch2/catch.hpp>

#include "rollsense/testing/classifier_conformance.hpp"
#include "rollsense/bagged_trees/bagged_trees.hpp"
#include "rollsense/nearest_centroid/nearest_centroid.hpp"
#include "temp_dir.hpp"

TEST_CASE("bagged_trees passes the classifier conformance suite", "[bagged_trees][conformance]") {
    rollsense::testing::TempDir dir("bagged-trees-conformance");
    rollsense::testing::ClassifierConformance c;
    c.name = "bagged_trees";
    c.make = [] { return std::make_unique<rollsense::bagged_trees::BaggedTrees>(); };
    c.schema = rollsense::bagged_trees::bagged_trees_schema();
    c.params = {{"learners", std::int64_t{15}}, {"seed", std::int64_t{3}}};
    c.scratch = dir.path();
    c.others = {[] { return std::make_unique<rollsense::nearest_centroid::NearestCentroid>(); }};
    rollsense::testing::check_classifier_conformance(c);
}
