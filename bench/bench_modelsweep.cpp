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
//
// With --train-range and --holdout-range and one SESSION: one time-ordered split of that
// session instead (FL_THERMAL's public 60/20 anchor), with MAE besides RMSE.
// scripts/model-sweep.sh builds the databases (FL_THERMAL cut into its on/off cycles, rig
// campaigns) and runs this program on each.

#include "DataDrivenFit.h"
#include "SessionStore.h"

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
            return 0;
        }
        if (sessions.size() < 4) {
            std::fprintf(stderr, "bench_modelsweep: leave-runs-out needs at least 4 sessions (3 to train)\n");
            return 2;
        }
        std::map<QString, double> sse, count;
        double autoSse = 0.0, autoN = 0.0, autoTime = 0.0, lagTime = 0.0;
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
    } catch (const std::exception &e) {
        std::fprintf(stderr, "bench_modelsweep: %s\n", e.what());
        return 1;
    }
    return 0;
}
