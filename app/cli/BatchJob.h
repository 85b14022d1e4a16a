#pragma once
// A batch job file (docs/batch.md): the recordings to process (bundles, a folder of bundles,
// or sessions of a database), the steps to run on each (import, select-points, fit, diagnose,
// export-model, plot, report, each with its command's options) and the output folder. Paths are relative
// to the job file. Parsing checks everything it can before any work starts and throws
// UsageError naming the file and field ("job.json: steps[2].step: unknown step 'fitt'").

#include <QJsonObject>
#include <QString>
#include <QStringList>
#include <QVector>

namespace driftlab {

struct BatchStep {
    QString name;        // import | select-points | fit | diagnose | export-model | plot | report
    QStringList options; // the command's options from the step's other fields: "--key", "value"
    QString label;       // name plus its distinguishing option (fit-mlr, plot-error-surface)
    QString source;      // export-model: the label of the fit step whose model it exports (fit-mlr)
};

struct BatchInput {
    QString bundle;      // a bundle directory or .zip (imported into its own database) ...
    QString database;    // ... or a session of an existing database
    qint64 session = 0;
    QString label;       // the input's folder name under the output folder
};

struct BatchJob {
    QString file;
    QString output;      // absolute
    QVector<BatchInput> inputs;
    QVector<BatchStep> steps;
    int jobs = 0;        // sessions at a time; 0 = the number of cores

    static BatchJob read(const QString &path);
    static QStringList stepNames();
};

} // namespace driftlab
