// Leave-runs-out sweep of the data-driven families over the sessions of a database (issue 32
// item 7): for every listed session in turn, every family is fitted on the other sessions by
// `fit --model auto` (DataDrivenAuto: hyperparameters, temperature reference and the family by
// cross-validation over whole sessions) and scored on the held-out one. Prints the held-out
// RMSE of every family per held-out session and pooled, the auto choice, and how often auto
// loses to either plain reference computed in the same run: the training mean (`mean`) and
// ridge on rises with first-order lags (`lagridge`). The time of the auto fit is printed
// against the plain lagridge fit alone (the ratio the speed target is stated against).
//
//   bench_modelsweep DB TARGET SESSION... [--train-range H:H --holdout-range H:H]
//
// Diagnostics (environment): BENCH_FOLDS=1 prints every family's nested CV RMSE per inner fold;
// BENCH_BLEND=1 also fits dynamic and lagridge alone per held-out session and prints the
// held-out RMSE of their blends (weight 0, 0.25 .. 1 on dynamic; docs/datadriven.md, FL ch5).
// Variants measured beside auto's rule (docs/datadriven.md, round 4b), never the default:
// the Nadeau-Bengio corrected resampled t-test in the one-SE rule (always printed: it needs no
// extra fit) and, with BENCH_STACK=1, non-negative stacking of mean, lagridge, dynamic and exp:
// weights >= 0 summing to 1 fitted by least squares on the pooled inner out-of-fold
// predictions (each inner run predicted by the families fitted, with their own searches, on
// the other training runs), applied to the families refitted on all training runs.
//
// With --train-range and --holdout-range and one SESSION: one time-ordered split of that
// session instead (FL_THERMAL's public 60/20 anchor), with MAE besides RMSE.
// scripts/model-sweep.sh builds the databases (FL_THERMAL cut into its on/off cycles, rig
// campaigns) and runs this program on each.

#include "DataDrivenFit.h"
#include "ModelSelection.h"
#include "SessionStore.h"

#include <Eigen/Dense>

#include <QCoreApplication>
#include <QStringList>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

using namespace driftlab;

namespace {

double seconds(std::chrono::steady_clock::time_point a)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count();
}

// The choice of auto's rule with every paired SE scaled by the Nadeau-Bengio factor.
const FamilyComparison &nadeauBengioChoice(const std::vector<FamilyComparison> &table, double factor)
{
    std::vector<FamilyScore> scores;
    for (const FamilyComparison &c : table) {
        FamilyScore f;
        f.family = c.model.toStdString();
        f.cvRmse = c.nestedCvRmse;
        f.foldRmse = c.nestedFoldRmse;
        f.parameters = c.parameters;
        f.fitted = c.error.isEmpty() && std::isfinite(c.nestedCvRmse);
        f.plainReference = c.plainReference;
        scores.push_back(f);
    }
    return table[ModelSelection::referencesFirst(scores, factor).chosen];
}

// min |y - F w|^2 subject to w >= 0, sum w = 1: equality-constrained least squares on every
// subset of the columns (at most 4), the best one whose weights are all non-negative.
std::vector<double> simplexLeastSquares(const Eigen::MatrixXd &F, const Eigen::VectorXd &y)
{
    const int k = static_cast<int>(F.cols());
    std::vector<double> best(static_cast<std::size_t>(k), 0.0);
    double bestSse = INFINITY;
    for (int mask = 1; mask < (1 << k); ++mask) {
        std::vector<int> cols;
        for (int j = 0; j < k; ++j)
            if (mask & (1 << j))
                cols.push_back(j);
        const int m = static_cast<int>(cols.size());
        Eigen::MatrixXd Fs(F.rows(), m);
        for (int j = 0; j < m; ++j)
            Fs.col(j) = F.col(cols[static_cast<std::size_t>(j)]);
        Eigen::MatrixXd K = Eigen::MatrixXd::Zero(m + 1, m + 1);
        K.topLeftCorner(m, m) = Fs.transpose() * Fs;
        K.block(0, m, m, 1).setOnes();
        K.block(m, 0, 1, m).setOnes();
        Eigen::VectorXd rhs(m + 1);
        rhs.head(m) = Fs.transpose() * y;
        rhs(m) = 1.0;
        const Eigen::VectorXd sol = K.colPivHouseholderQr().solve(rhs);
        if ((sol.head(m).array() < -1e-12).any())
            continue;
        const double sse = (y - Fs * sol.head(m)).squaredNorm();
        if (sse < bestSse) {
            bestSse = sse;
            std::fill(best.begin(), best.end(), 0.0);
            for (int j = 0; j < m; ++j)
                best[static_cast<std::size_t>(cols[static_cast<std::size_t>(j)])] = std::max(0.0, sol(j));
        }
    }
    return best;
}

// Held-out predictions of every family fitted on q's training runs (rows: samples of q's
// held-out runs, pooled; columns: families), and the measured values.
void familyPredictions(const DataDrivenFit &fit, DataDrivenFitRequest q, const QStringList &families,
                       std::vector<std::vector<double>> &cols, std::vector<double> &measured)
{
    q.reducedModels = false;
    for (const QString &f : families) {
        q.model = f;
        q.autoPoints = false;
        if (f == QLatin1String("exp") || f == QLatin1String("mean"))
            q.points.clear();
        const DataDrivenFitResult r = fit.fit(q);
        if (measured.empty())
            measured = r.holdout->measured;
        if (r.holdout->predicted.size() != measured.size())
            throw std::runtime_error("stacking: the families score different held-out samples");
        cols.push_back(r.holdout->predicted);
    }
}

// Stacked held-out squared error and sample count for q (training runs, one held-out run).
std::pair<double, double> stackedHeldOut(const DataDrivenFit &fit, const DataDrivenFitRequest &q, const QStringList &families)
{
    std::vector<std::vector<double>> oof(static_cast<std::size_t>(families.size()));
    std::vector<double> y;
    for (qint64 inner : q.sessions) {
        DataDrivenFitRequest iq = q;
        iq.sessions.removeAll(inner);
        iq.session = iq.sessions.front();
        iq.holdoutSessions = {inner};
        std::vector<std::vector<double>> cols;
        std::vector<double> measured;
        familyPredictions(fit, iq, families, cols, measured);
        for (std::size_t k = 0; k < measured.size(); ++k) {
            bool ok = std::isfinite(measured[k]);
            for (const auto &c : cols)
                ok = ok && std::isfinite(c[k]);
            if (!ok)
                continue;
            y.push_back(measured[k]);
            for (std::size_t j = 0; j < cols.size(); ++j)
                oof[j].push_back(cols[j][k]);
        }
    }
    Eigen::MatrixXd F(static_cast<Eigen::Index>(y.size()), families.size());
    for (std::size_t j = 0; j < oof.size(); ++j)
        F.col(static_cast<Eigen::Index>(j)) = Eigen::Map<const Eigen::VectorXd>(oof[j].data(), static_cast<Eigen::Index>(y.size()));
    const std::vector<double> w = simplexLeastSquares(F, Eigen::Map<const Eigen::VectorXd>(y.data(), static_cast<Eigen::Index>(y.size())));
    std::printf("    stack weights (inner out-of-fold, %zu samples):", y.size());
    for (int j = 0; j < families.size(); ++j)
        std::printf(" %s %.3f", qPrintable(families[j]), w[static_cast<std::size_t>(j)]);
    std::vector<std::vector<double>> cols;
    std::vector<double> measured;
    familyPredictions(fit, q, families, cols, measured);
    double e2 = 0.0, n = 0.0;
    for (std::size_t k = 0; k < measured.size(); ++k) {
        double p = 0.0;
        for (std::size_t j = 0; j < cols.size(); ++j)
            p += w[j] * cols[j][k];
        if (!std::isfinite(p) || !std::isfinite(measured[k]))
            continue;
        e2 += (measured[k] - p) * (measured[k] - p);
        n += 1.0;
    }
    std::printf(" | held-out RMSE %.3f\n", std::sqrt(e2 / n));
    return {e2, n};
}

int usage()
{
    std::fprintf(stderr, "usage: bench_modelsweep DB TARGET SESSION... [--train-range H:H --holdout-range H:H]\n");
    return 2;
}

} // namespace

int main(int argc, char **argv)
{
    QCoreApplication app(argc, argv);
    QStringList args = app.arguments().mid(1);
    QString trainRange, holdoutRange;
    for (int i = 0; i < args.size(); ++i)
        if ((args[i] == QLatin1String("--train-range") || args[i] == QLatin1String("--holdout-range")) && i + 1 < args.size()) {
            (args[i] == QLatin1String("--train-range") ? trainRange : holdoutRange) = args[i + 1];
            args.removeAt(i);
            args.removeAt(i);
            --i;
        }
    if (args.size() < 3)
        return usage();
    const QString db = args[0], target = args[1];
    QList<qint64> sessions;
    for (int i = 2; i < args.size(); ++i) {
        bool ok = false;
        const qint64 id = args[i].toLongLong(&ok);
        if (!ok)
            return usage();
        sessions << id;
    }
    try {
        SessionStore store(db);
        const DataDrivenFit fit(store);
        if (!trainRange.isEmpty()) {
            DataDrivenFitRequest q;
            q.session = sessions.front();
            q.model = QStringLiteral("auto");
            q.target = target;
            q.train = HourRange::parse(trainRange, QStringLiteral("--train-range"));
            q.holdoutRange = HourRange::parse(holdoutRange, QStringLiteral("--holdout-range"));
            const auto t0 = std::chrono::steady_clock::now();
            const DataDrivenFitResult r = fit.fit(q);
            std::printf("%s, session %lld, train %s h, held out %s h (auto %.1f s)\n", qPrintable(target),
                        static_cast<long long>(q.session), qPrintable(trainRange), qPrintable(holdoutRange), seconds(t0));
            std::printf("  %-9s %9s %9s %9s %9s %7s\n", "family", "CV RMSE", "nested CV", "held RMSE", "held MAE", "params");
            for (const FamilyComparison &c : r.comparison)
                std::printf("%s %-9s %9.3f %9.3f %9.3f %9.3f %7d%s\n", c.chosen ? "*" : " ", qPrintable(c.model), c.cvRmse, c.nestedCvRmse,
                            c.holdout ? c.holdout->rmse : NAN, c.holdout ? c.holdout->mae : NAN, c.parameters,
                            c.error.isEmpty() ? "" : qPrintable(QStringLiteral("  (%1)").arg(c.error)));
            // Time-blocked folds of about equal length: n_test / n_train = 1 / (folds - 1).
            const double nb = ModelSelection::nadeauBengioFactor(q.folds, 1.0 / (q.folds - 1));
            const FamilyComparison &c = nadeauBengioChoice(r.comparison, nb);
            std::printf("  Nadeau-Bengio (SE x %.2f) chooses %s: held RMSE %.3f, MAE %.3f\n", nb, qPrintable(c.model),
                        c.holdout ? c.holdout->rmse : NAN, c.holdout ? c.holdout->mae : NAN);
            return 0;
        }
        if (sessions.size() < 4) {
            std::fprintf(stderr, "bench_modelsweep: leave-runs-out needs at least 4 sessions (3 to train)\n");
            return 2;
        }
        std::map<QString, double> sse, count;
        double autoSse = 0.0, autoN = 0.0, autoTime = 0.0, lagTime = 0.0, nbSse = 0.0, nbN = 0.0, stackSse = 0.0,
               stackN = 0.0, stackTime = 0.0;
        int nbLosesToLag = 0, stackLosesToLag = 0, nbLosesToMean = 0, stackLosesToMean = 0;
        std::map<QString, int> nbChoices;
        const bool stack = qEnvironmentVariableIsSet("BENCH_STACK");
        int losesToMean = 0, losesToLag = 0, beatsBoth = 0;
        std::map<QString, int> choices;
        std::printf("%s: leave one session out of %d\n", qPrintable(target), static_cast<int>(sessions.size()));
        for (qint64 held : sessions) {
            DataDrivenFitRequest q;
            q.sessions = sessions;
            q.sessions.removeAll(held);
            q.session = q.sessions.front();
            q.holdoutSessions = {held};
            q.model = QStringLiteral("auto");
            q.target = target;
            auto t0 = std::chrono::steady_clock::now();
            const DataDrivenFitResult r = fit.fit(q);
            autoTime += seconds(t0);
            q.model = QStringLiteral("lagridge");
            t0 = std::chrono::steady_clock::now();
            fit.fit(q);
            lagTime += seconds(t0);
            std::map<QString, double> rmse;
            QString chosen;
            std::printf("  held out %lld:", static_cast<long long>(held));
            for (const FamilyComparison &c : r.comparison) {
                if (!c.holdout) {
                    std::printf("  %s -", qPrintable(c.model));
                    continue;
                }
                rmse[c.model] = c.holdout->rmse;
                sse[c.model] += c.holdout->mse * static_cast<double>(c.holdout->n);
                count[c.model] += static_cast<double>(c.holdout->n);
                std::printf("  %s%s %.3f", c.chosen ? "*" : "", qPrintable(c.model), c.holdout->rmse);
                if (c.chosen) {
                    chosen = c.model;
                    autoSse += c.holdout->mse * static_cast<double>(c.holdout->n);
                    autoN += static_cast<double>(c.holdout->n);
                }
            }
            std::printf("\n    nested CV (+- paired SE):");
            for (const FamilyComparison &c : r.comparison)
                std::printf("  %s %.3f+-%.3f", qPrintable(c.model), c.nestedCvRmse, c.pairedStandardError);
            std::printf("\n");
            if (qEnvironmentVariableIsSet("BENCH_FOLDS"))
                for (const FamilyComparison &c : r.comparison) {
                    std::printf("      %-9s folds:", qPrintable(c.model));
                    for (double x : c.nestedFoldRmse)
                        std::printf(" %.3f", x);
                    std::printf("\n");
                }
            if (qEnvironmentVariableIsSet("BENCH_BLEND")) {
                DataDrivenFitRequest a = q, b = q;
                a.model = QStringLiteral("dynamic");
                b.model = QStringLiteral("lagridge");
                const DataDrivenFitResult ra = fit.fit(a), rb = fit.fit(b);
                const ValidationSeries &sa = *ra.holdout, &sb = *rb.holdout;
                std::printf("    blend dynamic/lagridge held-out RMSE by weight on dynamic:");
                for (double w : {0.0, 0.25, 0.5, 0.75, 1.0}) {
                    double e2 = 0.0, n = 0.0;
                    for (std::size_t k = 0; k < sa.measured.size(); ++k) {
                        if (!std::isfinite(sa.predicted[k]) || !std::isfinite(sb.predicted[k]) || !std::isfinite(sa.measured[k]))
                            continue;
                        const double e = sa.measured[k] - (w * sa.predicted[k] + (1 - w) * sb.predicted[k]);
                        e2 += e * e;
                        n += 1;
                    }
                    std::printf(" %.2f:%.3f", w, std::sqrt(e2 / n));
                }
                std::printf("\n");
            }
            {
                // Leave-one-run-out inner folds: n_test / n_train averaged over the folds.
                double total = 0.0, ratio = 0.0;
                for (const ValidationSeries &t : r.trainingSessions)
                    total += static_cast<double>(t.t.size());
                for (const ValidationSeries &t : r.trainingSessions)
                    ratio += static_cast<double>(t.t.size()) / (total - static_cast<double>(t.t.size()));
                const int folds = static_cast<int>(r.trainingSessions.size());
                const double nb = ModelSelection::nadeauBengioFactor(folds, std::isfinite(ratio) && ratio > 0.0 ? ratio / folds
                                                                                                                    : 1.0 / (folds - 1));
                const FamilyComparison &c = nadeauBengioChoice(r.comparison, nb);
                ++nbChoices[c.model];
                nbSse += c.holdout->mse * static_cast<double>(c.holdout->n);
                nbN += static_cast<double>(c.holdout->n);
                nbLosesToLag += c.holdout->rmse > rmse[QStringLiteral("lagridge")];
                nbLosesToMean += c.holdout->rmse > rmse[QStringLiteral("mean")];
                std::printf("    Nadeau-Bengio (SE x %.2f): %s %.3f\n", nb, qPrintable(c.model), c.holdout->rmse);
            }
            if (stack) {
                QStringList fam;
                for (const FamilyComparison &c : r.comparison)
                    if (c.error.isEmpty() && (c.model == QLatin1String("mean") || c.model == QLatin1String("lagridge") ||
                                              c.model == QLatin1String("dynamic") || c.model == QLatin1String("exp")))
                        fam << c.model;
                t0 = std::chrono::steady_clock::now();
                const auto [e2, n] = stackedHeldOut(fit, q, fam);
                stackTime += seconds(t0);
                stackSse += e2;
                stackN += n;
                const double rm = std::sqrt(e2 / n);
                stackLosesToLag += rm > rmse[QStringLiteral("lagridge")];
                stackLosesToMean += rm > rmse[QStringLiteral("mean")];
            }
            ++choices[chosen];
            const double a = rmse[chosen];
            losesToMean += a > rmse[QStringLiteral("mean")];
            losesToLag += a > rmse[QStringLiteral("lagridge")];
            beatsBoth += a < std::min(rmse[QStringLiteral("mean")], rmse[QStringLiteral("lagridge")]);
        }
        std::printf("  pooled held-out RMSE:");
        for (const auto &e : sse)
            std::printf("  %s %.3f", qPrintable(e.first), std::sqrt(e.second / count[e.first]));
        const double pooledAuto = std::sqrt(autoSse / autoN);
        const double pooledRef = std::min(std::sqrt(sse[QStringLiteral("mean")] / count[QStringLiteral("mean")]),
                                          std::sqrt(sse[QStringLiteral("lagridge")] / count[QStringLiteral("lagridge")]));
        std::printf("  | auto %.3f (%s the better reference, %.3f)\n  auto chose:", pooledAuto,
                    pooledAuto <= pooledRef ? "not worse than" : "WORSE than", pooledRef);
        for (const auto &e : choices)
            std::printf(" %s x%d", qPrintable(e.first), e.second);
        std::printf("\n  auto loses to the training mean in %d of %d, to lagridge in %d of %d; beats both in %d\n",
                    losesToMean, static_cast<int>(sessions.size()), losesToLag, static_cast<int>(sessions.size()), beatsBoth);
        std::printf("  time: auto %.2f s, lagridge alone %.2f s (ratio %.1f)\n", autoTime, lagTime, autoTime / lagTime);
        std::printf("  Nadeau-Bengio variant: pooled %.3f (%s the better reference), chose:", std::sqrt(nbSse / nbN),
                    std::sqrt(nbSse / nbN) <= pooledRef ? "not worse than" : "WORSE than");
        for (const auto &e : nbChoices)
            std::printf(" %s x%d", qPrintable(e.first), e.second);
        std::printf("; loses to mean in %d, to lagridge in %d\n", nbLosesToMean, nbLosesToLag);
        if (stack)
            std::printf("  stacking variant: pooled %.3f (%s the better reference); loses to mean in %d, to lagridge in %d; "
                        "%.1f s\n",
                        std::sqrt(stackSse / stackN), std::sqrt(stackSse / stackN) <= pooledRef ? "not worse than" : "WORSE than",
                        stackLosesToMean, stackLosesToLag, stackTime);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "bench_modelsweep: %s\n", e.what());
        return 1;
    }
    return 0;
}
