#include "PlotCommand.h"

#include "AnalysisPlots.h"
#include "CliSupport.h"
#include "CliOptions.h"
#include "OutputTarget.h"
#include "SessionArgument.h"
#include "InfraredPanel.h"
#include "PlotExporter.h"
#include "ReviewWorkspace.h"
#include "SessionStore.h"
#include "UnitLabels.h"

#include <QCommandLineParser>
#include <QFileInfo>

#include <qwt_interval.h>
#include <qwt_plot.h>

#include <cmath>

namespace driftlab {

QString PlotCommand::summary() const
{
    return QStringLiteral("Render a review view of a session to PNG, SVG or PDF (no display needed).\n"
                          "Views: %1.\n"
                          "--channels picks the channels of the timeseries view, --from/--to its time window (also\n"
                          "error-time), --target the interferometer target of error-temperature, --frame the\n"
                          "infrared frame of ir-profile.")
        .arg((ReviewWorkspace::viewNames() + AnalysisPlots::selectionViews()).join(QStringLiteral(", ")));
}

int PlotCommand::run(const QStringList &args)
{
    QCommandLineParser p;
    const QCommandLineOption db = CliOptions::db();
    const QCommandLineOption view(QStringLiteral("view"), QStringLiteral("View to render (default timeseries)."),
                                  QStringLiteral("name"), QStringLiteral("timeseries"));
    const QCommandLineOption out = CliOptions::out(QStringLiteral("Output file: .png, .svg or .pdf."));
    const QCommandLineOption force = CliOptions::force();
    const QCommandLineOption width(QStringLiteral("width-mm"), QStringLiteral("Width in mm (default 240)."),
                                   QStringLiteral("mm"), QStringLiteral("240"));
    const QCommandLineOption height(QStringLiteral("height-mm"), QStringLiteral("Height in mm (default 150)."),
                                    QStringLiteral("mm"), QStringLiteral("150"));
    const QCommandLineOption dpi(QStringLiteral("dpi"), QStringLiteral("Resolution (default 120)."), QStringLiteral("dpi"),
                                 QStringLiteral("120"));
    const QCommandLineOption channels(QStringLiteral("channels"), QStringLiteral("timeseries: channel ids, comma-separated."),
                                      QStringLiteral("ids"));
    const QCommandLineOption from(QStringLiteral("from"), QStringLiteral("Time window start: SECONDS, H:MM:SS or with a unit (90 min)."),
                                  QStringLiteral("time"));
    const QCommandLineOption to(QStringLiteral("to"), QStringLiteral("Time window end: SECONDS, H:MM:SS or with a unit (2 h)."), QStringLiteral("time"));
    const QCommandLineOption target(QStringLiteral("target"),
                                    QStringLiteral("error-temperature: interferometer target (mm; the nearest is used)."),
                                    QStringLiteral("mm"));
    const QCommandLineOption frame(QStringLiteral("frame"), QStringLiteral("ir-profile: infrared frame number (1 = first)."),
                                   QStringLiteral("n"));
    p.addOptions({db, view, out, force, width, height, dpi, channels, from, to, target, frame});
    p.addPositionalArgument(QStringLiteral("SESSION"), QStringLiteral("Session id."));
    if (!parse(p, args))
        return 0;
    if (p.positionalArguments().size() != 1)
        throw UsageError(QStringLiteral("plot: give exactly one session id"));
    bool ok = false;
    SessionArgument::checkForm(p.positionalArguments().first(), QStringLiteral("SESSION"), name());
    if (!p.isSet(out))
        throw UsageError(QStringLiteral("plot: --out FILE is required"));
    const QString file = p.value(out);
    OutputTarget output(file, QStringLiteral("--out"));
    output.formats({QStringLiteral("png"), QStringLiteral("svg"), QStringLiteral("pdf")}).check(p.isSet(force));
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
    // A PNG is drawn whole in memory (4 bytes a pixel): its size is an output size too.
    if (output.format() == QLatin1String("png")) {
        const double pixels = size.width() / 25.4 * resolution * (size.height() / 25.4 * resolution);
        if (pixels * 4 > OutputTarget::kSizeBound && !p.isSet(force))
            throw UsageError(QStringLiteral("plot: --out %1: %2 x %3 mm at %4 dpi is %5 million pixels, %6 to draw, more than %7 "
                                            "(use --force to draw it, or a smaller --dpi, or .svg/.pdf)")
                                 .arg(file)
                                 .arg(size.width())
                                 .arg(size.height())
                                 .arg(resolution)
                                 .arg(pixels / 1e6, 0, 'f', 0)
                                 .arg(OutputTarget::sizeText(static_cast<qint64>(pixels * 4)), OutputTarget::sizeText(OutputTarget::kSizeBound)));
    }
    const double t0 = p.isSet(from) ? CliSupport::parseDuration(p.value(from), QStringLiteral("from")) : -1.0;
    const double t1 = p.isSet(to) ? CliSupport::parseDuration(p.value(to), QStringLiteral("to")) : -1.0;
    if (t0 >= 0 && t1 >= 0 && t1 <= t0)
        throw UsageError(QStringLiteral("plot: --to must be after --from"));
    if ((p.isSet(from) || p.isSet(to)) && name != QLatin1String("timeseries") && name != QLatin1String("error-time"))
        throw UsageError(QStringLiteral("plot: --from/--to apply to the timeseries and error-time views"));
    if (p.isSet(channels) && name != QLatin1String("timeseries"))
        throw UsageError(QStringLiteral("plot: --channels applies to the timeseries view"));
    if (p.isSet(target) && name != QLatin1String("error-temperature"))
        throw UsageError(QStringLiteral("plot: --target applies to the error-temperature view"));
    if (p.isSet(frame) && name != QLatin1String("ir-profile"))
        throw UsageError(QStringLiteral("plot: --frame applies to the ir-profile view"));

    const QString path = CliSupport::databasePath(p.value(db), QString(), true);
    SessionStore store(path);
    const qint64 session = SessionArgument::one(store, p.positionalArguments().first(), QStringLiteral("SESSION"), QStringLiteral("plot"));
    const double end = CliSupport::sessionEnd_s(store, session);
    if (t0 >= 0 && std::isfinite(end) && t0 >= end)
        throw UsageError(QStringLiteral("plot: --from %1 (%2 s) is at or after the end of session %3 at %4 (%5 s): nothing to draw")
                             .arg(p.value(from))
                             .arg(t0, 0, 'f', 0)
                             .arg(session)
                             .arg(UnitLabels::clock(end))
                             .arg(end, 0, 'f', 0));
    if (selectionView) { // the latest select-points result stored with the session
        std::unique_ptr<QwtPlot> plot;
        try {
            plot = AnalysisPlots::selectionPlot(name, AnalysisPlots::storedSelection(store, session), &store, session);
        } catch (const std::invalid_argument &e) {
            throw UsageError(QStringLiteral("plot: %1").arg(QString::fromUtf8(e.what())));
        }
        plot->resize(1600, 1000);
        // Drawn in memory, then written atomically: a failure leaves no partial file.
        OutputTarget::writeFile(file, PlotExporter::render(*plot, output.format(), size, resolution));
        CliSupport::progress(QStringLiteral("wrote %1 (%2 of session %3)").arg(QFileInfo(file).absoluteFilePath(), name).arg(session));
        return 0;
    }
    ReviewWorkspace workspace;
    workspace.resize(1600, 1000);
    workspace.setSession(&store, session);
    if (p.isSet(channels)) {
        QVector<qint64> ids;
        QStringList known;
        const QVector<ChannelInfo> all = store.channels(session);
        for (const ChannelInfo &c : all)
            known << c.key;
        for (const QString &key : p.value(channels).split(QLatin1Char(','), Qt::SkipEmptyParts)) {
            const int i = known.indexOf(key.trimmed());
            if (i < 0)
                throw UsageError(QStringLiteral("plot: --channels: session %1 has no channel '%2' (it has %3)")
                                     .arg(session)
                                     .arg(key, known.join(QStringLiteral(", "))));
            ids.push_back(all[i].id);
        }
        workspace.showChannels(ids);
    }
    if (p.isSet(target)) {
        bool good = false;
        const double mm = p.value(target).toDouble(&good);
        if (!good)
            throw UsageError(QStringLiteral("plot: --target must be a position in mm, got '%1'").arg(p.value(target)));
        workspace.selectTarget(mm);
    }
    QwtPlot *plot = workspace.plotForView(name);
    if (!plot)
        throw UsageError(QStringLiteral("plot: session %1 has no data for the view '%2'").arg(session).arg(name));
    if (p.isSet(frame)) {
        const int n = p.value(frame).toInt(&ok);
        if (!ok || n < 1 || n > workspace.infraredPanel()->frameCount())
            throw UsageError(QStringLiteral("plot: --frame must be 1..%1, got '%2'")
                                 .arg(workspace.infraredPanel()->frameCount())
                                 .arg(p.value(frame)));
        workspace.infraredPanel()->showFrame(n - 1);
    }
    if (t0 >= 0 || t1 >= 0) {
        const QwtInterval shown = plot->axisInterval(QwtPlot::xBottom);
        plot->setAxisScale(QwtPlot::xBottom, t0 >= 0 ? t0 : shown.minValue(), t1 >= 0 ? t1 : shown.maxValue());
        plot->replot();
    }
    OutputTarget::writeFile(file, PlotExporter::render(*plot, output.format(), size, resolution));
    CliSupport::progress(QStringLiteral("wrote %1 (%2 of session %3)").arg(QFileInfo(file).absoluteFilePath(), name).arg(session));
    return 0;
}

} // namespace driftlab
