// The closed-form leave-one-out ridge against refitting without each row.
#include <catch2/catch.hpp>

#include "rollsense/minirocket/ridge.hpp"
#include "rollsense/random.hpp"

using namespace rollsense::minirocket;

namespace {
struct Direct {
    Eigen::MatrixXd w;
    Eigen::RowVectorXd b;
};

// Ridge with an unpenalised intercept, solved directly in the primal.
Direct solve(const Eigen::MatrixXd& x, const Eigen::MatrixXd& y, double alpha) {
    const Eigen::RowVectorXd xm = x.colwise().mean(), ym = y.colwise().mean();
    const Eigen::MatrixXd xc = x.rowwise() - xm, yc = y.rowwise() - ym;
    const Eigen::MatrixXd a = xc.transpose() * xc + alpha * Eigen::MatrixXd::Identity(x.cols(), x.cols());
    Direct d;
    d.w = a.ldlt().solve(xc.transpose() * yc);
    d.b = ym - xm * d.w;
    return d;
}

double direct_loo(const Eigen::MatrixXd& x, const Eigen::MatrixXd& y, double alpha) {
    const Eigen::Index n = x.rows();
    double sum = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) {
        Eigen::MatrixXd xs(n - 1, x.cols()), ys(n - 1, y.cols());
        for (Eigen::Index r = 0, o = 0; r < n; ++r)
            if (r != i) {
                xs.row(o) = x.row(r);
                ys.row(o++) = y.row(r);
            }
        const Direct d = solve(xs, ys, alpha);
        sum += (y.row(i) - (x.row(i) * d.w + d.b)).squaredNorm();
    }
    return sum / static_cast<double>(n * y.cols());
}

void check_against_direct(Eigen::Index n, Eigen::Index p) {
    auto rng = rollsense::random::Xoshiro256ss::named_stream(static_cast<std::uint64_t>(n * 1000 + p), "ridge-test");
    RowMatrixF x(n, p);
    std::vector<int> labels(static_cast<std::size_t>(n));
    for (Eigen::Index r = 0; r < n; ++r) {
        labels[static_cast<std::size_t>(r)] = static_cast<int>(r % 3);
        for (Eigen::Index c = 0; c < p; ++c)
            x(r, c) = static_cast<float>(rng.normal() + (c % 3 == r % 3 ? 0.8 : 0.0));
    }
    const std::vector<double> alphas{0.01, 1.0, 30.0, 1000.0};
    auto fit = fit_ridge_loo(x, labels, 3, alphas, 2);
    REQUIRE(fit.ok());
    const Eigen::MatrixXd xd = x.cast<double>(), y = one_vs_rest_targets(labels, 3);
    std::size_t best = 0;
    for (std::size_t a = 0; a < alphas.size(); ++a) {
        const double ref = direct_loo(xd, y, alphas[a]);
        CHECK(fit->loo_error[a] == Approx(ref).epsilon(1e-4));
        if (ref < direct_loo(xd, y, alphas[best])) best = a;
    }
    CHECK(fit->alpha == alphas[best]);
    const Direct d = solve(xd, y, fit->alpha);
    CHECK((fit->weights - d.w).norm() == Approx(0.0).margin(1e-4 * d.w.norm()));
    CHECK((fit->intercept.transpose() - d.b).norm() == Approx(0.0).margin(1e-4));
}
}  // namespace

TEST_CASE("LOO residuals and the chosen α match refitting without each row, p > n", "[minirocket][ridge]") {
    check_against_direct(24, 60);
}

TEST_CASE("LOO residuals and the chosen α match refitting without each row, p < n", "[minirocket][ridge]") {
    check_against_direct(40, 9);
}

TEST_CASE("ridge rejects what it cannot fit", "[minirocket][ridge]") {
    RowMatrixF x = RowMatrixF::Random(5, 4);
    CHECK(!fit_ridge_loo(x, {0, 1, 0, 1}, 2, {1.0}, 1).ok());           // 4 labels for 5 rows
    CHECK(!fit_ridge_loo(x, {0, 1, 0, 1, 0}, 2, {}, 1).ok());           // no α
    CHECK(!fit_ridge_loo(x, {0, 1, 0, 1, 0}, 2, {-1.0}, 1).ok());       // negative α
    CHECK(!fit_ridge_loo(x.topRows(1), {0}, 2, {1.0}, 1).ok());         // one row: no LOO
    CHECK(log_grid(-3, 3, 10).size() == 10);
    CHECK(log_grid(-3, 3, 10).front() == Approx(1e-3));
    CHECK(log_grid(-3, 3, 10).back() == Approx(1e3));
    CHECK(log_grid(-3, 3, 7)[3] == Approx(1.0));
}
