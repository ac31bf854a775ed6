// nearest_centroid against the classifier contract every plugin meets.
#include <catch2/catch.hpp>

#include "rollsense/testing/classifier_conformance.hpp"
#include "rollsense/bagged_trees/bagged_trees.hpp"
#include "rollsense/nearest_centroid/nearest_centroid.hpp"
#include "temp_dir.hpp"

TEST_CASE("nearest_centroid passes the classifier conformance suite", "[nearest_centroid][conformance]") {
    rollsense::testing::TempDir dir("nearest-centroid-conformance");
    rollsense::testing::ClassifierConformance c;
    c.name = "nearest_centroid";
    c.make = [] { return std::make_unique<rollsense::nearest_centroid::NearestCentroid>(); };
    c.schema = rollsense::nearest_centroid::nearest_centroid_schema();
    c.params = {{"shrink", 0.25}};
    c.scratch = dir.path();
    c.others = {[] {
        rollsense::bagged_trees::EnsembleOptions o;
        o.learners = 5;
        return std::make_unique<rollsense::bagged_trees::BaggedTrees>(o);
    }};
    rollsense::testing::check_classifier_conformance(c);
}
