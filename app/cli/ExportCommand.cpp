#include "ExportCommand.h"

#include "BundleError.h"
#include "BundleTransfer.h"
#include "CliOptions.h"
#include "CliSupport.h"
#include "OutputTarget.h"
#include "SessionArgument.h"
#include "SessionStore.h"

#include <QCommandLineParser>
#include <QFileInfo>
#include <QJsonObject>
#include <QTextStream>

namespace driftlab {

QString ExportCommand::summary() const
{
    return QStringLiteral("Export a session as a recording bundle: OUT ending in .zip gives a zip, NAME.bundle or a\n"
                          "name without extension a directory; other extensions are refused. OUT must not exist and\n"
                          "its folder must.");
}

int ExportCommand::run(const QStringList &args)
{
    QCommandLineParser p;
    const auto [db, json, force] = CliOptions::dbJsonForce(p);
    p.addPositionalArgument(QStringLiteral("SESSION"), QStringLiteral("Session id (see 'driftlab-cli list')."));
    p.addPositionalArgument(QStringLiteral("OUT"), QStringLiteral("Output NAME.bundle directory or NAME.zip."));
    if (!parse(p, args))
        return 0;
    if (p.positionalArguments().size() != 2)
        throw UsageError(QStringLiteral("export: expected SESSION and OUT, got %1 arguments").arg(p.positionalArguments().size()));
    SessionArgument::checkForm(p.positionalArguments().at(0), QStringLiteral("SESSION"), name());
    const QString out = p.positionalArguments().at(1);
    // A bundle is never replaced (not even with --force): the exported copy is a record.
    OutputTarget target(out, QStringLiteral("OUT"), QFileInfo(out).suffix().isEmpty() ? OutputTarget::Kind::Folder : OutputTarget::Kind::File);
    if (!QFileInfo(out).suffix().isEmpty())
        target.formats({QStringLiteral("zip"), QStringLiteral("bundle")});
    target.neverReplaced().check(false);
    OutputTarget::checkJson(p, json, force);
    const QString path = CliSupport::databasePath(p.value(db), QString(), true);
    SessionStore store(path);
    const qint64 id = SessionArgument::one(store, p.positionalArguments().at(0), QStringLiteral("SESSION"), name());
    CliSupport::progress(QStringLiteral("exporting session %1 of %2 to %3").arg(id).arg(path, out));
    // Announced like every large output: about 17.5 bytes of channels.csv a sample and 0.85 of
    // PNG a frame pixel (a simulated 4 h session: 6.7 MB for 388 k samples, 8.6 kB per 256 x 40
    // frame); a zip holds about a quarter of that for such data, more for noisy data.
    double estimate = 0.0;
    for (const SessionSummary &s : store.sessionSummaries())
        if (s.id == id)
            estimate += 17.5 * static_cast<double>(s.samples);
    for (const IrFrame &f : store.irFrames(id))
        estimate += 0.85 * f.width * f.height;
    OutputTarget::announce(out, static_cast<qint64>(estimate), target.format() == QLatin1String("zip") ? QStringLiteral("before compression") : QString());
    BundleTransfer::exportBundle(store, id, out);
    if (p.isSet(json))
        CliSupport::writeJson(QJsonDocument(QJsonObject{{QStringLiteral("database"), path},
                                                        {QStringLiteral("session"), static_cast<double>(id)},
                                                        {QStringLiteral("bundle"), out}}),
                              p.value(json));
    else
        QTextStream(stdout) << "session " << id << " -> " << out << '\n';
    return 0;
}

} // namespace driftlab
