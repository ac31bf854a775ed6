// The classifier end to end: accuracy on separable shapes, scores, errors,
// determinism and the plugin manifest.
#include <catch2/catch.hpp>

#include <boost/dll/shared_library.hpp>

#include "rollsense/minirocket/minirocket.hpp"
#include "rollsense/plugin.hpp"
#include "shapes.hpp"

using namespace rollsense;
using namespace rollsense::minirocket;

namespace {
double accuracy(const MiniRocket& m, const FeatureTable& test) {
    std::size_t right = 0;
    for (std::size_t i = 0; i < test.rows; ++i) {
        auto p = m.predict(test.row(i));
        REQUIRE(p.ok());
        right += p->label == test.y[i];
    }
    return static_cast<double>(right) / static_cast<double>(test.rows);
}
}  // namespace

TEST_CASE("minirocket separates bump, two bumps and ramp on held-out series", "[minirocket][classifier]") {
    const auto data = shapes::make(60, 96, 5);  // 180 rows, classes interleaved
    const auto train = shapes::slice(data, 0, 120), test = shapes::slice(data, 120, 180);
    MiniRocket m;
    CHECK(m.input() == ClassifierInput::series);
    CHECK(m.search_space(120, data.cols()).empty());
    REQUIRE(m.train(train).ok());
    CHECK(accuracy(m, test) >= 0.95);
    CHECK(m.model().transform.features() == 9996);
    CHECK(m.model().alpha > 0.0);

    auto p = m.predict(test.row(0));
    REQUIRE(p.ok());
    REQUIRE(p->scores.size() == 3);
    double sum = 0.0;
    for (double s : p->scores) {
        CHECK(s > 0.0);
        sum += s;
    }
    CHECK(sum == Approx(1.0));
    CHECK(std::max_element(p->scores.begin(), p->scores.end()) - p->scores.begin() == p->label);
    CHECK(p->class_name == data.class_names[static_cast<std::size_t>(p->label)]);

    auto many = m.predict_many(test.x, test.rows);
    REQUIRE(many.ok());
    for (std::size_t i = 0; i < test.rows; ++i) CHECK((*many)[i].scores == m.predict(test.row(i))->scores);
}

TEST_CASE("minirocket is deterministic by seed and does not depend on threads", "[minirocket][classifier]") {
    const auto data = shapes::make(20, 64, 9);
    Options o;
    o.transform.num_features = 2000;
    o.threads = 1;
    MiniRocket a(o);
    o.threads = 2;
    MiniRocket b(o);
    o.transform.seed = 2;
    MiniRocket c(o);
    REQUIRE(a.train(data).ok());
    REQUIRE(b.train(data).ok());
    REQUIRE(c.train(data).ok());
    CHECK(a.model().weights == b.model().weights);
    CHECK(a.model().transform.biases() == b.model().transform.biases());
    CHECK(a.model().transform.biases() != c.model().transform.biases());
    CHECK(a.predict(data.row(3))->scores == b.predict(data.row(3))->scores);
}

TEST_CASE("minirocket refuses what it cannot use", "[minirocket][classifier][errors]") {
    MiniRocket m;
    const auto data = shapes::make(10, 32, 1);
    auto early = m.predict(data.row(0));
    REQUIRE(!early.ok());
    CHECK(early.error().code == ErrorCode::state_error);
    CHECK(early.error().message.find("before train") != std::string::npos);

    FeatureTable features;
    features.feature_names = {"a", "b"};
    features.class_names = {"x", "y"};
    features.rows = 2;
    features.x = {1, 2, 3, 4};
    features.y = {0, 1};
    auto s = m.train(features);
    REQUIRE(!s.ok());
    CHECK(s.error().message.find("prepared series") != std::string::npos);

    auto bad_label = data;
    bad_label.y[4] = 7;
    CHECK(!m.train(bad_label).ok());
    auto not_finite = data;
    not_finite.x[40] = std::nan("");
    auto nf = m.train(not_finite);
    REQUIRE(!nf.ok());
    CHECK(nf.error().message.find("channel 'p1' sample 8") != std::string::npos);
    auto short_series = data;
    short_series.series_length = 4;
    short_series.x.resize(short_series.rows * 12);
    CHECK(!m.train(short_series).ok());

    REQUIRE(m.train(data).ok());
    std::vector<double> wrong(data.cols() - 1, 0.0);
    auto w = m.predict(wrong);
    REQUIRE(!w.ok());
    CHECK(w.error().code == ErrorCode::invalid_argument);
    CHECK(w.error().message.find("3 channels × 32 samples = 96") != std::string::npos);
    std::vector<double> nan_row(data.row(0).begin(), data.row(0).end());
    nan_row[33] = std::numeric_limits<double>::infinity();
    CHECK(!m.predict(nan_row).ok());
}

TEST_CASE("schema parameters become options, and bad ones are refused", "[minirocket][classifier]") {
    ParamSet p;
    p.set("num_features", std::int64_t{5000});
    p.set("seed", std::int64_t{7});
    p.set("alphas", std::int64_t{4});
    auto o = options_from(p);
    REQUIRE(o.ok());
    CHECK(o->transform.num_features == 5000);
    CHECK(o->transform.seed == 7);
    CHECK(o->alphas == 4);
    p.set("alpha_log10_low", 4.0);
    CHECK(!options_from(p).ok());  // above the high end
    const auto schema = minirocket_schema();
    CHECK(std::any_of(schema.begin(), schema.end(), [](const auto& s) { return s.name == "num_features"; }));
}

TEST_CASE("the minirocket module exports a series classifier manifest", "[minirocket][plugin]") {
    const auto path = std::filesystem::path(ROLLSENSE_PLUGIN_DIR) / "librollsense_minirocket.so";
    boost::dll::shared_library lib(path);
    auto manifest_fn = lib.get_alias<PluginManifestFn>(kPluginManifestSymbol);
    const PluginManifest* m = manifest_fn();
    REQUIRE(m->magic == kPluginMagic);
    CHECK(std::string(m->name) == "minirocket");
    CHECK(m->kind == PluginKind::classifier);
    REQUIRE(m->create_classifier != nullptr);
    Classifier* c = m->create_classifier();
    CHECK(c->input() == ClassifierInput::series);
    const auto data = shapes::make(15, 48, 2);
    REQUIRE(c->train(data).ok());
    CHECK(c->predict(data.row(0)).ok());
    m->destroy(c);
}
