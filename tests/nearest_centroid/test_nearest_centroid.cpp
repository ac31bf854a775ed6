// nearest_centroid's arithmetic on tables small enough to check by hand, its
// parameters and refusals, and the built plugin module.
#include <catch2/catch.hpp>

#include <cmath>

#include <boost/dll/shared_library.hpp>

#include "rollsense/nearest_centroid/nearest_centroid.hpp"
#include "rollsense/plugin.hpp"

using namespace rollsense;
using rollsense::nearest_centroid::NearestCentroid;

namespace {

// Class A at x = 0, 2; class B at x = 4, 6; a constant second feature; a
// third class "none" without trials.
FeatureTable two_groups() {
    FeatureTable t;
    t.feature_names = {"x", "constant"};
    t.class_names = {"A", "B", "none"};
    for (double x : {0.0, 2.0, 4.0, 6.0}) {
        t.x.push_back(x);
        t.x.push_back(5.0);
        t.y.push_back(x < 3 ? 0 : 1);
        ++t.rows;
    }
    return t;
}

NearestCentroid configured(double shrink, double temperature = 1.0) {
    NearestCentroid c;
    ParamSet p;
    p.set("shrink", shrink);
    p.set("temperature", temperature);
    REQUIRE(c.on_configure(p, {}).ok());
    return c;
}

const double kSd = std::sqrt(20.0 / 3.0);  // sample sd of 0, 2, 4, 6
const double kCentroid = 2.0 / kSd;        // |class mean − 3| / sd

}  // namespace

TEST_CASE("nearest_centroid standardises, averages and softmaxes as documented", "[nearest_centroid]") {
    auto c = configured(0.0);
    REQUIRE(c.train(two_groups()).ok());
    const auto& m = c.model();
    CHECK(m.mean[0] == Approx(3.0));
    CHECK(m.sd[0] == Approx(kSd));
    CHECK(m.sd[1] == 0.0);  // constant: ignored
    CHECK(m.centroids[0] == Approx(-kCentroid));
    CHECK(m.centroids[2] == Approx(kCentroid));
    CHECK(m.class_rows == std::vector<std::uint64_t>{2, 2, 0});

    auto p = c.predict(std::vector<double>{1.0, 5.0});  // exactly on A's centroid
    REQUIRE(p.ok());
    CHECK(p->class_name == "A");
    const double far = 2.0 * kCentroid;  // distance to B
    CHECK(p->scores[0] == Approx(1.0 / (1.0 + std::exp(-far))));
    CHECK(p->scores[1] == Approx(std::exp(-far) / (1.0 + std::exp(-far))));
    CHECK(p->scores[2] == 0.0);  // no trials, no centroid

    // The ignored feature does not matter, whatever its value.
    auto q = c.predict(std::vector<double>{1.0, 1000.0});
    REQUIRE(q.ok());
    CHECK(q->scores == p->scores);

    auto b = c.predict(std::vector<double>{5.5, 5.0});
    REQUIRE(b.ok());
    CHECK(b->label == 1);

    auto tie = c.predict(std::vector<double>{3.0, 5.0});  // half way: the first class, even scores
    REQUIRE(tie.ok());
    CHECK(tie->label == 0);
    CHECK(tie->scores[0] == Approx(0.5));
}

TEST_CASE("nearest_centroid: shrink pulls centroids together, temperature only flattens scores", "[nearest_centroid]") {
    auto half = configured(0.5);
    REQUIRE(half.train(two_groups()).ok());
    CHECK(half.model().centroids[0] == Approx(-(kCentroid - 0.5)));
    CHECK(half.model().centroids[2] == Approx(kCentroid - 0.5));

    auto all = configured(kCentroid + 0.01);  // every coordinate thresholded to 0: no information left
    REQUIRE(all.train(two_groups()).ok());
    auto p = all.predict(std::vector<double>{6.0, 5.0});
    REQUIRE(p.ok());
    CHECK(p->scores[0] == Approx(0.5));
    CHECK(p->scores[1] == Approx(0.5));

    auto cold = configured(0.0, 1.0), warm = configured(0.0, 10.0);
    REQUIRE(cold.train(two_groups()).ok());
    REQUIRE(warm.train(two_groups()).ok());
    const std::vector<double> x{1.5, 5.0};
    CHECK(cold.predict(x)->label == warm.predict(x)->label);
    CHECK(warm.predict(x)->scores[0] < cold.predict(x)->scores[0]);
    CHECK(warm.predict(x)->scores[0] > 0.5);
}

TEST_CASE("nearest_centroid refuses what it cannot use, naming it", "[nearest_centroid]") {
    auto c = configured(0.0);
    auto nan_table = two_groups();
    nan_table.x[3] = std::nan("");
    auto st = c.train(nan_table);
    REQUIRE_FALSE(st.ok());
    CHECK_THAT(st.message(), Catch::Contains("row 1") && Catch::Contains("'constant'"));

    FeatureTable series;
    series.channel_names = {"ch1"};
    series.series_length = 4;
    series.class_names = {"A"};
    series.rows = 1;
    series.x = {1, 2, 3, 4};
    series.y = {0};
    CHECK_THAT(c.train(series).message(), Catch::Contains("feature vectors"));
    CHECK_THAT(c.train(FeatureTable{}).message(), Catch::Contains("no training trials"));

    REQUIRE(c.train(two_groups()).ok());
    CHECK_THAT(c.predict(std::vector<double>{std::nan(""), 5.0}).error().message, Catch::Contains("'x'"));
    CHECK_THAT(c.predict(std::vector<double>{1.0}).error().message, Catch::Contains("got 1 features"));

    NearestCentroid bad;
    ParamSet p;
    p.set("shrink", -1.0);
    CHECK_THAT(bad.on_configure(p, {}).message(), Catch::Contains("shrink"));
    p.set("shrink", 0.0);
    p.set("temperature", 0.0);
    CHECK_THAT(bad.on_configure(p, {}).message(), Catch::Contains("temperature"));
}

TEST_CASE("nearest_centroid declares shrink as its search space", "[nearest_centroid]") {
    const NearestCentroid c;
    const auto s = c.search_space(100, 13);
    REQUIRE(s.size() == 1);
    CHECK(s[0].name == "shrink");
    CHECK(s[0].scale == SearchDimension::Scale::real_linear);
    CHECK(s[0].low == 0.0);
    CHECK(s[0].high == 2.0);
    CHECK(c.input() == ClassifierInput::features);
}

TEST_CASE("the nearest_centroid module exports a classifier manifest", "[nearest_centroid][plugin]") {
    const auto path = std::filesystem::path(ROLLSENSE_PLUGIN_DIR) / "librollsense_nearest_centroid.so";
    boost::dll::shared_library lib(path);
    auto manifest_fn = lib.get_alias<PluginManifestFn>(kPluginManifestSymbol);
    const PluginManifest* m = manifest_fn();
    REQUIRE(m->magic == kPluginMagic);
    CHECK(std::string(m->name) == "nearest_centroid");
    CHECK(m->kind == PluginKind::classifier);
    REQUIRE(m->create_classifier != nullptr);
    const auto schema = m->schema();
    CHECK(std::any_of(schema.begin(), schema.end(), [](const auto& s) { return s.name == "shrink"; }));
    Classifier* c = m->create_classifier();
    REQUIRE(c->train(two_groups()).ok());
    CHECK(c->predict(std::vector<double>{6.0, 5.0})->class_name == "B");
    m->destroy(c);
}
