#pragma once
// One family of DataDrivenFit::fit on runs already read (the steps of fitFamily that depend on
// the family): mean, the linear-lag families (mlr, ridge, lagridge, dynamic), exp and synthetic.
// Each fills the result's model, CV figures and parameters and returns the family's
// "hyperparameters" and "uncertainties" objects of MODEL.json. Throws std::invalid_argument
// naming the session or option on bad input.

#include "DataDrivenFit.h"

#include <QJsonObject>

namespace driftlab {

class DataDrivenSession;

// The training runs of one fit: per training session its table and the rows in --train-range.
struct DataDrivenTrainingRuns {
    QList<qint64> ids;
    std::vector<SignalTable> tables;
    std::vector<std::vector<char>> rows;
};

class DataDrivenFamilyFit {
public:
    struct Json {
        QJsonObject hyperparameters, uncertainties;
    };
    using Sub = std::function<bool(double)>;

    static Json mean(const DataDrivenFitRequest &q, const DataDrivenTrainingRuns &runs, DataDrivenFitResult &result);
    // Also sets result.linearOptions / linearChosen, from which the reduced models are fitted.
    static Json linearLag(const DataDrivenFitRequest &q, const DataDrivenTrainingRuns &runs, const QStringList &inputs,
                          const QString &drive, const Sub &sub, DataDrivenFitResult &result);
    static Json exponential(const DataDrivenFitRequest &q, const DataDrivenSession &first, const DataDrivenTrainingRuns &runs,
                            const QString &drive, const Sub &sub, DataDrivenFitResult &result);
    static Json synthetic(const DataDrivenFitRequest &q, const DataDrivenSession &first, const DataDrivenTrainingRuns &runs,
                          const QStringList &inputs, DataDrivenFitResult &result);
};

} // namespace driftlab
