// The CSV import dialog as a user drives it: a ';'/decimal-comma logger file is read with
// the dialect and kinds guessed, an assignment is changed, the import runs on its worker
// thread into the database; the same header later brings the changed assignment back; the map
// saves as JSON the CLI reads; a bad row names its line and column and imports nothing; a
// cancelled import leaves nothing; File > Import CSV table exists.

#include "CsvColumnMap.h"
#include "CsvImportDialog.h"
#include "CsvMapGuesser.h"
#include "MainWindow.h"
#include "SessionStore.h"

#include "../support/TestFiles.h"

#include <QAction>
#include <QComboBox>
#include <QDateTimeEdit>
#include <QHeaderView>
#include <QJsonDocument>
#include <QLineEdit>
#include <QSettings>
#include <QSignalSpy>
#include <QSpinBox>
#include <QTableWidget>
#include <QTemporaryDir>
#include "../support/GrabForDocs.h"

#include <QtTest>

#include <algorithm>

using namespace driftlab;

class TestCsvImportDialog : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void guessesAssignsImportsAndRemembers();
    void savedMapIsTheCliMap();
    void badRowNamesLineAndColumn();
    void cancelLeavesNothing();
    void mainWindowHasTheAction();
    void loggerFilesGuessedRight_data();
    void loggerFilesGuessedRight();
    void fixingTheFormatKeepsColumnsTicked();
    void loadingAMapClearsTheError();
    void intervalClockAndRunColumn();
    void reguessAfterAFormatFixReadsWhatTheCliReads();

private:
    QString write(const QString &name, const QByteArray &bytes);
    int row(CsvImportDialog &d, const QString &header);
    static int ticked(CsvImportDialog &d);
    QTemporaryDir m_dir;
    QString m_db;
};

QString TestCsvImportDialog::write(const QString &name, const QByteArray &bytes)
{
    return testfiles::write(m_dir.path(), name, bytes);
}

int TestCsvImportDialog::row(CsvImportDialog &d, const QString &header)
{
    for (int r = 0; r < d.columnTable()->rowCount(); ++r) {
        if (d.columnTable()->item(r, 1)->text() == header)
            return r;
    }
    return -1;
}

int TestCsvImportDialog::ticked(CsvImportDialog &d)
{
    int n = 0;
    for (int r = 0; r < d.columnTable()->rowCount(); ++r)
        n += d.columnTable()->item(r, 0)->checkState() == Qt::Checked ? 1 : 0;
    return n;
}

void TestCsvImportDialog::initTestCase()
{
    QVERIFY(m_dir.isValid());
    QSettings::setPath(QSettings::NativeFormat, QSettings::UserScope, m_dir.filePath(QStringLiteral("settings")));
    QCoreApplication::setOrganizationName(QStringLiteral("DriftLabTest"));
    QCoreApplication::setApplicationName(QStringLiteral("tst_csvimportdialog"));
    QSettings().clear();
    m_db = m_dir.filePath(QStringLiteral("dialog.sqlite"));
    SessionStore create(m_db);
}

void TestCsvImportDialog::guessesAssignsImportsAndRemembers()
{
    const QByteArray text = "\xEF\xBB\xBFZeit [s];T_amb (K);Mutter [\xC2\xB0" "C];X-Sonde [mm];spindle_rpm\r\n"
                            "0;293,15;20,0;0,001;0\r\n"
                            "60;293,65;21,5;0,004;1500\r\n";
    const QString file = write(QStringLiteral("logger.csv"), text);
    {
        CsvImportDialog d(m_db);
        QVERIFY(d.openFile(file));
        CsvColumnMap m = d.columnMap();
        QCOMPARE(m.separator, ';');
        QCOMPARE(m.decimal, ',');
        QCOMPARE(m.time.column, QStringLiteral("Zeit [s]"));
        QCOMPARE(m.time.unit, QStringLiteral("s"));
        QCOMPARE(d.preview()->rowCount(), 2);
        QCOMPARE(d.preview()->item(1, 2)->text(), QStringLiteral("21,5"));
        QCOMPARE(m.columns.size(), 4);
        QCOMPARE(m.columns[0].id, QStringLiteral("T_amb"));
        QCOMPARE(m.columns[0].kind, QStringLiteral("temperature"));
        QCOMPARE(m.columns[0].unit, QStringLiteral("K"));
        QCOMPARE(m.columns[0].role, QStringLiteral("ambient"));
        QCOMPARE(m.columns[2].kind, QStringLiteral("displacement"));
        QCOMPARE(m.columns[2].unit, QStringLiteral("mm"));
        QVERIFY(m.columns[2].target);
        QCOMPARE(m.columns[3].role, QStringLiteral("spindle"));
        // The user: the nut sensor is called T4, and the spindle speed is not wanted.
        const int nut = row(d, QStringLiteral("Mutter [\u00b0C]"));
        QVERIFY(nut >= 0);
        d.columnTable()->item(nut, 2)->setText(QStringLiteral("T4"));
        qobject_cast<QComboBox *>(d.columnTable()->cellWidget(nut, 5))->setCurrentText(QStringLiteral("nut"));
        d.columnTable()->item(row(d, QStringLiteral("spindle_rpm")), 0)->setCheckState(Qt::Unchecked);
        QSignalSpy imported(&d, &CsvImportDialog::imported);
        QSignalSpy finished(&d, &CsvImportDialog::importFinished);
        d.startImport();
        QVERIFY(d.isImporting());
        QVERIFY(finished.wait(20000));
        QCOMPARE(finished.front().front().toBool(), true);
        QCOMPARE(imported.size(), 1);
        SessionStore store(m_db);
        const qint64 id = imported.front().front().toLongLong();
        const QVector<ChannelInfo> ch = store.channels(id);
        QCOMPARE(ch.size(), 3);
        QCOMPARE(ch[1].key, QStringLiteral("T4"));
        QCOMPARE(ch[1].role, QStringLiteral("nut"));
        QCOMPARE(store.samples(ch[1].id).v, (QVector<double>{20.0, 21.5}));
        QVERIFY(std::fabs(store.samples(ch[0].id).v[1] - 20.5) < 1e-9); // 293.65 K
        QVERIFY(std::fabs(store.samples(ch[2].id).v[1] - 4.0) < 1e-9);  // 0.004 mm in um
        QCOMPARE(store.session(id).name, QStringLiteral("logger"));
    }
    // Another file with the same header: the changed assignment comes back.
    const QString second = write(QStringLiteral("logger2.csv"), text);
    CsvImportDialog d(m_db);
    QVERIFY(d.openFile(second));
    const CsvColumnMap m = d.columnMap();
    QCOMPARE(m.columns.size(), 3);
    QCOMPARE(m.columns[1].id, QStringLiteral("T4"));
    QCOMPARE(m.columns[1].role, QStringLiteral("nut"));
    QVERIFY(d.columnTable()->item(row(d, QStringLiteral("spindle_rpm")), 0)->checkState() == Qt::Unchecked);
}

void TestCsvImportDialog::savedMapIsTheCliMap()
{
    const QString file = write(QStringLiteral("plain.csv"), "time_s,t1_C,ch1_um,spindle_rpm\n0,20,0,0\n15,20.5,1.5,1250\n");
    CsvImportDialog d(m_db);
    QVERIFY(d.openFile(file));
    const QString json = m_dir.filePath(QStringLiteral("plain.json"));
    QVERIFY(d.saveMap(json));
    const CsvColumnMap loaded = CsvColumnMap::load(json);
    QCOMPARE(loaded.toJson(), d.columnMap().toJson());
    // The guess names the columns the way the shipped FL_THERMAL map does.
    QCOMPARE(loaded.columns.size(), 3);
    QCOMPARE(loaded.columns[0].id, QStringLiteral("t1"));
    QCOMPARE(loaded.columns[1].id, QStringLiteral("ch1"));
    QVERIFY(loaded.columns[1].target);
    QCOMPARE(loaded.columns[2].id, QStringLiteral("spindle_rpm"));
    QCOMPARE(loaded.columns[2].kind, QStringLiteral("other"));
    QCOMPARE(loaded.columns[2].role, QStringLiteral("spindle"));
}

void TestCsvImportDialog::badRowNamesLineAndColumn()
{
    const QString file = write(QStringLiteral("bad.csv"), "time_s,t1_C,ch1_um\n0,20,0\n15,20.5,1.5\n30,2O.7,2\n");
    const int before = SessionStore(m_db).sessions().size();
    CsvImportDialog d(m_db);
    QVERIFY(d.openFile(file));
    QSignalSpy finished(&d, &CsvImportDialog::importFinished);
    d.startImport();
    QVERIFY(finished.wait(20000));
    QCOMPARE(finished.front().front().toBool(), false);
    QVERIFY2(d.errorText().contains(QStringLiteral("line 4, column 2 (t1_C): non-numeric value '2O.7'")), qPrintable(d.errorText()));
    QVERIFY(d.errorText().contains(QStringLiteral("Nothing was imported")));
    // The preview shows file line numbers and selects the bad cell.
    QCOMPARE(d.preview()->currentRow(), 2);
    QCOMPARE(d.preview()->currentColumn(), 1);
    QCOMPARE(SessionStore(m_db).sessions().size(), before);
}

void TestCsvImportDialog::cancelLeavesNothing()
{
    QByteArray text = "time_s,t1_C,ch1_um\n";
    for (int i = 0; i < 150000; ++i)
        text += QByteArray::number(i) + ",20.25,1.5\n";
    const QString file = write(QStringLiteral("big.csv"), text);
    const int before = SessionStore(m_db).sessions().size();
    CsvImportDialog d(m_db);
    QVERIFY(d.openFile(file));
    QSignalSpy finished(&d, &CsvImportDialog::importFinished);
    d.startImport();
    d.reject(); // Escape or Cancel while importing cancels the import
    QVERIFY(finished.wait(20000));
    QCOMPARE(finished.front().front().toBool(), false);
    QVERIFY(!d.isImporting());
    QCOMPARE(SessionStore(m_db).sessions().size(), before);
}

void TestCsvImportDialog::mainWindowHasTheAction()
{
    MainWindow w;
    auto *action = w.findChild<QAction *>(QStringLiteral("ImportCsvAction"));
    QVERIFY(action);
    QVERIFY(action->text().contains(QStringLiteral("CSV")));
}

// The fixtures in tests/data/csv: German logger (preamble "Messung 17;Spindel 3", ';',
// decimal comma, dd.MM.yyyy, windows-1252), US logger (',', point, MM/dd/yyyy) and a ';' /
// decimal-comma table. The dialog's guess reads every row; imported, the values are the file's.
void TestCsvImportDialog::loggerFilesGuessedRight_data()
{
    QTest::addColumn<QString>("file");
    QTest::addColumn<char>("separator");
    QTest::addColumn<char>("decimal");
    QTest::addColumn<int>("skip");
    QTest::addColumn<QString>("timeColumn");
    QTest::addColumn<double>("lastTime");
    QTest::addColumn<QString>("channel");
    QTest::addColumn<double>("lastValue");
    QTest::addColumn<int>("rows");
    QTest::newRow("German") << "german_logger.csv" << ';' << ',' << 3 << "Datum" << 660.0 << "Weg_X" << 9.0 << 12;
    QTest::newRow("US") << "us_logger.csv" << ',' << '.' << 1 << "Timestamp" << 3300.0 << "Z_Growth" << 13.75 << 12;
    QTest::newRow("semicolon") << "semicolon_comma.csv" << ';' << ',' << 0 << "Zeit [min]" << 330.0 << "Verlagerung_Z" << 13.2 << 12;
    // Written for the issue 33 check of 2026-11-28, blind to the guesser: a German preamble
    // "Messung;Spindel" holding the separator, windows-1252 and CRLF; a US table in seconds with
    // a Fahrenheit column (stored in °C: 72.62 °F is 22.57 °C).
    QTest::newRow("German, separator in the preamble") << "audit_german.csv" << ';' << ',' << 3 << "Datum Uhrzeit" << 1740.0 << "Verlagerung_X" << 9.9 << 30;
    QTest::newRow("US, seconds and degF") << "audit_us.csv" << ',' << '.' << 0 << "Time (s)" << 1740.0 << "Nut_temp" << (72.62 - 32.0) * 5.0 / 9.0 << 30;
}

void TestCsvImportDialog::loggerFilesGuessedRight()
{
    QFETCH(QString, file);
    QFETCH(char, separator);
    QFETCH(char, decimal);
    QFETCH(int, skip);
    QFETCH(QString, timeColumn);
    QFETCH(double, lastTime);
    QFETCH(QString, channel);
    QFETCH(double, lastValue);
    QFETCH(int, rows);
    CsvImportDialog d(m_db);
    QVERIFY(d.openFile(QStringLiteral(DRIFTLAB_SOURCE_DIR "/tests/data/csv/") + file));
    const CsvColumnMap m = d.columnMap();
    QCOMPARE(m.separator, separator);
    QCOMPARE(m.decimal, decimal);
    QCOMPARE(m.skipLines, skip);
    QCOMPARE(m.time.column, timeColumn);
    QCOMPARE(d.preview()->rowCount(), std::min(rows, 20)); // the preview shows the first 20 rows
    QCOMPARE(d.columnTable()->rowCount(), d.preview()->columnCount() - 1);
    QCOMPARE(ticked(d), d.columnTable()->rowCount()); // every column but the time is imported
    // The preview shows each header and date whole (at 100 px a column read "T Lager [°C",
    // "01.03.20..." until 2026-11-28).
    QTableWidget *p = d.preview();
    for (int c = 0; c < p->columnCount(); ++c) {
        const int need = std::max(static_cast<const QAbstractItemView *>(p)->sizeHintForColumn(c), p->horizontalHeader()->sectionSizeHint(c));
        QVERIFY2(p->columnWidth(c) >= need, qPrintable(QStringLiteral("column '%1': %2 px, needs %3")
                                                          .arg(p->horizontalHeaderItem(c)->text()).arg(p->columnWidth(c)).arg(need)));
    }
    QVERIFY(d.errorText().isEmpty());
    QSignalSpy imported(&d, &CsvImportDialog::imported);
    QSignalSpy finished(&d, &CsvImportDialog::importFinished);
    d.startImport();
    QVERIFY(finished.wait(20000));
    QVERIFY2(finished.front().front().toBool(), qPrintable(d.errorText()));
    SessionStore store(m_db);
    const qint64 id = imported.front().front().toLongLong();
    QStringList keys;
    for (const ChannelInfo &c : store.channels(id)) {
        const SampleBlock b = store.samples(c.id);
        QCOMPARE(b.t.size(), rows);
        QCOMPARE(b.t.back(), lastTime);
        keys << c.key + QLatin1Char(' ') + c.unit;
        if (c.key == channel)
            QVERIFY2(std::fabs(b.v.back() - lastValue) < 1e-9, qPrintable(QString::number(b.v.back(), 'g', 17)));
    }
    QVERIFY2(std::any_of(keys.cbegin(), keys.cend(), [&](const QString &k) { return k.startsWith(channel + QLatin1Char(' ')); }),
             qPrintable(keys.join(QStringLiteral(", "))));
    QVERIFY(store.channels(id).size() == d.preview()->columnCount() - 1);
}

// The old guess on the German logger: ',' and no preamble, so the header was "Messung 17;
// Spindel 3". Fixing the separator and the preamble must give the table's columns, ticked.
void TestCsvImportDialog::fixingTheFormatKeepsColumnsTicked()
{
    CsvImportDialog d(m_db);
    QVERIFY(d.openFile(QStringLiteral(DRIFTLAB_SOURCE_DIR "/tests/data/csv/german_logger.csv")));
    auto *separator = d.findChild<QComboBox *>(QStringLiteral("CsvSeparator"));
    auto *skip = d.findChild<QSpinBox *>(QStringLiteral("CsvSkipLines"));
    QVERIFY(separator && skip);
    separator->setCurrentIndex(separator->findData(static_cast<int>(',')));
    skip->setValue(0);
    // One column of text under that header: no clock (since 2026-11-28 the guess does not take
    // a column of words for the time), so the one column is offered as a channel.
    QVERIFY(d.columnMap().time.fromRows());
    QCOMPARE(d.columnMap().columns.front().column, QStringLiteral("Messung 17;Spindel 3"));
    separator->setCurrentIndex(separator->findData(static_cast<int>(';')));
    skip->setValue(3);
    const CsvColumnMap m = d.columnMap();
    QCOMPARE(m.time.column, QStringLiteral("Datum"));
    QCOMPARE(m.time.format, QStringLiteral("dd.MM.yyyy HH:mm:ss"));
    QCOMPARE(m.columns.size(), 4);
    QCOMPARE(ticked(d), 4);
    // A change the user made survives a format change that keeps the header.
    const int bearing = row(d, QStringLiteral("T Lager [\u00b0C]"));
    QVERIFY(bearing >= 0);
    d.columnTable()->item(bearing, 2)->setText(QStringLiteral("T_fixed"));
    auto *decimal = d.findChild<QComboBox *>(QStringLiteral("CsvDecimal"));
    decimal->setCurrentIndex(decimal->findData(static_cast<int>('.')));
    decimal->setCurrentIndex(decimal->findData(static_cast<int>(',')));
    QCOMPARE(ticked(d), 4);
    QCOMPARE(d.columnMap().columns[0].id, QStringLiteral("T_fixed"));
    // A row interval leaves the greyed time-column box blank (it showed "Datum" before
    // 2026-11-28, as if that were still the clock); the date-time unit brings "Datum" back.
    auto *unit = d.findChild<QComboBox *>(QStringLiteral("CsvTimeUnit"));
    auto *timeColumn = d.findChild<QComboBox *>(QStringLiteral("CsvTimeColumn"));
    unit->setCurrentText(QStringLiteral("interval"));
    QVERIFY(!timeColumn->isEnabled());
    QCOMPARE(timeColumn->currentText(), QString());
    QVERIFY(d.columnMap().time.fromRows());
    decimal->setCurrentIndex(decimal->findData(static_cast<int>('.'))); // the preview reloads
    QCOMPARE(timeColumn->currentText(), QString());
    decimal->setCurrentIndex(decimal->findData(static_cast<int>(',')));
    unit->setCurrentText(QStringLiteral("date-time"));
    QVERIFY(timeColumn->isEnabled());
    QCOMPARE(timeColumn->currentText(), QStringLiteral("Datum"));
    QCOMPARE(d.columnMap().time.column, QStringLiteral("Datum"));
}

void TestCsvImportDialog::loadingAMapClearsTheError()
{
    const QString file = write(QStringLiteral("twocols.csv"), "time_s,t1_C,ch1_um\n0,20,0\n15,20.5,1.5\n");
    CsvImportDialog d(m_db);
    QVERIFY(d.openFile(file));
    const CsvColumnMap good = d.columnMap();
    for (int r = 0; r < d.columnTable()->rowCount(); ++r)
        d.columnTable()->item(r, 0)->setCheckState(Qt::Unchecked);
    d.startImport();
    QVERIFY(!d.isImporting());
    QVERIFY2(d.errorText().contains(QStringLiteral("field 'columns': missing or empty")), qPrintable(d.errorText()));
    const QString json = m_dir.filePath(QStringLiteral("twocols.json"));
    QFile f(json);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write(QJsonDocument(good.toJson()).toJson());
    f.close();
    QVERIFY(d.loadMapFile(json));
    QVERIFY2(d.errorText().isEmpty(), qPrintable(d.errorText()));
    QCOMPARE(ticked(d), 2);
    // A map that is not one: the error names it, and stays until the next good one.
    const QString broken = write(QStringLiteral("broken.json"), R"({"format":"driftlab-csv-map","version":1,"time":{"interval":"soon"},"columns":[]})");
    QVERIFY(!d.loadMapFile(broken));
    QVERIFY2(d.errorText().contains(QStringLiteral("field 'time.interval'")), qPrintable(d.errorText()));
    QVERIFY(d.loadMapFile(json));
    QVERIFY(d.errorText().isEmpty());
}

void TestCsvImportDialog::intervalClockAndRunColumn()
{
    const QString file = write(QStringLiteral("lauf.csv"), "Lauf;T Motor [\xC2\xB0" "C];Weg [\xC2\xB5m]\n1;20,0;0,0\n1;20,5;1,0\n"
                                                           "2;19,0;0,0\n2;19,4;0,8\n2;19,8;1,5\n");
    CsvImportDialog d(m_db);
    QVERIFY(d.openFile(file));
    QVERIFY2(d.startWarning().contains(QStringLiteral("guess")), qPrintable(d.startWarning())); // the file's modification time
    auto *unit = d.findChild<QComboBox *>(QStringLiteral("CsvTimeUnit"));
    auto *run = d.findChild<QComboBox *>(QStringLiteral("CsvRunColumn"));
    auto *interval = d.findChild<QLineEdit *>(QStringLiteral("CsvInterval"));
    auto *started = d.findChild<QDateTimeEdit *>(QStringLiteral("CsvStarted"));
    QVERIFY(unit && run && interval && started);
    // Guessed already (2026-11-28): no column is a time, "Lauf" names the runs.
    QCOMPARE(unit->currentText(), QStringLiteral("interval"));
    QCOMPARE(run->currentText(), QStringLiteral("Lauf"));
    if (!grabfordocs::dir().isEmpty()) // the guess as the dialog shows it, to look at
        QVERIFY(grabfordocs::maximised(d, QStringLiteral("csv-guess-interval-run"), [] {}));
    unit->setCurrentText(QStringLiteral("interval"));
    QCOMPARE(interval->text(), QStringLiteral("1 min"));
    QVERIFY(interval->isEnabled());
    QVERIFY(!d.findChild<QComboBox *>(QStringLiteral("CsvTimeColumn"))->isEnabled());
    run->setCurrentText(QStringLiteral("Lauf"));
    QVERIFY2(d.startWarning().contains(QStringLiteral("Each run starts")), qPrintable(d.startWarning()));
    started->setDateTime(QDateTime(QDate(2025, 6, 1), QTime(7, 0), Qt::UTC));
    QVERIFY(!d.startWarning().contains(QStringLiteral("guess"))); // the user set it
    const CsvColumnMap m = d.columnMap();
    QCOMPARE(m.time.interval_s, 60.0);
    QCOMPARE(m.runColumn, QStringLiteral("Lauf"));
    QCOMPARE(m.columns.size(), 2);
    QCOMPARE(ticked(d), 2);
    QCOMPARE(d.columnTable()->rowCount(), 2); // the run column is no channel
    // The map the dialog saves is the CLI's, with the new fields.
    const QString json = m_dir.filePath(QStringLiteral("lauf.json"));
    QVERIFY(d.saveMap(json));
    const CsvColumnMap loaded = CsvColumnMap::load(json);
    QCOMPARE(loaded.time.interval, QStringLiteral("1 min"));
    QCOMPARE(loaded.runColumn, QStringLiteral("Lauf"));
    QSignalSpy imported(&d, &CsvImportDialog::imported);
    QSignalSpy finished(&d, &CsvImportDialog::importFinished);
    const int before = SessionStore(m_db).sessions().size();
    d.startImport();
    QVERIFY(finished.wait(20000));
    QVERIFY2(finished.front().front().toBool(), qPrintable(d.errorText()));
    SessionStore store(m_db);
    QCOMPARE(store.sessions().size(), before + 2);
    const qint64 first = imported.front().front().toLongLong();
    QCOMPARE(store.session(first).name, QStringLiteral("lauf run 1"));
    QCOMPARE(store.session(first + 1).name, QStringLiteral("lauf run 2"));
    QCOMPARE(store.session(first).started, QStringLiteral("2025-06-01T07:00:00Z"));
    QCOMPARE(store.session(first + 1).started, QStringLiteral("2025-06-01T07:02:00Z")); // its first row is the file's third
    QCOMPARE(store.samples(store.channels(first + 1)[1].id).t, (QVector<double>{0, 60, 120}));
    QCOMPARE(store.samples(store.channels(first + 1)[1].id).v, (QVector<double>{0.0, 0.8, 1.5}));
}

void TestCsvImportDialog::reguessAfterAFormatFixReadsWhatTheCliReads()
{
    // A logger without a time column whose first channel warms for 30 rows and then cools: a
    // clock never runs back, so it is no clock and the rows are (the interval guess). The first
    // 20 rows alone rise, so a guess from them takes the channel for the time. After a wrong
    // separator is set and put right, the dialog guesses again: from the same rows as
    // `import-csv --guess-map` (CsvMapGuesser::guessFile). Before 2026-11-28 it guessed from
    // the 20 rows of its preview and took "Kanal 1" for the time.
    QByteArray text = "Kanal 1,Kanal 2\n";
    for (int r = 0; r < 60; ++r) {
        const double k1 = r < 30 ? 20.0 + 0.1 * r : 23.0 - 0.1 * (r - 30);
        text += QByteArray::number(k1, 'f', 1) + ',' + QByteArray::number(21.0 + 0.01 * r, 'f', 2) + '\n';
    }
    const QString file = write(QStringLiteral("warm_cool.csv"), text);
    const CsvColumnMap cli = CsvMapGuesser::guessFile(file);
    QVERIFY(cli.time.fromRows());
    CsvImportDialog d(m_db);
    QVERIFY(d.openFile(file));
    QVERIFY(d.columnMap().time.fromRows());
    auto *separator = d.findChild<QComboBox *>(QStringLiteral("CsvSeparator"));
    QVERIFY(separator);
    separator->setCurrentIndex(separator->findData(static_cast<int>(';')));
    QCOMPARE(d.columnMap().columns.size(), 1); // "Kanal 1,Kanal 2" as one column
    separator->setCurrentIndex(separator->findData(static_cast<int>(',')));
    const CsvColumnMap m = d.columnMap();
    QVERIFY2(m.time.fromRows(), qPrintable(m.time.column));
    QCOMPARE(m.time.interval, cli.time.interval);
    QCOMPARE(m.columns.size(), cli.columns.size());
    for (int c = 0; c < m.columns.size(); ++c) {
        QCOMPARE(m.columns[c].column, cli.columns[c].column);
        QCOMPARE(m.columns[c].kind, cli.columns[c].kind);
        QCOMPARE(m.columns[c].unit, cli.columns[c].unit);
    }
}

QTEST_MAIN(TestCsvImportDialog)
#include "tst_csvimportdialog.moc"
