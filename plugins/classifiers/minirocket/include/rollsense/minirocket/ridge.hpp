// Ridge classification with the regularisation chosen by exact leave-one-out
// in closed form (as scikit-learn's RidgeClassifierCV): one-vs-rest targets
// ±1, an unpenalised intercept, and for every α on the grid the leave-one-out
// residuals from the hat matrix, H = 11ᵀ/n + Xc (XcᵀXc + αI)⁻¹ Xcᵀ with Xc the
// centred features (computed in the stable form (M·y)_i / M_ii, see ridge.cpp). With more features than trials (MiniRocket: ~10,000 vs
// ~1,000) everything goes through the n × n Gram matrix K = Xc Xcᵀ = Q Λ Qᵀ,
// eigendecomposed once: every α then costs O(n²) instead of a new solve.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "rollsense/status.hpp"

namespace rollsense::minirocket {

using RowMatrixF = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// n log-spaced values from 10^lo to 10^hi (n = 1: 10^lo).
std::vector<double> log_grid(double log10_low, double log10_high, int n);

struct RidgeFit {
    Eigen::MatrixXd weights;             // features × classes
    Eigen::VectorXd intercept;           // classes
    double alpha = 0.0;                  // the chosen regularisation
    std::vector<double> loo_error;       // mean squared LOO residual per α of the grid
};

// x: n × p features (already standardised; centred here); labels in
// [0, classes). Picks the first α of `alphas` with the least LOO error.
// `threads` splits the Gram matrix over feature blocks (a fixed two-block sum,
// so the result does not depend on it).
Result<RidgeFit> fit_ridge_loo(const RowMatrixF& x, const std::vector<int>& labels, int classes,
                               const std::vector<double>& alphas, unsigned threads);

// ±1 one-vs-rest targets, n × classes.
Eigen::MatrixXd one_vs_rest_targets(const std::vector<int>& labels, int classes);

}  // namespace rollsense::minirocket
