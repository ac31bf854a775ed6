#include "analysis/learn/gaussian_process.hpp"

#include <cmath>
#include <limits>

namespace rollsense::learn {

double GaussianProcess::kernel(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
    const double r = (a - b).norm() / length_;
    const double s5 = std::sqrt(5.0) * r;
    return (1.0 + s5 + 5.0 * r * r / 3.0) * std::exp(-s5);
}

void GaussianProcess::fit(const Eigen::MatrixXd& x, const Eigen::VectorXd& y) {
    x_ = x;
    const auto m = static_cast<double>(y.size());
    y_mean_ = y.mean();
    const double var = (y.array() - y_mean_).square().sum() / std::max(1.0, m - 1.0);
    y_scale_ = var > 1e-18 ? std::sqrt(var) : 1.0;
    const Eigen::VectorXd z = (y.array() - y_mean_) / y_scale_;

    // The objective is a cross-validation error: noisy and of unknown
    // smoothness, so both length scale and noise are chosen from the data.
    const double lengths[] = {0.08, 0.15, 0.25, 0.4, 0.6, 1.0, 1.6};
    const double noises[] = {1e-4, 1e-3, 1e-2, 0.05, 0.2, 0.5};
    double best_ll = -std::numeric_limits<double>::infinity();
    double best_len = 0.4, best_noise = 0.05;
    const auto n = x.rows();
    Eigen::MatrixXd k(n, n);
    for (double len : lengths) {
        length_ = len;
        for (Eigen::Index i = 0; i < n; ++i)
            for (Eigen::Index j = 0; j <= i; ++j) k(i, j) = k(j, i) = kernel(x.row(i), x.row(j));
        for (double noise : noises) {
            Eigen::MatrixXd kn = k;
            kn.diagonal().array() += noise;
            Eigen::LLT<Eigen::MatrixXd> llt(kn);
            if (llt.info() != Eigen::Success) continue;
            const Eigen::VectorXd a = llt.solve(z);
            const double logdet = 2.0 * llt.matrixL().toDenseMatrix().diagonal().array().log().sum();
            const double ll = -0.5 * z.dot(a) - 0.5 * logdet;
            if (ll > best_ll) {
                best_ll = ll;
                best_len = len;
                best_noise = noise;
            }
        }
    }
    length_ = best_len;
    noise_ = best_noise;
    for (Eigen::Index i = 0; i < n; ++i)
        for (Eigen::Index j = 0; j <= i; ++j) k(i, j) = k(j, i) = kernel(x.row(i), x.row(j));
    k.diagonal().array() += noise_;
    chol_.compute(k);
    alpha_ = chol_.solve(z);
}

void GaussianProcess::predict(const Eigen::VectorXd& x, double& mean, double& sd) const {
    const auto n = x_.rows();
    Eigen::VectorXd ks(n);
    for (Eigen::Index i = 0; i < n; ++i) ks(i) = kernel(x, x_.row(i));
    const double mu = ks.dot(alpha_);
    const Eigen::VectorXd v = chol_.matrixL().solve(ks);
    const double var = std::max(1e-12, 1.0 - v.squaredNorm());
    mean = y_mean_ + y_scale_ * mu;
    sd = y_scale_ * std::sqrt(var);
}

}  // namespace rollsense::learn
