// BlockGram and DesignSums (the cross-validation of LinearLagFitter without design matrices):
// the sums of a design assembled from cached block products equal those of the explicit
// design matrix; the squared error from the sums equals the residuals summed one by one; sums
// of adjacent ranges add up.

#include "BlockGram.h"

#include <QtTest>

#include <random>

using namespace driftlab;
using Eigen::MatrixXd;
using Eigen::VectorXd;

class TestBlockGram : public QObject {
    Q_OBJECT
private slots:
    void sumsEqualTheExplicitDesign();
};

namespace {

MatrixXd random(Eigen::Index rows, Eigen::Index cols, std::mt19937 &rng)
{
    std::normal_distribution<double> n(0.0, 1.0);
    MatrixXd m(rows, cols);
    for (Eigen::Index j = 0; j < cols; ++j)
        for (Eigen::Index i = 0; i < rows; ++i)
            m(i, j) = 2.0 + n(rng);
    return m;
}

double maxDiff(const DesignSums &a, const DesignSums &b)
{
    double d = std::fabs(a.n - b.n) + std::fabs(a.sy - b.sy) + std::fabs(a.syy - b.syy);
    d = std::max(d, (a.s - b.s).cwiseAbs().maxCoeff());
    d = std::max(d, (a.S - b.S).cwiseAbs().maxCoeff());
    return std::max(d, (a.sxy - b.sxy).cwiseAbs().maxCoeff());
}

} // namespace

void TestBlockGram::sumsEqualTheExplicitDesign()
{
    std::mt19937 rng(5);
    const MatrixXd m1 = random(50, 3, rng), m2 = random(50, 4, rng), p2 = random(4, 2, rng);
    const VectorXd y = random(50, 1, rng).col(0);
    MatrixXd select = MatrixXd::Zero(3, 2); // columns 2 and 0 of m1, in that order
    select(2, 0) = 1.0;
    select(0, 1) = 1.0;
    BlockGram gram(y);
    const std::vector<BlockGram::Block> design{{&m1, MatrixXd()}, {&m2, p2}, {&m1, select}};
    MatrixXd x(50, 7);
    x << m1, m2 * p2, m1.col(2), m1.col(0);
    const DesignSums a = gram.sums(design, 10, 35), b = DesignSums::of(x, y, 10, 35);
    QCOMPARE(a.S.rows(), Eigen::Index(7));
    QVERIFY2(maxDiff(a, b) < 1e-9, qPrintable(QString::number(maxDiff(a, b))));
    // Again from the cache (the products are reused, the result is the same).
    QVERIFY(maxDiff(gram.sums(design, 10, 35), b) < 1e-9);
    // Adjacent ranges add up; the difference of a range and a part of it is the rest.
    const DesignSums whole = gram.sums(design, 0, 50);
    QVERIFY(maxDiff(gram.sums(design, 0, 10) + gram.sums(design, 10, 50), whole) < 1e-9);
    QVERIFY(maxDiff(whole - gram.sums(design, 0, 10), DesignSums::of(x, y, 10, 50)) < 1e-9);
    // The squared error of any coefficients from the sums equals the residuals one by one.
    const VectorXd c = random(7, 1, rng).col(0);
    const double intercept = 0.7;
    const double explicitSse = (y.segment(10, 25) - x.middleRows(10, 25) * c - VectorXd::Constant(25, intercept)).squaredNorm();
    QVERIFY(explicitSse > 1.0);
    QVERIFY(std::fabs(a.squaredError(c, intercept) - explicitSse) < 1e-9 * explicitSse);
}

QTEST_APPLESS_MAIN(TestBlockGram)
#include "tst_blockgram.moc"
