#include "ExportModelCommand.h"

#include "CliOptions.h"
#include "CliSupport.h"
#include "OutputTarget.h"
#include "ModelExport.h"

#include <QCommandLineParser>
#include <QJsonArray>
#include <QJsonObject>
#include <QTextStream>

#include <cmath>

namespace driftlab {

namespace {

ExportRange range(const QString &text, const QString &option)
{
    const QStringList parts = text.split(QLatin1Char(':'));
    bool ok[3] = {false, false, false};
    if (parts.size() == 3) {
        const ExportRange r{parts[0].toDouble(&ok[0]), parts[1].toDouble(&ok[1]), parts[2].toDouble(&ok[2])};
        if (ok[0] && ok[1] && ok[2] && std::isfinite(r.from) && r.to > r.from && r.step > 0 &&
            (r.to - r.from) / r.step <= 100000)
            return r;
    }
    throw UsageError(QStringLiteral("export-model: %1 must be FROM:TO:STEP with FROM < TO, STEP > 0 and at most "
                                    "100000 steps, got '%2'")
                         .arg(option, text));
}

double finite(const QString &text, const QString &option)
{
    bool ok = false;
    const double v = text.toDouble(&ok);
    if (!ok || !std::isfinite(v))
        throw UsageError(QStringLiteral("export-model: %1 must be a number, got '%2'").arg(option, text));
    return v;
}

} // namespace

QString ExportModelCommand::summary() const
{
    return QStringLiteral(
        "Write a fitted model (MODEL.json from 'fit --out', or 'fit --json' for the seed-000 model) for a\n"
        "CNC controller: 840d, fanuc, heidenhain, linuxcnc, twincat, m80, c (portable C99), csv, json.\n"
        "Prints what it wrote, the notes (units, inputs) and the approximation error where the target\n"
        "cannot hold the model exactly; a model the target cannot express is refused with the reason\n"
        "(exit 2) and nothing is written. See docs/export.md.");
}

int ExportModelCommand::run(const QStringList &args)
{
    const ModelExport exporting;
    const ModelExporterRegistry &registry = exporting.registry();
    QCommandLineParser p;
    const QString targets = QString::fromStdString(registry.names());
    const QCommandLineOption target(QStringLiteral("target"), QStringLiteral("Format: %1.").arg(targets), QStringLiteral("name"));
    const QCommandLineOption out = CliOptions::out(
        QStringLiteral("Folder to write into: created if missing (its parent must exist), an existing one only with --force."),
        QStringLiteral("dir"));
    const QCommandLineOption axis(QStringLiteral("axis"), QStringLiteral("Axis letter (default X)."), QStringLiteral("X"),
                                  QStringLiteral("X"));
    const QCommandLineOption base(QStringLiteral("name"), QStringLiteral("Base name of the files (default driftlab_comp)."),
                                  QStringLiteral("name"), QStringLiteral("driftlab_comp"));
    const QCommandLineOption positions(QStringLiteral("positions"),
                                       QStringLiteral("Table positions, mm (default: the model's range)."),
                                       QStringLiteral("from:to:step"));
    const QCommandLineOption temperatures(QStringLiteral("temperatures"),
                                          QStringLiteral("Table temperatures, \u00b0C (default 15:40:1)."),
                                          QStringLiteral("from:to:step"), QStringLiteral("15:40:1"));
    const QCommandLineOption temperature(QStringLiteral("temperature"),
                                         QStringLiteral("Temperature of single-temperature files (linuxcnc, twincat "
                                                        "parameters), \u00b0C (default: middle of --temperatures)."),
                                         QStringLiteral("degC"));
    const QCommandLineOption first(QStringLiteral("first-variable"),
                                   QStringLiteral("First controller variable of the inputs (840d R, fanuc #, heidenhain W)."),
                                   QStringLiteral("n"));
    const QCommandLineOption json = CliOptions::json();
    const QCommandLineOption force = CliOptions::force();
    const QCommandLineOption list(QStringLiteral("list-targets"), QStringLiteral("List the targets and their sources."));
    p.addOptions({target, out, axis, base, positions, temperatures, temperature, first, json, force, list});
    p.addPositionalArgument(QStringLiteral("MODEL.json"), QStringLiteral("Fitted model."));
    if (!parse(p, args))
        return 0;
    QTextStream o(stdout);
    if (p.isSet(list)) {
        for (const auto &e : registry.exporters())
            o << QString::fromStdString(e->name()).leftJustified(12) << QString::fromStdString(e->description()) << "\n"
              << QString(12, QLatin1Char(' ')) << "source: " << QString::fromStdString(e->reference()) << '\n';
        return 0;
    }
    if (p.positionalArguments().size() != 1)
        throw UsageError(QStringLiteral("export-model: give exactly one MODEL.json"));
    if (!p.isSet(target))
        throw UsageError(QStringLiteral("export-model: --target is required (%1)").arg(targets));
    ModelExport::Request request{p.positionalArguments().front(), p.value(target), ExportOptions{}};
    const auto checked = [&] { // the use case's own request check: the same text as the dialog's
        try {
            exporting.check(request);
        } catch (const std::invalid_argument &e) {
            throw UsageError(QStringLiteral("export-model: %1").arg(QString::fromUtf8(e.what())));
        }
    };
    checked();
    if (!p.isSet(out))
        throw UsageError(QStringLiteral("export-model: --out DIR is required"));
    OutputTarget(p.value(out), QStringLiteral("--out"), OutputTarget::Kind::Folder).check(p.isSet(force));
    OutputTarget::checkJson(p, json, force);

    ExportOptions &options = request.options;
    options.axis = p.value(axis).toUpper().toStdString();
    options.baseName = p.value(base).toStdString();
    checked();
    if (p.isSet(positions))
        options.positions = range(p.value(positions), QStringLiteral("--positions"));
    options.temperatures = range(p.value(temperatures), QStringLiteral("--temperatures"));
    if (p.isSet(temperature))
        options.temperature = finite(p.value(temperature), QStringLiteral("--temperature"));
    if (p.isSet(first)) {
        bool ok = false;
        options.firstVariable = p.value(first).toInt(&ok);
        if (!ok || options.firstVariable < 0)
            throw UsageError(QStringLiteral("export-model: --first-variable must be an integer >= 0, got '%1'").arg(p.value(first)));
    }

    ModelExport::Result result;
    try {
        result = exporting.prepare(request);
    } catch (const std::invalid_argument &e) {
        throw UsageError(QStringLiteral("export-model: %1").arg(QString::fromUtf8(e.what())));
    } catch (const ExportRefused &e) {
        throw UsageError(QStringLiteral("export-model: %1 refused: %2").arg(request.modelPath, QString::fromUtf8(e.what())));
    }

    // Everything is in memory: say how much it is (refused above the bound without --force),
    // and only now touch the file system.
    const QString dir = p.value(out);
    OutputTarget(dir, QStringLiteral("--out"), OutputTarget::Kind::Folder).announceSize(result.bytes(), p.isSet(force));
    exporting.write(result, dir); // on failure it removes a folder it made: nothing is left
    const QJsonObject summary = ModelExport::summaryJson(result);
    if (p.isSet(json))
        CliSupport::writeJson(QJsonDocument(summary), p.value(json));
    if (!p.isSet(json) || p.value(json) != QLatin1String("-")) {
        o << result.kind << " -> " << result.target << ": " << result.paths.size() << " file(s) in " << dir
          << ", approximation error " << QString::number(result.exported.approximationError_um, 'g', 4) << QStringLiteral(" \u00b5m\n");
        for (const QString &f : result.paths)
            o << "  " << f << '\n';
        for (const std::string &n : result.exported.notes)
            o << "  note: " << QString::fromStdString(n) << '\n';
    }
    return 0;
}

} // namespace driftlab
