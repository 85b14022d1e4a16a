#pragma once
// Sufficient statistics of a linear regression over a set of samples: the count, the column
// sums and cross-products of the design X and the sums of y, y^2 and X'y. Ridge and OLS fits
// (LinearLagFitter) and their squared error on the same samples need nothing else, so
// cross-validation folds are added and subtracted instead of refitted from the rows.

#include <Eigen/Dense>

namespace driftlab {

struct DesignSums {
    double n = 0.0;
    Eigen::VectorXd s;   // column sums of X
    Eigen::MatrixXd S;   // X'X
    double sy = 0.0, syy = 0.0;
    Eigen::VectorXd sxy; // X'y

    // Over rows [begin, end) of X and y.
    static DesignSums of(const Eigen::MatrixXd &X, const Eigen::VectorXd &y, Eigen::Index begin, Eigen::Index end);
    DesignSums operator+(const DesignSums &o) const;
    DesignSums operator-(const DesignSums &o) const;
    // Sum over these samples of (y - intercept - x'c)^2 (clamped at 0 against rounding).
    double squaredError(const Eigen::VectorXd &c, double intercept) const;
};

} // namespace driftlab
