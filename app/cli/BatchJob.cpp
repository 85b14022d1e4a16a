#include "BatchJob.h"

#include "CliCommand.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QSet>

#include <cmath>

namespace driftlab {

QStringList BatchJob::stepNames()
{
    return {QStringLiteral("import"), QStringLiteral("select-points"), QStringLiteral("fit"), QStringLiteral("diagnose"),
            QStringLiteral("export-model"), QStringLiteral("plot"), QStringLiteral("report")};
}

BatchJob BatchJob::read(const QString &path)
{
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly))
        throw UsageError(QStringLiteral("batch: cannot read the job file %1 (%2)").arg(path, f.errorString()));
    QJsonParseError error{};
    const QJsonDocument doc = QJsonDocument::fromJson(f.readAll(), &error);
    if (error.error != QJsonParseError::NoError || !doc.isObject())
        throw UsageError(QStringLiteral("batch: %1: not a JSON object (%2 at offset %3)").arg(path, error.errorString()).arg(error.offset));
    const QJsonObject o = doc.object();
    const QDir base = QFileInfo(path).absoluteDir();
    const auto fail = [&](const QString &field, const QString &what) {
        return UsageError(QStringLiteral("batch: %1: %2: %3").arg(path, field, what));
    };
    static const QStringList known = {QStringLiteral("output"), QStringLiteral("bundles"), QStringLiteral("bundle_folder"),
                                      QStringLiteral("database"), QStringLiteral("sessions"), QStringLiteral("steps"),
                                      QStringLiteral("jobs")};
    for (const QString &key : o.keys())
        if (!known.contains(key))
            throw fail(key, QStringLiteral("unknown field (known: %1)").arg(known.join(QStringLiteral(", "))));

    BatchJob job;
    job.file = QFileInfo(path).absoluteFilePath();
    if (!o.value(QStringLiteral("output")).isString() || o.value(QStringLiteral("output")).toString().isEmpty())
        throw fail(QStringLiteral("output"), QStringLiteral("required: the folder for the results"));
    job.output = QDir::cleanPath(base.absoluteFilePath(o.value(QStringLiteral("output")).toString()));
    if (o.contains(QStringLiteral("jobs"))) {
        job.jobs = o.value(QStringLiteral("jobs")).toInt(-1);
        if (job.jobs < 1)
            throw fail(QStringLiteral("jobs"), QStringLiteral("must be a whole number >= 1"));
    }

    QSet<QString> labels;
    const auto addBundle = [&](const QString &file, const QString &field) {
        const QFileInfo fi(base.absoluteFilePath(file));
        if (!fi.exists())
            throw fail(field, QStringLiteral("%1 does not exist").arg(fi.filePath()));
        BatchInput in;
        in.bundle = fi.absoluteFilePath();
        QString label = fi.fileName();
        for (const char *suffix : {".zip", ".bundle"})
            if (label.endsWith(QLatin1String(suffix)))
                label.chop(static_cast<int>(qstrlen(suffix)));
        in.label = label;
        for (int n = 2; labels.contains(in.label); ++n)
            in.label = QStringLiteral("%1-%2").arg(label).arg(n);
        labels.insert(in.label);
        job.inputs.push_back(in);
    };
    const QJsonValue bundles = o.value(QStringLiteral("bundles"));
    if (!bundles.isUndefined() && !bundles.isArray())
        throw fail(QStringLiteral("bundles"), QStringLiteral("must be an array of bundle paths"));
    const QJsonArray bundleList = bundles.toArray();
    for (int i = 0; i < bundleList.size(); ++i) {
        if (!bundleList[i].isString())
            throw fail(QStringLiteral("bundles[%1]").arg(i), QStringLiteral("must be a path"));
        addBundle(bundleList[i].toString(), QStringLiteral("bundles[%1]").arg(i));
    }
    if (o.contains(QStringLiteral("bundle_folder"))) {
        const QDir folder(base.absoluteFilePath(o.value(QStringLiteral("bundle_folder")).toString()));
        if (!o.value(QStringLiteral("bundle_folder")).isString() || !folder.exists())
            throw fail(QStringLiteral("bundle_folder"), QStringLiteral("must name an existing folder"));
        const QFileInfoList entries = folder.entryInfoList(QDir::Dirs | QDir::Files | QDir::NoDotAndDotDot, QDir::Name);
        for (const QFileInfo &e : entries)
            if ((e.isDir() && QFileInfo::exists(e.filePath() + QStringLiteral("/manifest.json"))) ||
                (e.isFile() && e.suffix().toLower() == QLatin1String("zip")))
                addBundle(e.absoluteFilePath(), QStringLiteral("bundle_folder"));
    }
    if (o.contains(QStringLiteral("sessions"))) {
        const QString db = base.absoluteFilePath(o.value(QStringLiteral("database")).toString());
        if (!o.value(QStringLiteral("database")).isString() || !QFileInfo(db).isFile())
            throw fail(QStringLiteral("database"), QStringLiteral("'sessions' needs 'database': an existing session database"));
        const QJsonArray ids = o.value(QStringLiteral("sessions")).toArray();
        for (int i = 0; i < ids.size(); ++i) {
            const qint64 id = ids[i].isDouble() && ids[i].toDouble() == std::floor(ids[i].toDouble()) ? static_cast<qint64>(ids[i].toDouble()) : -1;
            if (id < 1)
                throw fail(QStringLiteral("sessions[%1]").arg(i), QStringLiteral("must be a session id"));
            BatchInput in;
            in.database = db;
            in.session = id;
            in.label = QStringLiteral("session-%1").arg(id);
            labels.insert(in.label);
            job.inputs.push_back(in);
        }
    } else if (o.contains(QStringLiteral("database"))) {
        throw fail(QStringLiteral("database"), QStringLiteral("only used with 'sessions'"));
    }
    if (job.inputs.isEmpty())
        throw fail(QStringLiteral("bundles"), QStringLiteral("no recordings: give 'bundles', 'bundle_folder' or 'database' + 'sessions'"));

    const QJsonArray steps = o.value(QStringLiteral("steps")).toArray();
    if (steps.isEmpty())
        throw fail(QStringLiteral("steps"), QStringLiteral("required: an array of steps such as {\"step\": \"report\", \"format\": \"pdf\"}"));
    bool imports = false;
    QSet<QString> stepLabels;
    for (int i = 0; i < steps.size(); ++i) {
        const QString field = QStringLiteral("steps[%1]").arg(i);
        const QJsonObject s = steps[i].toObject();
        BatchStep step;
        step.name = s.value(QStringLiteral("step")).toString();
        if (!stepNames().contains(step.name))
            throw fail(field + QStringLiteral(".step"), QStringLiteral("'%1' is not a step (one of %2)")
                                                            .arg(step.name, stepNames().join(QStringLiteral(", "))));
        if (step.name == QLatin1String("import")) {
            if (i != 0)
                throw fail(field, QStringLiteral("import must be the first step"));
            imports = true;
        }
        step.label = step.name;
        for (auto it = s.begin(); it != s.end(); ++it) {
            if (it.key() == QLatin1String("step"))
                continue;
            // The batch chooses the database and every output file itself.
            static const QStringList owned = {QStringLiteral("db"), QStringLiteral("out"), QStringLiteral("json")};
            if (owned.contains(it.key()))
                throw fail(field + QLatin1Char('.') + it.key(), QStringLiteral("set by the batch (outputs go to the output folder)"));
            QString value;
            if (it.value().isString())
                value = it.value().toString();
            else if (it.value().isDouble())
                value = QString::number(it.value().toDouble(), 'g', 12);
            else
                throw fail(field + QLatin1Char('.') + it.key(), QStringLiteral("must be a string or a number"));
            if (it.key() == QLatin1String("format")) {
                if (step.name != QLatin1String("report") && step.name != QLatin1String("plot"))
                    throw fail(field + QStringLiteral(".format"), QStringLiteral("only report and plot have a format"));
                const QStringList formats = step.name == QLatin1String("report")
                                                ? QStringList{QStringLiteral("pdf"), QStringLiteral("html")}
                                                : QStringList{QStringLiteral("svg"), QStringLiteral("pdf"), QStringLiteral("png")};
                if (!formats.contains(value))
                    throw fail(field + QStringLiteral(".format"), QStringLiteral("one of %1").arg(formats.join(QStringLiteral(", "))));
                step.label += QStringLiteral("-") + value;
                step.options << QStringLiteral("%format") << value; // resolved into --out by the runner
                continue;
            }
            if ((it.key() == QLatin1String("template") || it.key() == QLatin1String("validate") ||
                 it.key() == QLatin1String("holdout")) && QFileInfo::exists(base.absoluteFilePath(value)))
                value = base.absoluteFilePath(value); // paths relative to the job file
            if (it.key() == QLatin1String("model") || it.key() == QLatin1String("view"))
                step.label += QStringLiteral("-") + value;
            if (step.name == QLatin1String("export-model") && it.key() == QLatin1String("model")) {
                // Not an option of export-model: names the fit step whose MODEL.json it exports.
                step.source = QStringLiteral("fit-") + value;
                if (value == QLatin1String("fdm") && !stepLabels.contains(step.source))
                    step.source = QStringLiteral("fit"); // {"step": "fit"} fits the physics model
                if (!stepLabels.contains(step.source))
                    throw fail(field + QStringLiteral(".model"),
                               QStringLiteral("no earlier {\"step\": \"fit\", \"model\": \"%1\"} step writes the model to export").arg(value));
                continue;
            }
            if (step.name == QLatin1String("export-model") && it.key() == QLatin1String("target"))
                step.label += QStringLiteral("-") + value;
            step.options << QStringLiteral("--") + it.key() << value;
        }
        if (step.name == QLatin1String("diagnose") && !s.contains(QStringLiteral("validate")))
            throw fail(field + QStringLiteral(".validate"), QStringLiteral("required: the held-out recording (bundle path or session id)"));
        if (step.name == QLatin1String("export-model") && (step.source.isEmpty() || !s.contains(QStringLiteral("target"))))
            throw fail(field + (step.source.isEmpty() ? QStringLiteral(".model") : QStringLiteral(".target")),
                       QStringLiteral("required: export-model needs the fitted 'model' (of an earlier fit step) and the controller 'target'"));
        if (step.name == QLatin1String("plot") && !s.contains(QStringLiteral("view")))
            throw fail(field + QStringLiteral(".view"), QStringLiteral("required (plot --help lists the views)"));
        if (stepLabels.contains(step.label))
            throw fail(field, QStringLiteral("a second '%1' step would overwrite the first's output").arg(step.label));
        stepLabels.insert(step.label);
        job.steps.push_back(step);
    }
    for (const BatchInput &in : job.inputs)
        if (!in.bundle.isEmpty() && !imports)
            throw fail(QStringLiteral("steps"), QStringLiteral("bundles need an 'import' step first"));
        else if (in.bundle.isEmpty() && imports)
            throw fail(QStringLiteral("steps[0]"), QStringLiteral("sessions of 'database' are already imported: drop 'import'"));
    return job;
}

} // namespace driftlab
