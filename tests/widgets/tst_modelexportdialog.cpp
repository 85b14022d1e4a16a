// The Export dialog previews exactly what export-model writes: the same files and bytes as the
// exporter, the notes and approximation error, or the refusal with its reason (Export disabled);
// Export writes the previewed files.

#include "ModelExportDialog.h"
#include "ModelExporterRegistry.h"

#include "ExportableModelJson.h"

#include <QDir>
#include <QFile>
#include <QPushButton>
#include <QTemporaryDir>
#include <QtTest>

using namespace driftlab;

class TestModelExportDialog : public QObject {
    Q_OBJECT

private slots:
    void previewEqualsExportAndWrites();
    void refusalDisablesExport();

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

QTEST_MAIN(TestModelExportDialog)
#include "tst_modelexportdialog.moc"
