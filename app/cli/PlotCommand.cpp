#include "PlotCommand.h"

#include "AnalysisPlots.h"
#include "CliSupport.h"
#include "PlotExporter.h"
#include "ReviewWorkspace.h"
#include "SessionStore.h"

#include <QCommandLineParser>
#include <QFileInfo>

#include <qwt_plot.h>

namespace driftlab {

QString PlotCommand::summary() const
{
    return QStringLiteral("Render a review view of a session to PNG, SVG or PDF (no display needed).\n"
                          "Views: %1.")
        .arg((ReviewWorkspace::viewNames() + AnalysisPlots::selectionViews()).join(QStringLiteral(", ")));
}

int PlotCommand::run(const QStringList &args)
{
    QCommandLineParser p;
    const QCommandLineOption db(QStringLiteral("db"), QStringLiteral("Session database."), QStringLiteral("file"));
    const QCommandLineOption view(QStringLiteral("view"), QStringLiteral("View to render (default timeseries)."),
                                  QStringLiteral("name"), QStringLiteral("timeseries"));
    const QCommandLineOption out(QStringLiteral("out"), QStringLiteral("Output file: .png, .svg or .pdf."),
                                 QStringLiteral("file"));
    const QCommandLineOption width(QStringLiteral("width-mm"), QStringLiteral("Width in mm (default 240)."),
                                   QStringLiteral("mm"), QStringLiteral("240"));
    const QCommandLineOption height(QStringLiteral("height-mm"), QStringLiteral("Height in mm (default 150)."),
                                    QStringLiteral("mm"), QStringLiteral("150"));
    const QCommandLineOption dpi(QStringLiteral("dpi"), QStringLiteral("Resolution (default 120)."), QStringLiteral("dpi"),
                                 QStringLiteral("120"));
    p.addOptions({db, view, out, width, height, dpi});
    p.addPositionalArgument(QStringLiteral("SESSION"), QStringLiteral("Session id."));
    if (!parse(p, args))
        return 0;
    if (p.positionalArguments().size() != 1)
        throw UsageError(QStringLiteral("plot: give exactly one session id"));
    bool ok = false;
    const qint64 session = p.positionalArguments().first().toLongLong(&ok);
    if (!ok)
        throw UsageError(QStringLiteral("plot: '%1' is not a session id").arg(p.positionalArguments().first()));
    if (!p.isSet(out))
        throw UsageError(QStringLiteral("plot: --out FILE is required"));
    const QString file = p.value(out);
    if (!PlotExporter::supportedSuffix(file))
        throw UsageError(QStringLiteral("plot: --out %1: use a .png, .svg or .pdf file").arg(file));
    const QString name = p.value(view);
    const bool selectionView = AnalysisPlots::selectionViews().contains(name);
    if (!selectionView && !ReviewWorkspace::viewNames().contains(name))
        throw UsageError(QStringLiteral("plot: --view '%1' is not a view; choose one of %2")
                             .arg(name, (ReviewWorkspace::viewNames() + AnalysisPlots::selectionViews()).join(QStringLiteral(", "))));
    auto number = [&](const QCommandLineOption &o, double lo, double hi) {
        bool good = false;
        const double v = p.value(o).toDouble(&good);
        if (!good || v < lo || v > hi)
            throw UsageError(QStringLiteral("plot: --%1 must be a number in [%2, %3], got '%4'")
                                 .arg(o.names().first())
                                 .arg(lo)
                                 .arg(hi)
                                 .arg(p.value(o)));
        return v;
    };
    const QSizeF size(number(width, 20, 2000), number(height, 20, 2000));
    const int resolution = static_cast<int>(number(dpi, 30, 1200));

    const QString path = CliSupport::databasePath(p.value(db), QString(), true);
    SessionStore store(path);
    bool found = false;
    for (const SessionInfo &s : store.sessions())
        found = found || s.id == session;
    if (!found)
        throw UsageError(QStringLiteral("plot: %1 has no session %2").arg(path).arg(session));
    if (selectionView) { // the latest select-points result stored with the session
        std::unique_ptr<QwtPlot> plot;
        try {
            plot = AnalysisPlots::selectionPlot(name, AnalysisPlots::storedSelection(store, session), &store, session);
        } catch (const std::invalid_argument &e) {
            throw UsageError(QStringLiteral("plot: %1").arg(QString::fromUtf8(e.what())));
        }
        plot->resize(1600, 1000);
        PlotExporter::exportPlot(*plot, file, size, resolution);
        CliSupport::progress(QStringLiteral("wrote %1 (%2 of session %3)").arg(QFileInfo(file).absoluteFilePath(), name).arg(session));
        return 0;
    }
    ReviewWorkspace workspace;
    workspace.resize(1600, 1000);
    workspace.setSession(&store, session);
    QwtPlot *plot = workspace.plotForView(name);
    if (!plot)
        throw UsageError(QStringLiteral("plot: session %1 has no data for the view '%2'").arg(session).arg(name));
    PlotExporter::exportPlot(*plot, file, size, resolution);
    CliSupport::progress(QStringLiteral("wrote %1 (%2 of session %3)").arg(QFileInfo(file).absoluteFilePath(), name).arg(session));
    return 0;
}

} // namespace driftlab
