#include "ReportCommand.h"

#include "CliSupport.h"
#include "CliOptions.h"
#include "OutputTarget.h"
#include "SessionArgument.h"
#include "ReportBuilder.h"
#include "ReportTemplate.h"
#include "ReportWriter.h"
#include "SessionStore.h"

#include <QBuffer>
#include <QCommandLineParser>
#include <QElapsedTimer>
#include <QFileInfo>

namespace driftlab {

QString ReportCommand::summary() const
{
    return QStringLiteral("Test report of a session as PDF or HTML (same content): metadata and sensors, the error and\n"
                          "temperature figures, ISO 230-2/230-3 values, sensitive points, fitted models, diagnosis and\n"
                          "compensation; sections without data are left out with one line saying why. --template DIR:\n"
                          "a folder with template.json (lab_name, title, language, logo, headings; docs/report.md).");
}

int ReportCommand::run(const QStringList &args)
{
    QCommandLineParser p;
    const QCommandLineOption db = CliOptions::db();
    const QCommandLineOption out = CliOptions::out(QStringLiteral("Output file: .pdf or .html."));
    const QCommandLineOption force = CliOptions::force();
    const QCommandLineOption look(QStringLiteral("template"), QStringLiteral("Template folder (default: the built-in one)."),
                                  QStringLiteral("dir"));
    p.addOptions({db, out, force, look});
    p.addPositionalArgument(QStringLiteral("SESSION"), QStringLiteral("Session id."));
    if (!parse(p, args))
        return 0;
    if (p.positionalArguments().size() != 1)
        throw UsageError(QStringLiteral("report: give exactly one session id"));
    SessionArgument::checkForm(p.positionalArguments().first(), QStringLiteral("SESSION"), name());
    if (!p.isSet(out))
        throw UsageError(QStringLiteral("report: --out FILE.pdf|FILE.html is required"));
    const QString file = p.value(out);
    OutputTarget target(file, QStringLiteral("--out"));
    target.formats({QStringLiteral("pdf"), QStringLiteral("html"), QStringLiteral("htm")}, {QStringLiteral("pdf"), QStringLiteral("html")}).check(p.isSet(force));
    ReportTemplate tmpl;
    try {
        tmpl = ReportTemplate::load(p.value(look));
    } catch (const std::invalid_argument &e) {
        throw UsageError(QStringLiteral("report: --template: %1").arg(QString::fromUtf8(e.what())));
    }
    const QString path = CliSupport::databasePath(p.value(db), QString(), true);
    SessionStore store(path);
    const qint64 session = SessionArgument::one(store, p.positionalArguments().first(), QStringLiteral("SESSION"), name());
    QElapsedTimer timer;
    timer.start();
    const ReportDocument doc = ReportBuilder(store, session, tmpl).build([](const QString &stage) {
        CliSupport::progress(QStringLiteral("report: %1...").arg(stage));
    });
    // Made in memory, then written (and announced when large) like every output.
    const ReportWriter writer(doc, tmpl);
    QByteArray bytes;
    if (target.format() == QLatin1String("pdf")) {
        QBuffer buffer(&bytes);
        buffer.open(QIODevice::WriteOnly);
        writer.writePdf(&buffer);
    } else {
        bytes = writer.html();
    }
    OutputTarget::writeFile(file, bytes);
    CliSupport::progress(QStringLiteral("wrote %1 (report of session %2) in %3 s")
                             .arg(QFileInfo(file).absoluteFilePath())
                             .arg(session)
                             .arg(timer.elapsed() / 1000.0, 0, 'f', 2));
    return 0;
}

} // namespace driftlab
