#include "analysis/learn/cv_scheme.hpp"

#include <algorithm>
#include <map>
#include <set>

namespace rollsense::learn {

std::string CvScheme::describe() const {
    if (kind == Kind::grouped) return "grouped by " + group_by;
    return "blocked: " + std::to_string(block) + " consecutive trials within a mount";
}

std::string CvScheme::id() const {
    return kind == Kind::grouped ? "grouped:" + group_by : "blocked:" + std::to_string(block);
}

Result<std::vector<CvScheme>> parse_cv_schemes(const std::string& list, const std::string& group_by,
                                               const std::string& block) {
    // The schemes in the order asked for (each once): every output lists them so.
    std::vector<CvScheme::Kind> asked;
    std::size_t start = 0;
    while (start <= list.size() && !list.empty()) {
        const auto comma = list.find(',', start);
        const std::string word = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        std::optional<CvScheme::Kind> kind;
        if (word == "grouped") {
            kind = CvScheme::Kind::grouped;
        } else if (word == "blocked") {
            kind = CvScheme::Kind::blocked;
        } else if (word != "random") {
            return Error{ErrorCode::invalid_argument,
                         "--cv: unknown scheme '" + word + "'; use random, grouped, blocked (comma-separated)"};
        }
        if (kind && std::find(asked.begin(), asked.end(), *kind) == asked.end()) asked.push_back(*kind);
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    const auto wants = [&asked](CvScheme::Kind k) { return std::find(asked.begin(), asked.end(), k) != asked.end(); };
    const bool want_grouped = wants(CvScheme::Kind::grouped), want_blocked = wants(CvScheme::Kind::blocked);
    if (want_grouped != !group_by.empty())
        return Error{ErrorCode::invalid_argument,
                     want_grouped
                         ? "--cv grouped needs --group-by COLUMN (rs.analyse: group_by), a manifest column such as speed"
                         : "--group-by (group_by) applies to --cv grouped; add grouped to --cv"};
    if (want_blocked != !block.empty())
        return Error{ErrorCode::invalid_argument,
                     want_blocked ? "--cv blocked needs --block N (rs.analyse: block), the trials per block"
                                  : "--block (block) applies to --cv blocked; add blocked to --cv"};
    std::vector<CvScheme> out;
    for (const auto kind : asked) {
        CvScheme s;
        s.kind = kind;
        if (kind == CvScheme::Kind::grouped) {
            s.group_by = group_by;
        } else {
            try {
                std::size_t used = 0;
                s.block = std::stoi(block, &used);
                if (used != block.size() || s.block < 1) throw std::invalid_argument(block);
            } catch (const std::exception&) {
                return Error{ErrorCode::invalid_argument, "--block expects an integer >= 1, got '" + block + "'"};
            }
        }
        out.push_back(s);
    }
    return out;
}

std::optional<std::string> manifest_value(const features::FeatureRow& row, const std::string& column) {
    if (column == "trial_id") return row.trial_id;
    if (column == "object") return row.object;
    if (column == "speed") return row.speed;
    if (column == "repetition") return std::to_string(row.repetition);
    if (auto it = row.extra.find(column); it != row.extra.end()) return it->second;
    return std::nullopt;
}

namespace {

std::string known_columns(const features::FeatureRow& row) {
    std::string out = "trial_id, object, speed, repetition";
    for (const auto& [key, value] : row.extra) out += ", " + key;
    return out;
}

}  // namespace

Result<std::vector<std::string>> scheme_groups(const CvScheme& scheme, const std::vector<features::FeatureRow>& rows,
                                               const std::vector<std::size_t>& row_of) {
    std::vector<std::string> group_of_row(rows.size());
    if (scheme.kind == CvScheme::Kind::grouped) {
        for (std::size_t r = 0; r < rows.size(); ++r) {
            auto v = manifest_value(rows[r], scheme.group_by);
            if (!v)
                return Error{ErrorCode::invalid_argument,
                             "--group-by " + scheme.group_by + ": trial '" + rows[r].trial_id +
                                 "' has no manifest column '" + scheme.group_by +
                                 "'; group by one of its columns (rs.analyse: group_by): " + known_columns(rows[r])};
            group_of_row[r] = *v;
        }
    } else {
        std::map<std::string, long long> seen;  // mount → rows so far, for manifests without index_in_mount
        for (std::size_t r = 0; r < rows.size(); ++r) {
            const std::string mount = manifest_value(rows[r], "mount").value_or(rows[r].object);
            long long index = seen[mount]++;
            if (auto i = manifest_value(rows[r], "index_in_mount")) {
                try {
                    index = std::stoll(*i);
                } catch (const std::exception&) {
                    return Error{ErrorCode::invalid_argument, "trial '" + rows[r].trial_id +
                                                                  "': index_in_mount '" + *i + "' is not an integer"};
                }
            }
            group_of_row[r] = mount + "#" + std::to_string(index / scheme.block);
        }
    }
    std::vector<std::string> out;
    out.reserve(row_of.size());
    for (std::size_t r : row_of) out.push_back(group_of_row[r]);
    return out;
}

Result<FoldPlan> make_scheme_plan(const CvScheme& scheme, const std::vector<int>& labels,
                                  const std::vector<std::string>& class_names,
                                  const std::vector<std::string>& groups, int k, int repeats, std::uint64_t seed) {
    const std::size_t distinct = std::set<std::string>(groups.begin(), groups.end()).size();
    if (distinct < 2)
        return Error{ErrorCode::invalid_argument, scheme.describe() + ": the clean trials form " +
                                                      std::to_string(distinct) +
                                                      " group; cross-validation needs at least 2"};
    const bool leave_one_out = distinct <= static_cast<std::size_t>(k);
    auto plan = make_fold_plan(labels, &groups, leave_one_out ? static_cast<int>(distinct) : k,
                               leave_one_out ? 1 : repeats, seed);
    if (!plan) return plan.error();
    for (std::size_t rep = 0; rep < plan->repeats(); ++rep) {
        const auto& fold = plan->assignment[rep];
        for (int f = 0; f < plan->folds; ++f) {
            std::set<int> trained;
            for (std::size_t i = 0; i < labels.size(); ++i)
                if (fold[i] != f) trained.insert(labels[i]);
            for (std::size_t i = 0; i < labels.size(); ++i) {
                if (fold[i] != f || trained.count(labels[i])) continue;
                // The class's groups: one, and the grouping is the class there (review: a speed that varies
                // elsewhere was suggested when this class's clean trials were all at one speed).
                std::set<std::string> own;
                for (std::size_t j = 0; j < labels.size(); ++j)
                    if (labels[j] == labels[i]) own.insert(groups[j]);
                const std::string why =
                    scheme.kind != CvScheme::Kind::grouped
                        ? ": the class has too few blocks for " + std::to_string(plan->folds) +
                              " folds. Use smaller blocks (--block) or fewer folds (--folds)"
                    : own.size() == 1
                        ? ": its clean trials all have " + scheme.group_by + " '" + *own.begin() +
                              "', one group, so the grouping is the class there (as a mount is when each object is "
                              "mounted once). Group by a column that varies within each class, record more of it, "
                              "or use --cv blocked"
                        : ": its " + std::to_string(own.size()) + " groups all fall in that fold. Use fewer folds "
                                                                   "(--folds), or --cv blocked";
                return Error{ErrorCode::invalid_argument,
                             scheme.describe() + ": every trial of class '" + class_names[labels[i]] +
                                 "' falls in test fold " + std::to_string(f + 1) +
                                 ", so no training fold ever sees that class and the figure would be 0 % by "
                                 "construction" + why + "; see docs/identification.md"};
            }
        }
    }
    return plan;
}

}  // namespace rollsense::learn
