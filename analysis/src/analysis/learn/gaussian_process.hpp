// A small Gaussian-process regressor for the optimiser's surrogate.
#pragma once

#include <Eigen/Dense>

namespace rollsense::learn {

class GaussianProcess {
public:
    // Fits a zero-mean GP with a Matérn 5/2 kernel to standardised targets,
    // choosing length scale and noise from a grid by log marginal likelihood.
    void fit(const Eigen::MatrixXd& x, const Eigen::VectorXd& y);
    // Predictive mean and standard deviation (of the latent function) at x,
    // in the original units of y.
    void predict(const Eigen::VectorXd& x, double& mean, double& sd) const;

    double length_scale() const { return length_; }
    double noise() const { return noise_; }

private:
    double kernel(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const;

    Eigen::MatrixXd x_;
    Eigen::VectorXd alpha_;
    Eigen::LLT<Eigen::MatrixXd> chol_;
    double y_mean_ = 0.0, y_scale_ = 1.0;
    double length_ = 0.3, noise_ = 1e-3;
};

}  // namespace rollsense::learn
