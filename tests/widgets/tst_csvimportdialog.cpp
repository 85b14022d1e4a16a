// The CSV import dialog as a user drives it: a ';'/decimal-comma logger file is read with
// the dialect and kinds guessed, an assignment is changed, the import runs on its worker
// thread into the database; the same header later brings the changed assignment back; the map
// saves as JSON the CLI reads; a bad row names its line and column and imports nothing; a
// cancelled import leaves nothing; File > Import CSV table exists.

#include "CsvColumnMap.h"
#include "CsvImportDialog.h"
#include "MainWindow.h"
#include "SessionStore.h"

#include <QAction>
#include <QComboBox>
#include <QSettings>
#include <QSignalSpy>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QtTest>

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

private:
    QString write(const QString &name, const QByteArray &bytes);
    int row(CsvImportDialog &d, const QString &header);
    QTemporaryDir m_dir;
    QString m_db;
};

QString TestCsvImportDialog::write(const QString &name, const QByteArray &bytes)
{
    const QString path = m_dir.filePath(name);
    QFile f(path);
    if (!f.open(QIODevice::WriteOnly) || f.write(bytes) != bytes.size())
        qFatal("cannot write %s", qPrintable(path));
    return path;
}

int TestCsvImportDialog::row(CsvImportDialog &d, const QString &header)
{
    for (int r = 0; r < d.columnTable()->rowCount(); ++r) {
        if (d.columnTable()->item(r, 1)->text() == header)
            return r;
    }
    return -1;
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

QTEST_MAIN(TestCsvImportDialog)
#include "tst_csvimportdialog.moc"
