// Conformance tests every classifier plugin runs (one contract, one suite;
// see conformance.hpp for sensors and actuators). Header-only; call from a
// Catch2 TEST_CASE:
//
//     rollsense::testing::ClassifierConformance c;
//     c.name = "my_classifier";
//     c.make = [] { return std::make_unique<MyClassifier>(); };
//     c.schema = my_classifier_schema();
//     c.scratch = temp_dir.path();
//     rollsense::testing::check_classifier_conformance(c);
//
// What it holds a classifier to: it trains and predicts on a small separable
// table of the input it declares (feature vectors or prepared series); every
// prediction has one score per class, each in [0, 1], summing to 1, and a
// label that is the class scored highest, named by its class name; class names (spaces included) survive
// training, save and load; a reloaded model predicts exactly what the saved one
// did; the same parameters and data give the same predictions and the same
// model bytes; predicting before training or loading is an error; a model file
// written by another classifier, a damaged one, a missing one and one whose
// format version is newer than the plugin reads are refused with an error,
// never a crash; every search-space dimension is a parameter of the schema
// with a valid range whose ends the schema and the classifier accept.
//
// Model files are assumed to follow the project's convention (bagged_trees'
// model_file.cpp): the first line is "<magic> <version>". A format that does
// not can supply `newer_version` itself.
#pragma once

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "rollsense/classifier.hpp"
#include "rollsense/params.hpp"

namespace rollsense::testing {

struct ClassifierConformance {
    std::string name;                                   // the plugin's name (for messages)
    std::function<std::unique_ptr<Classifier>()> make;  // a new, unconfigured instance
    ParamSchema schema;                                 // the plugin's parameter schema
    std::map<std::string, ParamValue> params;           // raw values (validated against `schema`)
    std::filesystem::path scratch;                      // an empty folder for model files
    // Other classifiers whose saved models this one must refuse to load.
    std::vector<std::function<std::unique_ptr<Classifier>()>> others;
    // The text of a saved model with its format version raised by one;
    // default: the first line's last word is the version.
    std::function<std::string(const std::string& saved)> newer_version;
    double min_training_accuracy = 0.9;  // on the separable table
};

namespace detail {

inline std::string read_all(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void write_all(const std::filesystem::path& p, const std::string& text) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out << text;
}

inline std::string bump_first_line_version(const std::string& saved) {
    const auto nl = saved.find('\n');
    REQUIRE(nl != std::string::npos);
    const std::string first = saved.substr(0, nl);
    const auto sp = first.rfind(' ');
    REQUIRE(sp != std::string::npos);
    const long version = std::stol(first.substr(sp + 1));
    return first.substr(0, sp + 1) + std::to_string(version + 1) + saved.substr(nl);
}

// Deterministic uniform [0, 1).
struct Lcg {
    std::uint64_t s;
    double next() {
        s = s * 6364136223846793005ULL + 1442695040888963407ULL;
        return static_cast<double>(s >> 11) / 9007199254740992.0;
    }
};

}  // namespace detail

// Three well separated classes (one name with a space), 20 trials each, of
// the given input kind: feature vectors of 4 columns (the class shifts the
// first two, the third is constant, the fourth noise), or 2 channels × 12
// samples whose level and slope the class sets.
inline FeatureTable separable_table(ClassifierInput input, std::uint64_t seed = 7) {
    FeatureTable t;
    t.class_names = {"C1", "big cylinder", "P2"};
    if (input == ClassifierInput::series) {
        t.channel_names = {"ch1", "ch2"};
        t.series_length = 12;
    } else {
        t.feature_names = {"F1", "F2", "F3", "F4"};
    }
    detail::Lcg g{seed};
    for (int i = 0; i < 20; ++i)
        for (int c = 0; c < 3; ++c) {
            const double k = static_cast<double>(c);
            if (input == ClassifierInput::series) {
                for (std::size_t s = 0; s < t.series_length; ++s) t.x.push_back(k * 2.0 + 0.3 * (g.next() - 0.5));
                for (std::size_t s = 0; s < t.series_length; ++s)
                    t.x.push_back(k * 0.2 * static_cast<double>(s) + 0.3 * (g.next() - 0.5));
            } else {
                t.x.push_back(k * 3.0 + g.next());
                t.x.push_back(-k * 2.0 + g.next());
                t.x.push_back(1.5);
                t.x.push_back(g.next());
            }
            t.y.push_back(c);
            ++t.rows;
        }
    return t;
}

inline std::unique_ptr<Classifier> make_configured(const ClassifierConformance& c,
                                                   const std::map<std::string, ParamValue>& raw) {
    auto params = validate_params(c.schema, raw, c.name + " conformance");
    INFO((params ? std::string() : params.error().message));
    REQUIRE(params.ok());
    auto clf = c.make();
    REQUIRE(clf);
    auto st = clf->on_configure(*params, {});
    INFO(st.message());
    REQUIRE(st.ok());
    return clf;
}

inline std::vector<Prediction> predict_all(const Classifier& clf, const FeatureTable& t) {
    std::vector<Prediction> out;
    for (std::size_t r = 0; r < t.rows; ++r) {
        auto p = clf.predict(t.row(r));
        INFO("row " << r << ": " << (p ? std::string() : p.error().message));
        REQUIRE(p.ok());
        out.push_back(*p);
    }
    return out;
}

inline void check_same_predictions(const std::vector<Prediction>& a, const std::vector<Prediction>& b) {
    REQUIRE(a.size() == b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        INFO("row " << i);
        CHECK(a[i].label == b[i].label);
        CHECK(a[i].class_name == b[i].class_name);
        CHECK(a[i].scores == b[i].scores);  // exactly: a reloaded model is the same model
    }
}

inline void check_classifier_conformance(const ClassifierConformance& c) {
    REQUIRE(c.make);
    REQUIRE(!c.scratch.empty());
    std::filesystem::create_directories(c.scratch);
    const auto kind = c.make()->input();
    const FeatureTable table = separable_table(kind);
    const auto file = [&](const std::string& n) { return c.scratch / (c.name + "-" + n); };

    SECTION("predict before train or load is an error, not a crash") {
        auto clf = make_configured(c, c.params);
        auto p = clf->predict(table.row(0));
        REQUIRE_FALSE(p.ok());
        CHECK_FALSE(p.error().message.empty());
        CHECK_FALSE(clf->save(file("untrained")).ok());
    }

    SECTION("trains and predicts: one score per class, in [0, 1], summing to 1; class names kept") {
        auto clf = make_configured(c, c.params);
        auto st = clf->train(table);
        INFO(st.message());
        REQUIRE(st.ok());
        CHECK(clf->class_names() == table.class_names);
        const auto preds = predict_all(*clf, table);
        std::size_t right = 0;
        for (std::size_t r = 0; r < table.rows; ++r) {
            const auto& p = preds[r];
            INFO("row " << r);
            REQUIRE(p.scores.size() == table.class_names.size());
            double sum = 0.0;
            for (double s : p.scores) {
                CHECK(s >= 0.0);
                CHECK(s <= 1.0);
                sum += s;
            }
            CHECK(sum == Approx(1.0).margin(1e-9));
            REQUIRE(p.label >= 0);
            REQUIRE(static_cast<std::size_t>(p.label) < table.class_names.size());
            CHECK(p.class_name == table.class_names[static_cast<std::size_t>(p.label)]);
            // The predicted class is the one scored highest, within the tolerance the program allows when it checks a
            // plugin's predictions (1e-6, analysis/learn/checked_classifier.cpp): evaluate, predict and the Lua calls
            // refuse any other (plugin review: a classifier this suite passed was refused in use).
            const double top = *std::max_element(p.scores.begin(), p.scores.end());
            INFO("label " << p.label << " scored " << p.scores[static_cast<std::size_t>(p.label)] << ", the top score is "
                          << top);
            CHECK(p.scores[static_cast<std::size_t>(p.label)] >= top - 1e-6);
            right += p.label == table.y[r];
        }
        CHECK(static_cast<double>(right) / static_cast<double>(table.rows) >= c.min_training_accuracy);
        // A row of the wrong width is refused.
        std::vector<double> short_row(table.cols() - 1, 0.0);
        CHECK_FALSE(clf->predict(short_row).ok());
    }

    SECTION("save, load: the same class names and exactly the same predictions") {
        auto clf = make_configured(c, c.params);
        REQUIRE(clf->train(table).ok());
        REQUIRE(clf->save(file("model")).ok());
        auto loaded = make_configured(c, c.params);
        auto st = loaded->load(file("model"));
        INFO(st.message());
        REQUIRE(st.ok());
        CHECK(loaded->class_names() == table.class_names);
        check_same_predictions(predict_all(*clf, table), predict_all(*loaded, table));
        // Saving the loaded model writes the same bytes.
        REQUIRE(loaded->save(file("model-again")).ok());
        CHECK(detail::read_all(file("model")) == detail::read_all(file("model-again")));
    }

    SECTION("deterministic: same parameters and data give the same predictions and model bytes") {
        auto a = make_configured(c, c.params);
        auto b = make_configured(c, c.params);
        REQUIRE(a->train(table).ok());
        REQUIRE(b->train(table).ok());
        check_same_predictions(predict_all(*a, table), predict_all(*b, table));
        REQUIRE(a->save(file("a")).ok());
        REQUIRE(b->save(file("b")).ok());
        CHECK(detail::read_all(file("a")) == detail::read_all(file("b")));
    }

    SECTION("refuses foreign, newer, damaged and missing model files with an error") {
        auto clf = make_configured(c, c.params);
        REQUIRE(clf->train(table).ok());
        REQUIRE(clf->save(file("model")).ok());
        const std::string saved = detail::read_all(file("model"));

        const auto refused = [&](const std::filesystem::path& p) {
            auto fresh = make_configured(c, c.params);
            auto st = fresh->load(p);
            INFO("loading " << p.string());
            REQUIRE_FALSE(st.ok());
            CHECK_FALSE(st.message().empty());
            CHECK_FALSE(fresh->predict(table.row(0)).ok());  // a refused file leaves nothing loaded
            return st.message();
        };

        detail::write_all(file("foreign"), "rollsense-some-other-classifier 1\nclasses 1\nclass C1\n");
        refused(file("foreign"));
        for (std::size_t i = 0; i < c.others.size(); ++i) {
            auto other = c.others[i]();
            REQUIRE(other);
            REQUIRE(other->train(table).ok());
            const auto p = file("other-" + std::to_string(i));
            REQUIRE(other->save(p).ok());
            refused(p);
        }

        detail::write_all(file("newer"), c.newer_version ? c.newer_version(saved)
                                                         : detail::bump_first_line_version(saved));
        CHECK_THAT(refused(file("newer")), Catch::Contains("version"));

        detail::write_all(file("truncated"), saved.substr(0, saved.size() / 2));
        refused(file("truncated"));
        detail::write_all(file("empty"), "");
        refused(file("empty"));
        refused(file("does-not-exist"));
    }

    SECTION("search space: schema parameters with valid ranges the classifier accepts") {
        const auto clf = make_configured(c, c.params);
        for (const auto& [rows, cols] : {std::pair<std::size_t, std::size_t>{table.rows, table.cols()}, {3, 1},
                                         {1164, 13}}) {
            const SearchSpace space = clf->search_space(rows, cols);
            for (const auto& d : space) {
                INFO("dimension '" << d.name << "' for " << rows << " x " << cols);
                const auto spec = std::find_if(c.schema.begin(), c.schema.end(),
                                               [&](const ParamSpec& s) { return s.name == d.name; });
                REQUIRE(spec != c.schema.end());
                std::vector<ParamValue> ends;
                using Scale = SearchDimension::Scale;
                if (d.scale == Scale::categorical) {
                    REQUIRE_FALSE(d.choices.empty());
                    for (const auto& ch : d.choices) ends.emplace_back(ch);
                } else {
                    REQUIRE(std::isfinite(d.low));
                    REQUIRE(std::isfinite(d.high));
                    CHECK(d.low <= d.high);
                    if (d.scale == Scale::integer_log || d.scale == Scale::real_log) CHECK(d.low > 0.0);
                    const bool integer = d.scale == Scale::integer_log || d.scale == Scale::integer_linear;
                    for (double v : {d.low, d.high}) {
                        if (integer) {
                            CHECK(v == std::round(v));
                            ends.emplace_back(static_cast<std::int64_t>(v));
                        } else {
                            ends.emplace_back(v);
                        }
                    }
                }
                for (const auto& v : ends) {
                    auto raw = c.params;
                    raw[d.name] = v;
                    INFO("value " << format_param_value(v));
                    make_configured(c, raw);  // the schema and on_configure accept it
                }
            }
        }
    }
}

}  // namespace rollsense::testing
