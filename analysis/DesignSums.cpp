#include "DesignSums.h"

#include <algorithm>

namespace driftlab {

DesignSums DesignSums::of(const Eigen::MatrixXd &X, const Eigen::VectorXd &y, Eigen::Index begin, Eigen::Index end)
{
    DesignSums r;
    const Eigen::Index p = X.cols();
    r.n = static_cast<double>(end - begin);
    const auto Xb = X.middleRows(begin, end - begin);
    const auto yb = y.segment(begin, end - begin);
    r.s = Xb.colwise().sum().transpose();
    r.S = Eigen::MatrixXd::Zero(p, p);
    r.S.selfadjointView<Eigen::Lower>().rankUpdate(Xb.transpose());
    r.S = r.S.selfadjointView<Eigen::Lower>();
    r.sy = yb.sum();
    r.syy = yb.squaredNorm();
    r.sxy = Xb.transpose() * yb;
    return r;
}

DesignSums DesignSums::operator+(const DesignSums &o) const
{
    DesignSums r;
    r.n = n + o.n;
    r.s = s + o.s;
    r.S = S + o.S;
    r.sy = sy + o.sy;
    r.syy = syy + o.syy;
    r.sxy = sxy + o.sxy;
    return r;
}

DesignSums DesignSums::operator-(const DesignSums &o) const
{
    DesignSums r;
    r.n = n - o.n;
    r.s = s - o.s;
    r.S = S - o.S;
    r.sy = sy - o.sy;
    r.syy = syy - o.syy;
    r.sxy = sxy - o.sxy;
    return r;
}

double DesignSums::squaredError(const Eigen::VectorXd &c, double intercept) const
{
    const double e = syy - 2.0 * intercept * sy - 2.0 * c.dot(sxy) + n * intercept * intercept + 2.0 * intercept * c.dot(s) +
                     c.dot(S * c);
    return std::max(0.0, e);
}

} // namespace driftlab
