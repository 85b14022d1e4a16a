#include "ReportIso230Section.h"

#include "Iso230View.h"
#include "ReportBuilder.h"
#include "ReportTemplate.h"
#include "SessionIso230.h"
#include "TimeSeriesPlot.h"

#include <QSet>
#include <QStringList>

namespace driftlab {

namespace {

constexpr auto num = &ReportDocument::number;
constexpr auto elapsed = &ReportDocument::elapsed;
constexpr auto svg = &ReportBuilder::svg;
constexpr QSizeF kFigure_mm = ReportBuilder::kFigure_mm;

} // namespace

void ReportIso230Section::write(ReportDocument &doc, const SessionStore &store, qint64 session, const ReportTemplate &look)
{
    doc.heading(look.heading(QStringLiteral("iso230")));
    // The result `iso230` or the ISO 230 view stored with the session; without one (or with
    // one this version cannot read), evaluated here with the default request.
    std::optional<Iso230Report> iso;
    try {
        iso = SessionIso230::stored(store, session);
    } catch (const std::invalid_argument &e) {
        doc.leftOut(QStringLiteral("the stored ISO 230 result was not used: %1").arg(QString::fromUtf8(e.what())));
    }
    const bool stored = iso.has_value();
    if (!stored) {
        try {
            Iso230Request request;
            request.session = session;
            iso = SessionIso230(store, request).run();
        } catch (const std::invalid_argument &e) {
            doc.leftOut(QString::fromUtf8(e.what()));
            return;
        }
    }
    const Iso230Request &request = iso->request();
    doc.paragraph(QStringLiteral("%1: %2 run(s) per test, targets within %3 mm, drift %4.")
                      .arg(stored ? QStringLiteral("The result stored with the session") : QStringLiteral("Evaluated for this report (none stored)"))
                      .arg(request.runsPerTest)
                      .arg(request.targetTolerance_mm)
                      .arg(request.temperatureChannel.isEmpty() ? QStringLiteral("without a temperature channel")
                                                                : QStringLiteral("against %1").arg(request.temperatureChannel)));
    QVector<QStringList> rows;
    QSet<QString> notes;
    for (const Iso230Test &t : iso->tests()) {
        QStringList runs;
        for (int r : t.runs)
            runs << QString::number(r);
        // One direction (or none recorded): the values of that direction, as Iso230Report::text.
        const Iso230Axis &a = t.axis;
        const bool both = t.bidirectional;
        rows.push_back({runs.join(QLatin1Char(',')), elapsed(t.time_s), QString::number(t.targets.size()),
                        both ? QStringLiteral("both") : t.directionRecorded ? QStringLiteral("one") : QStringLiteral("not recorded"),
                        QString::number(t.minApproaches), num(both ? a.accuracy_um : a.accuracyUp_um, 4),
                        num(both ? a.systematic_um : a.systematicUp_um, 4), num(a.meanRange_um, 4),
                        num(both ? a.repeat_um : a.repeatUp_um, 4), num(a.reversal_um, 4)});
        for (const std::string &n : t.notes)
            notes.insert(QString::fromStdString(n));
    }
    doc.paragraph(QStringLiteral("ISO 230-2 axis values per interferometer test, in \u00b5m: A accuracy, E systematic "
                                 "positioning error, M range of the mean positional deviation, R repeatability, "
                                 "B reversal value; n = fewest approaches per target and direction."));
    doc.table({QStringLiteral("Runs"), QStringLiteral("Time (h:mm:ss)"), QStringLiteral("Targets"), QStringLiteral("Directions"),
               QStringLiteral("n"), QStringLiteral("A"), QStringLiteral("E"), QStringLiteral("M"), QStringLiteral("R"), QStringLiteral("B")},
              rows);
    QStringList sorted = notes.values();
    sorted.sort();
    for (const QString &n : sorted)
        doc.paragraph(QStringLiteral("Note: %1").arg(n));

    // The reference test per target and direction, and the plots of the ISO 230 view (the
    // same Iso230Report numbers the view and `iso230 --json` show).
    const int reference = iso->referenceTest();
    if (!iso->tests().empty()) {
        const Iso230Test &ref = iso->tests()[static_cast<std::size_t>(reference)];
        QVector<QStringList> targets;
        for (const Iso230Target &t : ref.targets)
            targets.push_back({num(t.position_mm, 6), QString::number(t.approachesUp), QString::number(t.approachesDown),
                               num(t.meanUp_um, 4), num(t.meanDown_um, 4), num(t.reversal_um, 4), num(t.repeatUp_um, 4),
                               num(t.repeatDown_um, 4), num(t.repeat_um, 4)});
        doc.paragraph(QStringLiteral("ISO 230-2 per target and direction of the reference test (run %1), in \u00b5m: "
                                     "mean positional deviation x up and down, reversal B, repeatability R up, down and "
                                     "bidirectional.")
                          .arg(iso->referenceRun()));
        doc.table({QStringLiteral("Target (mm)"), QStringLiteral("n up"), QStringLiteral("n down"), QStringLiteral("x up"),
                   QStringLiteral("x down"), QStringLiteral("B"), QStringLiteral("R up"), QStringLiteral("R down"),
                   QStringLiteral("R")},
                  targets);
        Iso230View view;
        view.resize(1100, 700);
        view.showReport(*iso);
        view.showTest(reference);
        doc.figure(QStringLiteral("ISO 230-2 positional deviation of the reference test (session %1)").arg(session),
                   svg(*view.positioningPlot(), kFigure_mm), kFigure_mm);
        if (iso->tests().size() >= 2)
            doc.figure(QStringLiteral("ISO 230-3 drift against the reference run (session %1)").arg(session),
                       svg(*view.driftPlot(), kFigure_mm), kFigure_mm);
    }
    const Iso230DriftSummary &d = iso->drift();
    if (iso->tests().size() < 2) {
        doc.leftOut(QStringLiteral("ISO 230-3 drift: the session has a single positioning test, so there is no drift"));
        return;
    }
    doc.paragraph(QStringLiteral("ISO 230-3 drift against the reference run %1: largest drift %2 \u00b5m at %3 mm (%4) in run %5, "
                                 "%6 (h:mm:ss) after the start.")
                      .arg(d.referenceRun)
                      .arg(num(d.maxDrift_um, 4), num(d.maxDriftPosition_mm, 6),
                           d.maxDriftDirection > 0 ? QStringLiteral("+") : d.maxDriftDirection < 0 ? QStringLiteral("-") : QStringLiteral("no direction"))
                      .arg(d.maxDriftRun)
                      .arg(elapsed(d.maxDriftTime_s)));
    QVector<QStringList> drift;
    for (const Iso230DriftSeries &s : d.series)
        drift.push_back({num(s.position_mm, 6), s.direction > 0 ? QStringLiteral("+") : s.direction < 0 ? QStringLiteral("-") : QStringLiteral("?"),
                         num(s.maxDrift_um, 4), elapsed(s.maxDriftTime_s), QString::number(s.maxDriftRun)});
    doc.table({QStringLiteral("Target (mm)"), QStringLiteral("Direction"), QStringLiteral("Largest drift (\u00b5m)"),
               QStringLiteral("At (h:mm:ss)"), QStringLiteral("Run")},
              drift);
}

} // namespace driftlab
