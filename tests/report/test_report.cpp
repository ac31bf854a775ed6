// The report rendered from a small generated dataset: every figure and table
// is there, and the numbers on the page are the evaluation's numbers.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <unistd.h>

#include "rollsense/bagged_trees/bagged_trees.hpp"
#include "analysis/learn/evaluate.hpp"
#include "analysis/report/breakdown.hpp"
#include "analysis/report/confusion_figure.hpp"
#include "analysis/report/object_order.hpp"
#include "analysis/report/plotted_trial.hpp"
#include "analysis/report/report.hpp"
#include "analysis/report/svg.hpp"
#include "synthetic_dataset.hpp"

namespace fs = std::filesystem;
#include "temp_dir.hpp"

using namespace rollsense;
using namespace rollsense::report;

namespace {

learn::ClassifierFactory bagged_trees_factory() {
    return [](const ParamSet& raw) -> Result<learn::ClassifierPtr> {
        auto params = validate_params(bagged_trees::bagged_trees_schema(), raw.values(), "test");
        if (!params) return params.error();
        auto c = std::make_shared<bagged_trees::BaggedTrees>();
        if (auto s = c->on_configure(*params, {}); !s) return s;
        return learn::ClassifierPtr(c);
    };
}

// One dataset, evaluation and page shared by the structure checks.
struct Rendered {
    fs::path root;
    ReportInputs inputs;
    std::string html;
};

const Rendered& rendered() {
    static const rollsense::testing::TempDir folder("rollsense-test-report");  // removed when the test process ends
    static const Rendered r = [] {
        Rendered out;
        out.root = folder.path();
        test::write_synthetic_dataset(out.root / "dataset");
        auto dataset = DatasetReader::open(out.root / "dataset");
        REQUIRE(dataset.ok());
        auto rows = features::extract_dataset(*dataset, {}, 1);
        REQUIRE(rows.ok());
        learn::EvaluationOptions o;
        o.folds = 3;
        o.repeats = 2;
        ParamSet params;
        params.set("learners", std::int64_t{20});
        auto ev = learn::evaluate_features(*rows, {{"bagged_trees", bagged_trees_factory(), params}}, o);
        REQUIRE(ev.ok());
        out.inputs.dataset_dir = out.root / "dataset";
        out.inputs.rows = *rows;
        out.inputs.evaluation = *ev;
        out.inputs.command_line = "test_report <structure>";
        auto path = write_report(out.inputs);
        REQUIRE(path.ok());
        CHECK(*path == out.root / "dataset" / "report.html");
        std::ifstream in(*path);
        std::stringstream ss;
        ss << in.rdbuf();
        out.html = ss.str();
        return out;
    }();
    return r;
}

std::size_t occurrences(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (auto p = text.find(what); p != std::string::npos; p = text.find(what, p + what.size())) ++n;
    return n;
}

// The text between the opening of the element with this id and the end tag.
std::string element(const std::string& html, const std::string& tag, const std::string& id) {
    const auto at = html.find(" id=\"" + id + "\"");
    if (at == std::string::npos) return {};
    const auto start = html.rfind("<" + tag + " ", at);
    if (start == std::string::npos || html.find('>', start) < at) return {};
    const auto end = html.find("</" + tag + ">", start);
    return html.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

// Table rows of an HTML table: the text of each cell, tags removed.
std::vector<std::vector<std::string>> table_rows(const std::string& table) {
    std::vector<std::vector<std::string>> rows;
    const std::regex tr("<tr[^>]*>(.*?)</tr>"), cell("<t[dh][^>]*>(.*?)</t[dh]>"), tag("<[^>]+>");
    for (auto it = std::sregex_iterator(table.begin(), table.end(), tr); it != std::sregex_iterator(); ++it) {
        const std::string inner = (*it)[1];
        std::vector<std::string> cells;
        for (auto c = std::sregex_iterator(inner.begin(), inner.end(), cell); c != std::sregex_iterator(); ++c)
            cells.push_back(std::regex_replace(std::string((*c)[1]), tag, ""));
        rows.push_back(cells);
    }
    return rows;
}

}  // namespace

TEST_CASE("svg primitives escape text and print numbers plainly", "[report][svg]") {
    CHECK(escape_xml("a<b & \"c\" 'd'>") == "a&lt;b &amp; &quot;c&quot; &#39;d&#39;&gt;");
    CHECK(fixed(-0.001, 1) == "0.0");
    CHECK(fixed(12.345, 2) == "12.35");
    CHECK(fixed(std::nan(""), 1) == "\u2013");
    CHECK(percent(0.905) == "90.5\u00a0%");
    Svg svg(100, 50, "f", "a <title>");
    svg.text(1, 2, "x < y");
    const std::string s = svg.str();
    CHECK_THAT(s, Catch::Contains("<title id=\"f-title\">a &lt;title&gt;</title>") &&
                      Catch::Contains(">x &lt; y</text>") && Catch::EndsWith("</svg>\n"));
}

TEST_CASE("objects are ordered as the paper's Fig. 9: cylinders, large, small polygons", "[report][order]") {
    const std::vector<std::string> classes = {"C1", "C2", "C3", "H1", "H2", "P1", "P2", "S1", "S2", "X9"};
    const ObjectOrder o = order_objects(classes, learn::paper_objects());
    std::vector<std::string> shown;
    for (auto i : o.order) shown.push_back(classes[i]);
    CHECK(shown == std::vector<std::string>{"C1", "C2", "C3", "S2", "P2", "H2", "S1", "P1", "H1", "X9"});
    REQUIRE(o.groups.size() == 4);
    CHECK(o.groups[0].label == "cylinders");
    CHECK(o.groups[1].label == "large polygons (18 mm)");
    CHECK(o.groups[2].label == "small polygons (13 mm)");
    CHECK(o.groups[3].label == "not in the catalogue");
}

TEST_CASE("half-maximum span covers the samples at or above half the peak", "[report][features]") {
    const std::vector<double> x = {0, 0.1, 0.4, 0.6, 1.0, 0.7, 0.5, 0.2, 0};
    features::ChannelPeak p;
    p.peak.first = 1;
    p.peak.last = 7;
    p.peak.max_index = 4;
    p.peak.max = 1.0;
    const auto [a, b] = half_maximum_span(x, p);
    CHECK(a == 3);
    CHECK(b == 6);
}

TEST_CASE("the report holds every figure and table, self-contained", "[report][structure]") {
    const auto& r = rendered();
    const std::string& h = r.html;
    CHECK_THAT(h, Catch::StartsWith("<!DOCTYPE html>"));
    for (const char* id : {"sec-accuracy", "sec-confusion", "sec-breakdown", "sec-paper", "sec-peaks", "sec-features",
                           "sec-tuning", "sec-provenance"})
        CHECK(occurrences(h, std::string("<section id=\"") + id + "\">") == 1);
    for (const char* fig : {"fig-confusion", "fig-peaks", "fig-features"})
        CHECK_FALSE(element(h, "svg", fig).empty());
    for (const char* table : {"accuracy", "by-speed", "by-object", "paper-comparison", "hyperparameters", "protocols"})
        CHECK_FALSE(element(h, "table", table).empty());
    // Balanced elements, nothing fetched from elsewhere, nothing to execute.
    for (const char* tag : {"svg", "section", "table", "figure", "g"})
        CHECK(occurrences(h, std::string("<") + tag + " ") + occurrences(h, std::string("<") + tag + ">") ==
              occurrences(h, std::string("</") + tag + ">"));
    CHECK(occurrences(h, "<script") == 0);
    CHECK(occurrences(h, "src=") == 0);
    CHECK(occurrences(h, "href=\"http") == 0);
    CHECK(occurrences(h, "@media print") == 1);
    // Fig. 7: one plot per object and speed; Fig. 8: the feature labels.
    const std::string peaks = element(h, "svg", "fig-peaks");
    CHECK(occurrences(peaks, "<g class=\"peak-plot\">") == test::kSyntheticObjects * test::kSyntheticSpeeds);
    CHECK(occurrences(peaks, "<polyline") == 3u * test::kSyntheticObjects * test::kSyntheticSpeeds);
    const std::string feats = element(h, "svg", "fig-features");
    for (const char* label : {"F1 amplitude", "F2 amplitude", "F3 amplitude", "F7 half-width", "F8 half-width",
                              "F9 half-width", "F12 time between maxima", "F13 time between maxima", "F4 skew"})
        CHECK_THAT(feats, Catch::Contains(label));
    // Provenance: the recording's command line, escaped, and this report's.
    CHECK_THAT(h, Catch::Contains("rollsense run synthetic.lua --out &lt;dir&gt; &amp; friends") &&
                      Catch::Contains("test_report &lt;structure&gt;") && Catch::Contains("2026-01-02T03:04:05Z"));
}

TEST_CASE("the confusion figure shows the evaluation's counts and TPRs in Fig. 9 order", "[report][structure]") {
    const auto& r = rendered();
    const auto& m = r.inputs.evaluation.primary().baseline.confusion;
    const std::string fig = element(r.html, "svg", "fig-confusion");
    REQUIRE_FALSE(fig.empty());
    const ObjectOrder ord = order_objects(m.classes, learn::paper_objects());
    // Cells are drawn row by row in display order; each shows its count (blank for 0).
    std::vector<std::string> cells;
    const std::regex cell("<g class=\"cell\">\\n<rect[^>]*/>\\n(?:<text[^>]*>([0-9]+)</text>\\n)?</g>");
    for (auto it = std::sregex_iterator(fig.begin(), fig.end(), cell); it != std::sregex_iterator(); ++it)
        cells.push_back((*it)[1]);
    REQUIRE(cells.size() == m.size() * m.size());
    std::size_t k = 0, shown_total = 0;
    for (std::size_t r_ = 0; r_ < m.size(); ++r_)
        for (std::size_t c = 0; c < m.size(); ++c, ++k) {
            const std::size_t count = m.at(ord.order[r_], ord.order[c]);
            INFO("row " << m.classes[ord.order[r_]] << " column " << m.classes[ord.order[c]]);
            CHECK(cells[k] == (count == 0 ? std::string() : std::to_string(count)));
            shown_total += cells[k].empty() ? 0 : std::stoul(cells[k]);
        }
    CHECK(shown_total == m.total());
    CHECK(m.total() == r.inputs.evaluation.primary().baseline.total);
    const auto tpr = m.true_positive_rates();
    for (std::size_t i = 0; i < m.size(); ++i) CHECK_THAT(fig, Catch::Contains(">" + percent(tpr[i]) + "</text>"));
    CHECK_THAT(fig, Catch::Contains(std::to_string(m.correct()) + " of " + std::to_string(m.total()) + " correct"));
}

TEST_CASE("the tables carry the evaluation's figures", "[report][structure]") {
    const auto& r = rendered();
    const auto& ev = r.inputs.evaluation.primary();
    const std::string& h = r.html;
    const std::string headline = h.substr(h.find("id=\"headline\""), 300);
    CHECK_THAT(headline, Catch::Contains(fixed(100.0 * ev.baseline.mean, 1) + " \u00b1 " +
                                         fixed(100.0 * ev.baseline.sd, 1)));
    CHECK_THAT(headline, Catch::Contains(fixed(100.0 * ev.baseline.wilson.low, 1) + "\u2013" +
                                         fixed(100.0 * ev.baseline.wilson.high, 1)));

    // Per speed: counted here from the rows and the first repetition's predictions.
    std::map<std::string, std::array<std::size_t, 4>> by_speed;  // trials, clean, evaluated, correct
    std::vector<std::size_t> row_of;
    const FeatureTable table = features::to_feature_table(r.inputs.rows, &row_of);
    for (const auto& row : r.inputs.rows) {
        ++by_speed[row.speed][0];
        by_speed[row.speed][1] += row.clean;
    }
    for (std::size_t i = 0; i < row_of.size(); ++i) {
        auto& s = by_speed[r.inputs.rows[row_of[i]].speed];
        ++s[2];
        s[3] += ev.baseline.first_predicted[i] == table.y[i];
    }
    const auto speed_rows = table_rows(element(h, "table", "by-speed"));
    REQUIRE(speed_rows.size() == 1 + test::kSyntheticSpeeds);
    for (std::size_t i = 1; i < speed_rows.size(); ++i) {
        const auto& cells = speed_rows[i];
        REQUIRE(cells.size() == 6);
        const auto& want = by_speed.at(cells[0]);
        CHECK(cells[1] == std::to_string(want[0]));
        CHECK(cells[2] == std::to_string(want[1]));
        CHECK(cells[4] == std::to_string(want[3]) + " / " + std::to_string(want[2]));
    }
    // The synthetic data rejects the fast-speed last repetition of every polygon.
    CHECK(by_speed.at("20")[1] == by_speed.at("20")[0] - 6);

    const auto object_rows = table_rows(element(h, "table", "by-object"));
    REQUIRE(object_rows.size() == 1 + test::kSyntheticObjects);
    CHECK(object_rows[1][0] == "C1");
    CHECK(object_rows[4][0] == "S2");

    // The paper's analyses: ours from the evaluation, the paper's numbers beside them.
    const auto paper = table_rows(element(h, "table", "paper-comparison"));
    REQUIRE(paper.size() == 13);
    const auto& a = ev.analysis;
    auto count = [](const learn::Count& c) {
        return std::to_string(c.k) + " / " + std::to_string(c.n) + " (" + percent(c.fraction()) + ")";
    };
    CHECK(paper[1][1] == count(a.clean));
    CHECK(paper[1][2] == "1164 / 1350 (86.2\u00a0%)");
    CHECK(paper[4][1] == count(a.accuracy));
    CHECK(paper[6][1] == count(a.cylinders_misclassified));
    CHECK(paper[6][2] == "7 / 450 (1.6\u00a0%)");
    CHECK(paper[7][1] == count(a.polygon_edge_correct));
    // 120 samples at 31.1 Hz: the fast speed's recordings.
    CHECK_THAT(paper[12][0], Catch::Contains("fastest speed, 20"));
    CHECK(paper[12][1] == fixed(120 / 31.1, 2) + " s");

    // Without --optimize the tuned rows say how to get them.
    const auto protocols = table_rows(element(h, "table", "protocols"));
    REQUIRE(protocols.size() == 3);
    CHECK_THAT(protocols[2][3], Catch::Contains("--optimize"));
    const auto params = table_rows(element(h, "table", "hyperparameters"));
    REQUIRE(params.size() == 2);
    CHECK(params[1][0] == "learners");
    CHECK(params[1][1] == "20");
}

TEST_CASE("text summary: the headline figures and where the report is", "[report][summary]") {
    const auto& r = rendered();
    const std::string s = text_summary(r.inputs);
    char acc[32];
    std::snprintf(acc, sizeof acc, "accuracy %.1f %%", 100.0 * r.inputs.evaluation.primary().baseline.mean);
    CHECK_THAT(s, Catch::Contains(acc) && Catch::Contains("paper 90.5 %") && Catch::Contains("2 x 3-fold CV") &&
                      Catch::Contains("report: " + (r.root / "dataset" / "report.html").string()) &&
                      Catch::Contains("by speed"));
}

TEST_CASE("a missing dataset is an error naming it", "[report][errors]") {
    ReportInputs in = rendered().inputs;
    in.dataset_dir = "/nonexistent/rollsense-dataset";
    auto r = write_report(in);
    REQUIRE_FALSE(r.ok());
    CHECK_THAT(r.error().message, Catch::Contains("/nonexistent/rollsense-dataset"));
}

TEST_CASE("several classifiers are compared side by side, a single one gets no comparison", "[report][compare]") {
    const auto& single = rendered();
    CHECK_THAT(single.html, !Catch::Contains("id=\"sec-compare\"") && !Catch::Contains("fig-paired"));

    auto dataset = DatasetReader::open(single.root / "dataset");
    REQUIRE(dataset.ok());
    learn::EvaluationOptions o;
    o.folds = 3;
    o.repeats = 2;
    ParamSet few, many;
    few.set("learners", std::int64_t{3});
    many.set("learners", std::int64_t{20});
    auto ev = learn::evaluate_features(
        single.inputs.rows, {{"few", bagged_trees_factory(), few}, {"many", bagged_trees_factory(), many}}, o);
    REQUIRE(ev.ok());
    ReportInputs in = single.inputs;
    in.evaluation = *ev;
    auto html = render_report(in);
    REQUIRE(html.ok());
    const std::string& h = *html;
    CHECK_THAT(h, Catch::Contains("id=\"sec-compare\"") && Catch::Contains("id=\"compare-accuracy\"") &&
                      Catch::Contains("id=\"compare-per-class\"") && Catch::Contains("id=\"compare-paired\"") &&
                      Catch::Contains("id=\"fig-paired\"") && Catch::Contains("id=\"fig-confusion-1\"") &&
                      Catch::Contains("id=\"fig-confusion-2\""));
    // The accuracy table carries each classifier's own figure.
    const std::string table = h.substr(h.find("id=\"compare-accuracy\""), 2000);
    for (const auto& c : ev->classifiers)
        CHECK_THAT(table, Catch::Contains(c.name) &&
                              Catch::Contains(fixed(100.0 * c.baseline.mean, 1) + " \u00b1 " +
                                              fixed(100.0 * c.baseline.sd, 1)));
    const std::string paired = h.substr(h.find("id=\"compare-paired\""), 1500);
    CHECK_THAT(paired, Catch::Contains("few \u2212 many") &&
                           Catch::Contains(fixed(100.0 * ev->paired[0].difference.mean, 2)));
    // The headline and the paper's sections stay the first classifier's.
    CHECK_THAT(h.substr(h.find("id=\"headline\""), 300), Catch::Contains("(few, 2 \u00d7 3-fold CV)"));
    const std::string summary = text_summary(in);
    CHECK_THAT(summary, Catch::Contains("compared: many") && Catch::Contains("first minus it"));
}

TEST_CASE("a report made inside the recording run shows that run's provenance, not 'No run-info.csv'",
          "[report][provenance][issue24]") {
    const auto& r = rendered();
    const fs::path dir = r.root / "in-progress";
    fs::remove_all(dir);
    fs::create_directories(dir);
    fs::copy(r.inputs.dataset_dir, dir / "dataset", fs::copy_options::recursive);
    fs::remove(dir / "dataset" / "run-info.csv");  // what rs.analyse finds: the run has not ended yet
    ReportInputs in = r.inputs;
    in.dataset_dir = dir / "dataset";
    in.output.clear();
    SECTION("given the run's provenance") {
        in.recording_run = {{"command_line", "rollsense run paper.lua --seed 11"}, {"seed", "11"}};
        auto html = render_report(in);
        REQUIRE(html.ok());
        CHECK_THAT(*html, !Catch::Contains("No run-info.csv") && Catch::Contains("still in progress") &&
                              Catch::Contains("rollsense run paper.lua --seed 11"));
        // Review (data): the report named its own software "unknown" (the version was defined for the kernel only).
        CHECK_THAT(*html, !Catch::Contains("rollsense unknown") && Catch::Contains("<meta name=\"generator\" "
                                                                                   "content=\"rollsense 0."));
    }
    SECTION("a resumed run: the run-info.csv on disk is the interrupted run's, not this one's") {
        std::ofstream(in.dataset_dir / "run-info.csv") << "key,value\nstatus,cancelled: interrupted by Ctrl-C or a SIGTERM/SIGHUP\n";
        in.recording_run = {{"command_line", "rollsense run paper.lua --seed 11 --resume"}, {"seed", "11"}};
        auto html = render_report(in);
        REQUIRE(html.ok());
        CHECK_THAT(*html, Catch::Contains("still in progress") && Catch::Contains("--resume") &&
                              !Catch::Contains("interrupted by Ctrl-C"));
    }
    SECTION("a dataset made by hand still says it has none") {
        auto html = render_report(in);
        REQUIRE(html.ok());
        CHECK_THAT(*html, Catch::Contains("No run-info.csv"));
    }
    // Review (bad input) item 4: an empty run-info.csv failed the report after its evaluation.
    SECTION("an unreadable run-info.csv is said on the page; the report is made") {
        std::ofstream(in.dataset_dir / "run-info.csv") << "";
        auto html = render_report(in);
        REQUIRE(html.ok());
        CHECK_THAT(*html, Catch::Contains("run-info.csv could not be read: ") &&
                              Catch::Contains("run-info.csv:1: the file is empty"));
    }
}

TEST_CASE("the paper comparison says n/a where there is nothing to count, never a made-up 0",
          "[report][tables][issue24]") {
    const auto& r = rendered();
    const auto rows = table_rows(element(r.html, "table", "paper-comparison"));
    REQUIRE(rows.size() > 5);
    bool any_na = false;
    for (const auto& row : rows) {
        REQUIRE(row.size() == 3);
        for (const auto& cell : {row[1], row[2]}) {
            INFO(row[0] << " | " << cell);
            CHECK(cell != "0");
            any_na = any_na || cell == "n/a";
        }
    }
    // The synthetic dataset has no hexagons: their rows have nothing to count.
    CHECK(any_na);
    CHECK(learn::format_paper_comparison(learn::PaperAnalysis{}).find(" 0 ") == std::string::npos);
}

TEST_CASE("a trial whose file cannot be read is named in the report with its reason", "[report][issue24]") {
    const auto& r = rendered();
    ReportInputs in = r.inputs;
    in.output = r.root / "unreadable.html";
    in.rows[0].clean = false;
    in.rows[0].reason = "unreadable (trials/x.csv:3: column 'time': '0.06x' is not a number)";
    auto html = render_report(in);
    REQUIRE(html.ok());
    const auto at = html->find("id=\"unreadable-trials\"");
    REQUIRE(at != std::string::npos);
    CHECK_THAT(html->substr(at, 600), Catch::Contains(in.rows[0].trial_id) && Catch::Contains("x.csv:3"));
}

namespace {
struct SvgText {
    double x = 0, y = 0;
    std::string anchor, transform, text;
    double size = 0;
};
std::vector<SvgText> svg_texts(const std::string& svg) {
    std::vector<SvgText> out;
    const std::regex text_re(R"re(<text x="([-0-9.]+)" y="([-0-9.]+)" font-size="([0-9.]+)" text-anchor="(\w+)"[^>]*?(?:transform="([^"]*)")?>([^<]*)</text>)re");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), text_re); it != std::sregex_iterator(); ++it)
        out.push_back({std::stod((*it)[1]), std::stod((*it)[2]), (*it)[4], (*it)[5], (*it)[6], std::stod((*it)[3])});
    return out;
}
}  // namespace

TEST_CASE("long custom object names get room in the confusion figure and the peak grid", "[report][layout][issue24]") {
    const std::string long_a = "left_handed_teapot_lid_large", long_b = "left_handed_teapot_lid_small";
    learn::ConfusionMatrix m({"C1", long_a, long_b});
    m.add(0, 0), m.add(1, 2), m.add(2, 2);
    const std::string svg = confusion_figure(m, learn::paper_objects(), "fig", "long names");
    const auto texts = svg_texts(svg);
    std::size_t turned = 0;
    for (const auto& t : texts) {
        if (t.text != long_a && t.text != long_b) continue;
        if (!t.transform.empty()) {
            ++turned;  // a column name, at 45 degrees: neighbours cannot overlap
            CHECK(t.transform.find("rotate(-45") == 0);
            CHECK(t.y - 0.7072 * text_width(t.text, t.size) > 30.0);  // clear of the "predicted object" title
        } else {
            CHECK(t.anchor == "end");  // a row name: it ends at its glyph and must start inside the figure
            CHECK(t.x - text_width(t.text, t.size) >= 0.0);
        }
    }
    CHECK(turned == 2);
    // Short names stay level.
    learn::ConfusionMatrix short_names({"C1", "C2"});
    CHECK(svg.find("rotate(-45") != std::string::npos);
    CHECK(confusion_figure(short_names, learn::paper_objects(), "fig", "short").find("rotate(-45") == std::string::npos);
}

TEST_CASE("every plot has axis ticks and the units of its axes", "[report][layout][issue24]") {
    const auto& r = rendered();
    const std::string feats = element(r.html, "svg", "fig-features");
    CHECK_THAT(feats, Catch::Contains("time (samples)") && Catch::Contains("smoothed reading (unitless"));
    const std::string peaks = element(r.html, "svg", "fig-peaks");
    CHECK_THAT(peaks, Catch::Contains("time (samples) (x)") && Catch::Contains("smoothed reading (unitless"));
    // Tick labels: numbers in 11 px (feature figure) and 9 px (each peak plot).
    auto numeric = [](const std::vector<SvgText>& ts, double size) {
        std::size_t n = 0;
        for (const auto& t : ts) n += t.size == size && std::regex_match(t.text, std::regex("-?[0-9]+(\\.[0-9]+)?"));
        return n;
    };
    CHECK(numeric(svg_texts(feats), 11.0) >= 6);
    CHECK(numeric(svg_texts(peaks), 9.0) >= 4u * test::kSyntheticObjects * test::kSyntheticSpeeds);
    const auto ticks = nice_ticks(0.0, 1.0, 5);
    REQUIRE(ticks.size() == 6);
    CHECK(ticks[3] == Approx(0.6));
    CHECK(tick_label(0.25, 0.05) == "0.25");
    CHECK(tick_label(40.0, 20.0) == "40");
}
