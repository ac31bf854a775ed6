// check_search_space: what a classifier plugin's search_space() must be for tuning to search it, refused before any
// cross-validation (user and diff reviews: each of these failed only at the first optimiser evaluation, after the
// preset's CV, or with an integer cast of infinity).
#include <catch2/catch.hpp>

#include <limits>

#include "analysis/learn/checked_classifier.hpp"

using namespace rollsense;
using Scale = SearchDimension::Scale;

namespace {
const ParamSchema kSchema{param_number("smoothing", 1.0, "bounded", 0.0, 10.0), param_number("free", 1.0, "unbounded"),
                          param_int("neighbours", 3, "an integer", 1, 9),
                          param_string("metric", "l2", "a choice", {"l1", "l2"})};

std::string refusal(const SearchDimension& d) {
    const auto s = learn::check_search_space({d}, kSchema, "classifier plugin 'p'");
    return s.ok() ? "" : s.message();
}
}  // namespace

TEST_CASE("a search space tuning can search passes, and each kind of mistake is refused naming the parameter",
          "[learn][plugin]") {
    const double inf = std::numeric_limits<double>::infinity();
    CHECK(refusal({"smoothing", Scale::real_linear, 0.0, 10.0, {}}).empty());
    CHECK(refusal({"neighbours", Scale::integer_log, 1, 9, {}}).empty());
    CHECK(refusal({"metric", Scale::categorical, 0, 0, {"l1", "l2"}}).empty());

    CHECK_THAT(refusal({"depth", Scale::integer_linear, 1, 8, {}}),
               Catch::Contains("names the parameter 'depth' in its search_space(), which its schema() does not declare"));
    CHECK_THAT(refusal({"smoothing", Scale::real_linear, 0.0, 50.0, {}}),
               Catch::StartsWith("classifier plugin 'p': search_space(): key 'smoothing': 50 is outside the allowed "
                                 "range [0, 10]"));
    CHECK_THAT(refusal({"metric", Scale::categorical, 0, 0, {"l1", "cosine"}}), Catch::Contains("'cosine'"));
    const auto gives = [](const std::string& name, const std::string& wrong) {
        return Catch::StartsWith("classifier plugin 'p': search_space() gives '" + name + "' " + wrong +
                                 ", which tuning cannot search");
    };
    CHECK_THAT(refusal({"metric", Scale::categorical, 0, 0, {}}), gives("metric", "no choices"));
    CHECK_THAT(refusal({"neighbours", Scale::integer_linear, 9, 2, {}}), gives("neighbours", "an empty range [9, 2]"));
    CHECK_THAT(refusal({"free", Scale::real_linear, 0.0, inf, {}}), gives("free", "a range that is not finite [0, Inf]"));
    CHECK_THAT(refusal({"free", Scale::real_log, 0.0, 1.0, {}}), gives("free", "a log scale from 0 (it must start above 0)"));
    CHECK_THAT(refusal({"neighbours", Scale::real_linear, 1, 9, {}}),
               gives("neighbours", "a real scale for an integer parameter"));
}
