#include "DataDrivenAuto.h"

#include "ModelSelection.h"

#include <QJsonArray>

#include <chrono>
#include <cmath>
#include <stdexcept>

namespace driftlab {

QStringList DataDrivenAuto::families(bool withDrive)
{
    QStringList f{QStringLiteral("mean"), QStringLiteral("mlr"), QStringLiteral("ridge"), QStringLiteral("lagridge"),
                  QStringLiteral("dynamic")};
    if (withDrive)
        f << QStringLiteral("exp");
    return f;
}

bool DataDrivenAuto::isPlainReference(const QString &family)
{
    return family == QLatin1String("mean") || family == QLatin1String("lagridge");
}

DataDrivenFitResult DataDrivenAuto::fit(const DataDrivenFitRequest &q, const DataDrivenFit::Progress &progress) const
{
    const auto started = std::chrono::steady_clock::now();
    // A drive exists when named, or when the exp family's own check finds one.
    bool withDrive = !q.drive.isEmpty() && q.drive != QLatin1String("none");
    if (q.drive.isEmpty()) {
        DataDrivenFitRequest probe = q;
        probe.model = QStringLiteral("exp");
        probe.points.clear();
        probe.autoPoints = false;
        try {
            m_fit.check(probe);
            withDrive = true;
        } catch (const std::invalid_argument &) {
            withDrive = false;
        }
    }
    const QStringList names = families(withDrive);
    std::vector<DataDrivenFitResult> results(static_cast<std::size_t>(names.size()));
    std::vector<FamilyComparison> table;
    std::vector<FamilyScore> scores;
    QStringList errors;
    for (int i = 0; i < names.size(); ++i) {
        DataDrivenFitRequest r = q;
        r.model = names[i];
        if (r.model == QLatin1String("exp") || r.model == QLatin1String("mean")) {
            r.points.clear();
            r.autoPoints = false;
        }
        if (r.model != QLatin1String("mlr"))
            r.autoPoints = false;
        r.reducedModels = false; // for the chosen family only, below
        FamilyComparison row;
        row.model = names[i];
        FamilyScore score;
        score.family = names[i].toStdString();
        score.plainReference = row.plainReference = isPlainReference(names[i]);
        const double lo = static_cast<double>(i) / static_cast<double>(names.size());
        const double hi = static_cast<double>(i + 1) / static_cast<double>(names.size());
        try {
            results[static_cast<std::size_t>(i)] = m_fit.fit(r, [&](double f, const QString &stage) {
                return !progress || progress(lo + (hi - lo) * f, QStringLiteral("%1: %2").arg(names[i], stage));
            });
            const DataDrivenFitResult &f = results[static_cast<std::size_t>(i)];
            row.cvRmse = f.cvRmse;
            row.cvStandardError = ModelSelection::standardError(f.foldRmse);
            row.nestedCvRmse = f.nestedCvRmse;
            row.nestedFoldRmse = f.nestedFoldRmse;
            row.parameters = f.parameters;
            row.reference = f.model.usesRises() ? QString::fromStdString(f.model.reference.label())
                                                : QStringLiteral("absolute");
            if (f.holdout)
                row.holdout = f.holdout->metrics;
            score.cvRmse = f.nestedCvRmse;
            score.foldRmse = f.nestedFoldRmse;
            score.parameters = f.parameters;
            score.fitted = std::isfinite(f.nestedCvRmse);
        } catch (const std::invalid_argument &e) {
            row.error = QString::fromUtf8(e.what());
            errors << QStringLiteral("%1: %2").arg(names[i], row.error);
            score.fitted = false;
        }
        table.push_back(row);
        scores.push_back(score);
    }
    SelectionRuling ruling;
    try {
        ruling = ModelSelection::referencesFirst(scores);
    } catch (const std::invalid_argument &) {
        throw std::invalid_argument(QStringLiteral("--model auto: no family could be fitted (%1)")
                                        .arg(errors.join(QStringLiteral("; ")))
                                        .toStdString());
    }
    for (std::size_t i = 0; i < table.size(); ++i)
        table[i].pairedStandardError = ruling.pairedStandardError[i];
    table[ruling.chosen].chosen = true;
    DataDrivenFitResult result = results[ruling.chosen];
    if (q.reducedModels) {
        if (progress && !progress(0.99, QStringLiteral("%1: fitting the reduced models").arg(names[static_cast<int>(ruling.chosen)])))
            throw std::runtime_error("cancelled");
        m_fit.addReducedModels(result, q);
    }
    result.comparison = table;
    QJsonObject selection = DataDrivenFit::comparisonJson(table);
    selection.insert(QStringLiteral("lowest_cv"), names[static_cast<int>(ruling.lowest)]);
    selection.insert(QStringLiteral("cv_standard_error_um"), ruling.standardError);
    selection.insert(QStringLiteral("threshold_um"), ruling.threshold);
    result.document.insert(QStringLiteral("model_selection"), selection);
    result.wallTime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    result.document.insert(QStringLiteral("fit_wall_time_s"), result.wallTime_s);
    return result;
}

} // namespace driftlab
