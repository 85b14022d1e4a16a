// core/ModelExport, the export use case both faces run, without a process: a stored
// data-driven model (the fuzz corpus' mlr MODEL.json) exported for the portable C target and
// Sinumerik 840D writes exactly the files the target's exporter produces, nothing before
// write(); an unknown target or a missing model is refused before any work, a refused (a CSV table for two inputs)
// or cancelled export writes nothing, and the summary lists what was written with its sizes.

#include "ExportableModelJson.h"
#include "ModelExport.h"
#include "ModelExporterRegistry.h"

#include <QDir>
#include <QFile>
#include <QJsonArray>
#include <QTemporaryDir>
#include <QtTest>

using namespace driftlab;

namespace {
const QString kModel = QStringLiteral(DRIFTLAB_SOURCE_DIR "/tests/fuzz/corpus/model_json/mlr.json");
} // namespace

class TestModelExport : public QObject {
    Q_OBJECT
private:
    QTemporaryDir m_dir;

private slots:
    void writesWhatTheExporterProduces_data()
    {
        QTest::addColumn<QString>("target");
        QTest::newRow("c") << QStringLiteral("c");
        QTest::newRow("840d") << QStringLiteral("840d");
    }

    void writesWhatTheExporterProduces()
    {
        QFETCH(QString, target);
        const ModelExport exporting;
        ModelExport::Request q{kModel, target, ExportOptions{}};
        ModelExport::Result r = exporting.prepare(q);
        const QString folder = m_dir.filePath(target);
        QVERIFY(!QFileInfo::exists(folder)); // prepare() touches no file
        QCOMPARE(r.kind, QStringLiteral("mlr"));
        // The independent route: the registry's exporter on the parsed model.
        const ExportResult direct = ModelExporterRegistry().find(target.toStdString())->exportModel(ExportableModelJson::read(kModel), q.options);
        QCOMPARE(r.exported.files.size(), direct.files.size());
        QVERIFY(!direct.files.empty());
        exporting.write(r, folder);
        QCOMPARE(r.paths.size(), static_cast<int>(direct.files.size()));
        qint64 bytes = 0;
        for (std::size_t i = 0; i < direct.files.size(); ++i) {
            QFile f(r.paths[static_cast<int>(i)]);
            QVERIFY(f.open(QIODevice::ReadOnly));
            QCOMPARE(f.readAll(), QByteArray::fromStdString(direct.files[i].content));
            QCOMPARE(QFileInfo(f).absolutePath(), QDir(folder).absolutePath());
            bytes += static_cast<qint64>(direct.files[i].content.size());
        }
        QCOMPARE(r.bytes(), bytes);
        const QJsonObject summary = ModelExport::summaryJson(r);
        QCOMPARE(summary.value(QStringLiteral("files")).toArray().size(), r.paths.size());
        QCOMPARE(summary.value(QStringLiteral("target")).toString(), target);
        QCOMPARE(summary.value(QStringLiteral("model")).toString(), kModel);
    }

    void refusedOrCancelledWritesNothing()
    {
        const ModelExport exporting;
        QVERIFY_EXCEPTION_THROWN(exporting.prepare({kModel, QStringLiteral("no-such-cnc"), ExportOptions{}}), std::invalid_argument);
        QVERIFY_EXCEPTION_THROWN(exporting.prepare({m_dir.filePath(QStringLiteral("missing.json")), QStringLiteral("c"), ExportOptions{}}),
                                 std::invalid_argument);
        // A two-input model cannot be a table over one temperature: refused, nothing written.
        QVERIFY_EXCEPTION_THROWN(exporting.run({kModel, QStringLiteral("csv"), ExportOptions{}}, m_dir.filePath(QStringLiteral("refused"))),
                                 ExportRefused);
        QVERIFY(!QFileInfo::exists(m_dir.filePath(QStringLiteral("refused"))));
        const QString folder = m_dir.filePath(QStringLiteral("cancelled"));
        int stages = 0;
        QVERIFY_EXCEPTION_THROWN(exporting.run({kModel, QStringLiteral("c"), ExportOptions{}}, folder,
                                               [&](const QString &stage) { return ++stages < 3 || !stage.startsWith(QLatin1String("writing")); }),
                                 ModelExport::Cancelled);
        QCOMPARE(stages, 3); // read, export, then cancelled at the write
        QVERIFY(!QFileInfo::exists(folder));
    }
};

QTEST_GUILESS_MAIN(TestModelExport)
#include "tst_modelexport.moc"
