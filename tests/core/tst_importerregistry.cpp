// core/ImporterRegistry, the one importer list of drag and drop and `driftlab-cli import`:
// each kind of path finds its importer (bundle folder or zip, session database, .rtl, CSV,
// nothing for others); the shipped example bundle imports with every part (9 channels, 4
// infrared frames, 37 interferometer points, as the bundle holds), a second time only as an
// explicit copy; a database import copies its sessions with the same content; importers that
// need more (a CSV column map, an .rtl file's session) refuse before touching the store.

#include "DuplicateSessionError.h"
#include "ImporterRegistry.h"
#include "SessionCopier.h"
#include "SessionStore.h"

#include <QFile>
#include <QTemporaryDir>
#include <QtTest>

using namespace driftlab;

namespace {
const QString kBundle = QStringLiteral(DRIFTLAB_SOURCE_DIR "/resources/bundles/example.bundle");

QString touch(const QTemporaryDir &dir, const QString &name)
{
    QFile f(dir.filePath(name));
    f.open(QIODevice::WriteOnly);
    f.write("x\n");
    return f.fileName();
}
} // namespace

class TestImporterRegistry : public QObject {
    Q_OBJECT
private:
    QTemporaryDir m_dir;

private slots:
    void findsTheImporterOfEachPath()
    {
        const ImporterRegistry r;
        auto nameOf = [&](const QString &path) { return r.find(path) ? r.find(path)->name() : QStringLiteral("none"); };
        QCOMPARE(nameOf(kBundle), QStringLiteral("bundle"));
        QCOMPARE(nameOf(kBundle + QStringLiteral("/manifest.json")), QStringLiteral("bundle"));
        QCOMPARE(nameOf(m_dir.filePath(QStringLiteral("lab.ZIP"))), QStringLiteral("bundle"));
        QCOMPARE(nameOf(touch(m_dir, QStringLiteral("other.sqlite"))), QStringLiteral("sqlite"));
        QCOMPARE(nameOf(m_dir.filePath(QStringLiteral("missing.sqlite"))), QStringLiteral("none")); // not a file
        QCOMPARE(nameOf(m_dir.filePath(QStringLiteral("run1.RTL"))), QStringLiteral("rtl"));
        QCOMPARE(nameOf(m_dir.filePath(QStringLiteral("table.csv"))), QStringLiteral("csv"));
        QCOMPARE(nameOf(m_dir.filePath(QStringLiteral("photo.png"))), QStringLiteral("none"));
        QCOMPARE(nameOf(m_dir.path()), QStringLiteral("none")); // a folder without manifest.json
        QVERIFY(r.byName(QStringLiteral("csv"))->needsColumnMap());
        QVERIFY(!r.byName(QStringLiteral("bundle"))->needsColumnMap());
    }

    void importsBundleThenDatabase()
    {
        const ImporterRegistry r;
        const QString first = m_dir.filePath(QStringLiteral("first.sqlite"));
        qint64 id = 0;
        {
            SessionStore store(first);
            const QList<qint64> ids = r.find(kBundle)->import(kBundle, store, {});
            QCOMPARE(ids.size(), 1);
            id = ids.front();
            QCOMPARE(store.channels(id).size(), 9);
            QCOMPARE(store.irFrames(id).size(), 4);
            QCOMPARE(store.interferometerPoints(id).size(), 37);
            QVERIFY_EXCEPTION_THROWN(r.find(kBundle)->import(kBundle, store, {}), DuplicateSessionError);
            SessionImporter::Options copy;
            copy.allowDuplicate = true;
            QCOMPARE(r.find(kBundle)->import(kBundle, store, copy).size(), 1);
            QCOMPARE(store.sessions().size(), 2);
        }
        SessionStore second(m_dir.filePath(QStringLiteral("second.sqlite")));
        const QList<qint64> copied = r.find(first)->import(first, second, {});
        QCOMPARE(copied.size(), 2); // both complete sessions, each verified by SessionCopier
        const SessionStore from(first);
        QCOMPARE(second.session(copied.front()).uuid, from.session(id).uuid);
        QCOMPARE(SessionCopier::digest(second, copied.front()), SessionCopier::digest(from, id));
        QCOMPARE(SessionCopier::digest(second, copied.back()), SessionCopier::digest(from, from.sessions().back().id));
    }

    void refusesWhatItCannotRunBeforeWork()
    {
        const ImporterRegistry r;
        SessionStore store(m_dir.filePath(QStringLiteral("refuse.sqlite")));
        const QString csv = touch(m_dir, QStringLiteral("t.csv"));
        QVERIFY_EXCEPTION_THROWN(r.find(csv)->import(csv, store, {}), std::invalid_argument);
        const QString rtl = touch(m_dir, QStringLiteral("r.rtl"));
        QVERIFY_EXCEPTION_THROWN(r.find(rtl)->import(rtl, store, {}), std::invalid_argument);
        QVERIFY(store.sessions().isEmpty());
    }
};

QTEST_GUILESS_MAIN(TestImporterRegistry)
#include "tst_importerregistry.moc"
