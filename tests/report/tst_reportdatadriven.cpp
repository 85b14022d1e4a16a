// Issue 32 item 3 (report side): the data-driven section of a report warns, in the words of
// the CLI and the GUI (ExtrapolationWarning), when the stored fit's held-out inputs left the
// training range by more than the margin, and shows the comparison table `auto` chose from.

#include "DataDrivenFit.h"
#include "DataDrivenFitRecord.h"
#include "ExtrapolationWarning.h"
#include "ReportBuilder.h"
#include "ReportTemplate.h"
#include "RigRecorder.h"
#include "SessionStore.h"
#include "SimulatedRig.h"

#include <QRegularExpression>
#include <QTemporaryDir>
#include <QtTest>

using namespace driftlab;

class TestReportDataDriven : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void warnsOfExtrapolation();
    void showsTheAutoTable();

private:
    QString text(qint64 session) const;

    QTemporaryDir m_dir;
    std::unique_ptr<SessionStore> m_store;
};

void TestReportDataDriven::initTestCase()
{
    m_store = std::make_unique<SessionStore>(m_dir.filePath(QStringLiteral("report.sqlite")));
    // Session 1 at 20 C, session 2 at 26 C: absolute temperatures of 2 leave 1's range.
    for (double ambient : {20.0, 26.0}) {
        RigConfig c;
        c.thermal.ambientMean_C = ambient;
        c.program = FeedProgram::seed000Table2(6000.0, c.travelLow_mm, c.travelHigh_mm);
        SimulatedRig rig(c);
        QVERIFY(RigRecorder(*m_store, rig).record(QStringLiteral("at %1 C").arg(ambient), 3600.0) > 0);
    }
}

QString TestReportDataDriven::text(qint64 session) const
{
    const ReportDocument doc = ReportBuilder(*m_store, session, ReportTemplate::load()).build();
    QString all;
    for (const ReportBlock &b : doc.blocks)
        all += b.text + QLatin1Char('\n');
    return all;
}

void TestReportDataDriven::warnsOfExtrapolation()
{
    DataDrivenFitRequest q;
    q.session = 1;
    q.model = QStringLiteral("ridge");
    q.target = QStringLiteral("S1");
    q.reference = QStringLiteral("absolute");
    q.holdoutSession = 2;
    const DataDrivenFitResult r = DataDrivenFit(*m_store).fit(q);
    QVERIFY(!r.holdoutSessions.front().extrapolated.isEmpty());
    QVERIFY(!text(1).contains(QStringLiteral("extrapolation:"))); // nothing stored yet
    DataDrivenFitRecord::store(*m_store, r, r.document, DataDrivenFitRecord::Face::Gui);
    const QString report = text(1);
    const ValidationSeries &h = r.holdoutSessions.front();
    for (int i = 0; i < h.extrapolated.size(); ++i) {
        const QString line = ExtrapolationWarning::text(QStringLiteral("held-out session 2"), h.extrapolated[i],
                                                        h.extrapolatedFraction[static_cast<std::size_t>(i)]);
        QVERIFY2(report.contains(QStringLiteral("<b>Warning:</b> ") + line.toHtmlEscaped()), qPrintable(line));
    }
}

void TestReportDataDriven::showsTheAutoTable()
{
    DataDrivenFitRequest q;
    q.session = 1;
    q.model = QStringLiteral("auto");
    q.target = QStringLiteral("S1");
    q.holdoutSession = 2;
    const DataDrivenFitResult r = DataDrivenFit(*m_store).fit(q);
    QVERIFY(!r.comparison.empty());
    DataDrivenFitRecord::store(*m_store, r, r.document, DataDrivenFitRecord::Face::Gui);
    const QString report = text(1);
    QVERIFY(report.contains(QStringLiteral("Chosen by fit --model auto")));
    QVERIFY(report.contains(QStringLiteral("never used to choose")));
    QCOMPARE(report.count(QStringLiteral("<td>chosen</td>")), 1);
    for (const FamilyComparison &c : r.comparison) {
        const QString name = c.model + (c.plainReference ? QStringLiteral(" (ref)") : QString());
        QVERIFY2(report.contains(QStringLiteral("<tr><td>%1</td>").arg(name)), qPrintable(name));
        if (c.chosen) // the chosen family's row ends with "chosen"
            QVERIFY(report.contains(QRegularExpression(QStringLiteral("<tr><td>%1</td>(<td>[^<]*</td>){6}<td>chosen</td></tr>")
                                                           .arg(QRegularExpression::escape(name)))));
    }
}

QTEST_MAIN(TestReportDataDriven)
#include "tst_reportdatadriven.moc"
