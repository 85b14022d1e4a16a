// The Export dialog previews exactly what export-model writes: the same files and bytes as the
// exporter, the notes and approximation error, or the refusal with its reason (Export disabled);
// Export writes the previewed files. Issue 34: the dialog runs core/ModelExport as
// 'driftlab-cli export-model' does: the same folder, byte for byte, for the same model and
// target, and a write that fails on a full disk leaves nothing behind in either face.

#include "ModelExport.h"
#include "ModelExportDialog.h"
#include "ModelExporterRegistry.h"

#include "ExportableModelJson.h"
#include "SessionStore.h"

#include "../support/CliRunner.h"

#include <QComboBox>
#include <QJsonDocument>
#include <QJsonObject>

#include <QDir>
#include <QFile>
#include <QProcess>
#include <QPushButton>
#include <QScopeGuard>
#include <QTemporaryDir>
#include <QtTest>

using namespace driftlab;

class TestModelExportDialog : public QObject {
    Q_OBJECT

private slots:
    void previewEqualsExportAndWrites();
    void refusalDisablesExport();
    void listsTheModelsStoredWithTheSessions();
    void writesTheSameFolderAsTheCli_data();
    void writesTheSameFolderAsTheCli();
    void failedWriteLeavesNothingInBothFaces();

private:
    QString write(const QString &name, const QByteArray &bytes);
    QTemporaryDir m_dir;
};

QString TestModelExportDialog::write(const QString &name, const QByteArray &bytes)
{
    QFile f(m_dir.filePath(name));
    if (f.open(QIODevice::WriteOnly))
        f.write(bytes);
    return f.fileName();
}

void TestModelExportDialog::previewEqualsExportAndWrites()
{
    const QString model = write(QStringLiteral("syn.json"), R"({"format": "driftlab-model", "version": 1, "model": "synthetic",
        "target": {"channel": "interferometer"}, "inputs": [{"channel": "t1"}, {"channel": "t2"}],
        "synthetic": {"temperatures": [0, 1], "a": 6.5, "b_perK": 0.045, "c": -1.2, "t0_C": 20, "p0_mm": -141, "p_ref_mm": 550}})");
    ModelExportDialog dialog;
    dialog.setModelPath(model);
    dialog.setTarget(QStringLiteral("840d"));
    QVERIFY(!dialog.canExport()); // no folder yet
    const ExportResult expected =
        ModelExporterRegistry().find("840d")->exportModel(ExportableModelJson::read(model), ExportOptions{});
    QCOMPARE(dialog.previewFileNames(), (QStringList{QStringLiteral("driftlab_comp.mpf"), QStringLiteral("driftlab_comp_sd_table.csv")}));
    for (const ExportFile &f : expected.files)
        QCOMPARE(dialog.previewText(QString::fromStdString(f.name)), QString::fromStdString(f.content));
    QVERIFY2(dialog.message().contains(QStringLiteral("synthetic -> 840d")), qPrintable(dialog.message()));
    QVERIFY(dialog.message().contains(QStringLiteral("K3 Compensations")));
    const QString folder = m_dir.filePath(QStringLiteral("out"));
    dialog.setFolder(folder);
    QVERIFY(dialog.canExport());
    if (!qEnvironmentVariableIsEmpty("DRIFTLAB_SCREENSHOT")) { // docs/screenshots/export-dialog.png
        dialog.show();
        QVERIFY(dialog.grab().save(qEnvironmentVariable("DRIFTLAB_SCREENSHOT")));
    }
    QVERIFY(dialog.exportFiles());
    for (const ExportFile &f : expected.files) {
        QFile written(QDir(folder).filePath(QString::fromStdString(f.name)));
        QVERIFY(written.open(QIODevice::ReadOnly));
        QCOMPARE(written.readAll(), QByteArray::fromStdString(f.content));
    }
}

void TestModelExportDialog::refusalDisablesExport()
{
    const QString model = write(QStringLiteral("fdm.json"),
                                R"({"model": "fdm-seed000", "parameters": {"k1": 0.0008, "k2": 22, "k3": 0.00095, "k4": 0.0015,
                                    "lambda_W_mK": 420, "fixed_end_position_mm": -141}})");
    ModelExportDialog dialog;
    dialog.setFolder(m_dir.filePath(QStringLiteral("never")));
    dialog.setModelPath(model);
    dialog.setTarget(QStringLiteral("fanuc"));
    QVERIFY(!dialog.canExport());
    QVERIFY(dialog.previewFileNames().isEmpty());
    QVERIFY2(dialog.message().contains(QStringLiteral("fanuc refuses this model")) &&
                 dialog.message().contains(QStringLiteral("temperature field")),
             qPrintable(dialog.message()));
    QVERIFY(!dialog.exportFiles());
    QVERIFY(!QFileInfo::exists(m_dir.filePath(QStringLiteral("never"))));
    dialog.setTarget(QStringLiteral("c"));
    QVERIFY(dialog.canExport());
    QCOMPARE(dialog.previewFileNames(), (QStringList{QStringLiteral("driftlab_comp.c"), QStringLiteral("driftlab_comp.h")}));
    QVERIFY(dialog.previewText(QStringLiteral("driftlab_comp.c")).contains(QStringLiteral("K1 = 0.00080000000000000004")));
    dialog.setModelPath(m_dir.filePath(QStringLiteral("missing.json")));
    QVERIFY(!dialog.canExport());
    QVERIFY2(dialog.message().contains(QStringLiteral("cannot read")), qPrintable(dialog.message()));
}

// Issue 33 item 6: the dialog lists the fitted models stored with the open database's
// sessions (the current session's newest selected) and previews each exactly as export-model
// would preview the same model written as MODEL.json by hand; Browse... (a file) still works.
void TestModelExportDialog::listsTheModelsStoredWithTheSessions()
{
    const QString db = m_dir.filePath(QStringLiteral("models.sqlite"));
    SessionStore store(db);
    const QJsonObject screw{{QStringLiteral("length_m"), 0.8}, {QStringLiteral("diameter_m"), 0.034},
                            {QStringLiteral("nut_length_m"), 0.212}, {QStringLiteral("fixed_bearing_length_m"), 0.03},
                            {QStringLiteral("density_kg_m3"), 7800}, {QStringLiteral("specific_heat_J_kgK"), 448},
                            {QStringLiteral("expansion_per_K"), 1.17e-5}};
    SessionInfo a;
    a.name = QStringLiteral("X warm-up");
    a.machine = QJsonObject{{QStringLiteral("name"), QStringLiteral("rig")}, {QStringLiteral("screw"), screw}};
    const qint64 first = store.createSession(a);
    SessionInfo b;
    b.name = QStringLiteral("X cool-down");
    const qint64 second = store.createSession(b);
    store.createSession(SessionInfo{}); // a session without models
    const QByteArray synthetic = R"({"format": "driftlab-model", "version": 1, "model": "synthetic",
        "target": {"channel": "interferometer"}, "inputs": [{"channel": "t1"}, {"channel": "t2"}],
        "synthetic": {"temperatures": [0, 1], "a": 6.5, "b_perK": 0.045, "c": -1.2, "t0_C": 20, "p0_mm": -141, "p_ref_mm": 550}})";
    FittedModel dd;
    dd.model = QStringLiteral("driftlab-model/synthetic");
    dd.parameters = QJsonDocument::fromJson(synthetic).object();
    const qint64 ddId = store.addFittedModel(second, dd);
    FittedModel fdm;
    fdm.model = QStringLiteral("fdm-seed000");
    fdm.parameters = QJsonObject{{QStringLiteral("k1"), 0.0008}, {QStringLiteral("k2"), 22},    {QStringLiteral("k3"), 0.00095},
                                 {QStringLiteral("k4"), 0.0015}, {QStringLiteral("lambda_W_mK"), 42}, {QStringLiteral("fixed_end_position_mm"), -141}};
    fdm.provenance = QJsonObject{{QStringLiteral("schema_version"), 2}, {QStringLiteral("grid"), QJsonObject{{QStringLiteral("dx_m"), 0.01}}}};
    const qint64 fdmId = store.addFittedModel(first, fdm);

    ModelExportDialog dialog;
    dialog.setTarget(QStringLiteral("c"));
    dialog.setStore(&store, second);
    const QStringList listed = dialog.storedModels();
    QCOMPARE(listed.size(), 2);
    QVERIFY2(listed[0].startsWith(QStringLiteral("#%1 X warm-up: fdm-seed000").arg(first)), qPrintable(listed[0]));
    QVERIFY2(listed[1].startsWith(QStringLiteral("#%1 X cool-down: driftlab-model/synthetic").arg(second)), qPrintable(listed[1]));
    QCOMPARE(dialog.findChild<QComboBox *>(QStringLiteral("StoredModels"))->currentIndex(), 2); // the current session's
    // The data-driven model: as export-model previews the same JSON.
    const auto expect = [](const QByteArray &json, const QString &source, const char *target) {
        return ModelExporterRegistry().find(target)->exportModel(ExportableModelJson::parse(json, source), ExportOptions{});
    };
    ExportResult expected = expect(synthetic, QStringLiteral("session %1, model %2").arg(second).arg(ddId), "c");
    QVERIFY(!expected.files.empty());
    QCOMPARE(dialog.previewFileNames().size(), static_cast<int>(expected.files.size()));
    for (const ExportFile &f : expected.files)
        QCOMPARE(dialog.previewText(QString::fromStdString(f.name)), QString::fromStdString(f.content));
    // The screw model: its parameters and grid from the record, the screw from the session.
    dialog.selectStoredModel(0);
    const QByteArray fdmJson = QJsonDocument(QJsonObject{{QStringLiteral("model"), QStringLiteral("fdm-seed000")},
                                                         {QStringLiteral("schema_version"), 2},
                                                         {QStringLiteral("parameters"), fdm.parameters},
                                                         {QStringLiteral("screw"), screw},
                                                         {QStringLiteral("grid"), QJsonObject{{QStringLiteral("dx_m"), 0.01}}}})
                                   .toJson();
    expected = expect(fdmJson, QStringLiteral("session %1, model %2").arg(first).arg(fdmId), "c");
    QVERIFY2(dialog.message().contains(QStringLiteral("fdm-seed000 -> c")), qPrintable(dialog.message()));
    for (const ExportFile &f : expected.files)
        QCOMPARE(dialog.previewText(QString::fromStdString(f.name)), QString::fromStdString(f.content));
    dialog.setFolder(m_dir.filePath(QStringLiteral("stored")));
    QVERIFY(dialog.canExport());
    // Browse... stays: a file replaces the stored choice.
    const QString file = write(QStringLiteral("file.json"), synthetic);
    dialog.setModelPath(file);
    QCOMPARE(dialog.findChild<QComboBox *>(QStringLiteral("StoredModels"))->currentIndex(), 0);
    expected = expect(synthetic, file, "c");
    for (const ExportFile &f : expected.files)
        QCOMPARE(dialog.previewText(QString::fromStdString(f.name)), QString::fromStdString(f.content));
    // Without a current session with models: the newest of all; without models: says so.
    ModelExportDialog other;
    other.setStore(&store, 0);
    QVERIFY(fdmId > ddId);
    QCOMPARE(other.findChild<QComboBox *>(QStringLiteral("StoredModels"))->currentIndex(), 1); // the fdm model, stored last
    SessionStore empty(m_dir.filePath(QStringLiteral("empty.sqlite")));
    other.setStore(&empty, 0);
    QVERIFY(other.storedModels().isEmpty());
    QVERIFY(!other.canExport());
    QVERIFY(other.message().contains(QStringLiteral("Browse")));
}

namespace {

const QByteArray kSynthetic = R"({"format": "driftlab-model", "version": 1, "model": "synthetic",
    "target": {"channel": "interferometer"}, "inputs": [{"channel": "t1"}],
    "synthetic": {"temperatures": [0], "a": 6.5, "b_perK": 0.045, "c": -1.2, "t0_C": 20, "p0_mm": -141, "p_ref_mm": 550}})";

// name -> bytes of every file in a folder (sub-folders are not expected).
QMap<QString, QByteArray> contents(const QString &folder)
{
    QMap<QString, QByteArray> files;
    const QDir dir(folder);
    for (const QString &name : dir.entryList(QDir::AllEntries | QDir::NoDotAndDotDot | QDir::Hidden)) {
        QFile f(dir.filePath(name));
        files.insert(name, f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray("(not a readable file)"));
    }
    return files;
}

} // namespace

void TestModelExportDialog::writesTheSameFolderAsTheCli_data()
{
    QTest::addColumn<QString>("target");
    QTest::addColumn<QString>("axis");
    QTest::addColumn<bool>("namesAxis"); // the files name the axis (C code and a csv table do not)
    for (const char *t : {"840d", "linuxcnc", "heidenhain"})
        QTest::newRow(t) << QString::fromLatin1(t) << QStringLiteral("Y") << true;
    QTest::newRow("c") << QStringLiteral("c") << QStringLiteral("Z") << false;
    QTest::newRow("csv") << QStringLiteral("csv") << QStringLiteral("Z") << false;
}

void TestModelExportDialog::writesTheSameFolderAsTheCli()
{
    QFETCH(QString, target);
    QFETCH(QString, axis);
    QFETCH(bool, namesAxis);
    const QString model = write(QStringLiteral("faces.json"), kSynthetic);
    const QString cliOut = m_dir.filePath(QStringLiteral("cli-") + target);
    const clirunner::Result r = clirunner::run({QStringLiteral("export-model"), model, QStringLiteral("--target"), target,
                                                QStringLiteral("--axis"), axis, QStringLiteral("--out"), cliOut});
    QVERIFY2(r.code == 0, r.err.constData());
    ModelExportDialog dialog;
    dialog.setModelPath(model);
    dialog.setAxis(axis);
    dialog.setTarget(target);
    const QString guiOut = m_dir.filePath(QStringLiteral("gui-") + target);
    dialog.setFolder(guiOut);
    QVERIFY2(dialog.exportFiles(), qPrintable(dialog.message()));
    const QMap<QString, QByteArray> cli = contents(cliOut), gui = contents(guiOut);
    QVERIFY(!cli.isEmpty());
    QCOMPARE(gui.keys(), cli.keys());
    for (const QString &name : cli.keys())
        QVERIFY2(gui.value(name) == cli.value(name), qPrintable(name));
    // The axis really reached both faces: the files differ from the default (X) export.
    const ModelExport::Result defaultAxis = ModelExport().prepare({model, target, ExportOptions{}});
    bool differs = false;
    for (const ExportFile &f : defaultAxis.exported.files)
        differs = differs || cli.value(QString::fromStdString(f.name)) != QByteArray::fromStdString(f.content);
    QCOMPARE(differs, namesAxis);
}

// A model whose 840d table does not fit: the tmpfs has room for the first file only. Before,
// the dialog wrote through ModelExportWriter alone and left the first file (and the folder).
void TestModelExportDialog::failedWriteLeavesNothingInBothFaces()
{
    const QString mountPoint = m_dir.filePath(QStringLiteral("tiny"));
    QDir().mkpath(mountPoint);
    QProcess mount;
    mount.start(QStringLiteral("mount"), {QStringLiteral("-t"), QStringLiteral("tmpfs"), QStringLiteral("-o"), QStringLiteral("size=256k"),
                                          QStringLiteral("tmpfs"), mountPoint});
    if (!mount.waitForFinished(10000) || mount.exitStatus() != QProcess::NormalExit || mount.exitCode() != 0)
        QSKIP("cannot mount a small tmpfs here (needs root and mount permission)");
    const auto unmount = qScopeGuard([&] { QProcess::execute(QStringLiteral("umount"), {QStringLiteral("-l"), mountPoint}); });
    const QString model = write(QStringLiteral("full.json"), kSynthetic);
    ModelExportDialog dialog;
    dialog.setModelPath(model);
    dialog.setTarget(QStringLiteral("840d"));
    const QStringList names = dialog.previewFileNames();
    QCOMPARE(names.size(), 2);
    // Fill the disk so that the first file fits (its pages) and the second does not.
    const qint64 page = 4096;
    const qint64 first = dialog.previewText(names[0]).toUtf8().size();
    QVERIFY(first > 0 && dialog.previewText(names[1]).toUtf8().size() > 0);
    QFile filler(mountPoint + QStringLiteral("/filler"));
    QVERIFY(filler.open(QIODevice::WriteOnly));
    filler.write(QByteArray(256 * 1024 - (first + page - 1) / page * page, 'x'));
    filler.close();
    const QStringList before = QDir(mountPoint).entryList(QDir::AllEntries | QDir::NoDotAndDotDot);
    QCOMPARE(before, QStringList{QStringLiteral("filler")});
    // The first file alone fits (the check that the disk is as full as meant).
    {
        QFile probe(mountPoint + QStringLiteral("/probe"));
        QVERIFY(probe.open(QIODevice::WriteOnly));
        QCOMPARE(probe.write(dialog.previewText(names[0]).toUtf8()), first);
        QVERIFY(probe.flush());
        probe.close();
        QVERIFY(probe.remove());
    }
    // The CLI: exit 1, the folder it made is gone.
    const QString cliOut = mountPoint + QStringLiteral("/cli");
    const clirunner::Result r = clirunner::run({QStringLiteral("export-model"), model, QStringLiteral("--target"), QStringLiteral("840d"),
                                                QStringLiteral("--out"), cliOut});
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("(nothing was left)"), r.err.constData());
    QCOMPARE(QDir(mountPoint).entryList(QDir::AllEntries | QDir::NoDotAndDotDot), before);
    // The dialog: a folder it makes, and an existing (empty) folder: nothing it added stays.
    for (const bool existing : {false, true}) {
        const QString guiOut = mountPoint + QStringLiteral("/gui");
        if (existing)
            QVERIFY(QDir().mkpath(guiOut));
        dialog.setFolder(guiOut);
        QVERIFY(dialog.canExport());
        QVERIFY(!dialog.exportFiles());
        QVERIFY2(dialog.message().contains(QStringLiteral("cannot write")) && dialog.message().contains(QStringLiteral("(nothing was left)")),
                 qPrintable(dialog.message()));
        if (existing) {
            QCOMPARE(contents(guiOut).keys(), QStringList());
            QVERIFY(QDir(guiOut).removeRecursively());
        }
        QCOMPARE(QDir(mountPoint).entryList(QDir::AllEntries | QDir::NoDotAndDotDot), before);
    }
}

QTEST_MAIN(TestModelExportDialog)
#include "tst_modelexportdialog.moc"
