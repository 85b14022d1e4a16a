#include "BundleArchive.h"

#include "BundleError.h"

#include <QCoreApplication>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QTemporaryFile>

#include <signal.h>
#include <sys/stat.h>

#include <cerrno>

#include <zip.h>

#include <cstdlib>
#include <cstring>
#include <limits>
#include <algorithm>

namespace driftlab {

namespace {

constexpr qint64 kMaxEntryBytes = qint64(1) << 31; // QByteArray limit: files read whole
// Zip entries above 64 MiB may expand at most 100 times (CSV of sampled data: 3-10 times);
// all entries together at most 16 GiB.
constexpr zip_uint64_t kRatioCheckedBytes = zip_uint64_t(64) << 20;
constexpr zip_uint64_t kMaxRatio = 100;
constexpr zip_uint64_t kMaxTotalBytes = zip_uint64_t(16) << 30;

QString zipError(zip_t *z)
{
    return QString::fromUtf8(zip_strerror(z));
}

} // namespace

bool BundleArchive::isSafeRelativePath(const QString &path)
{
    if (path.isEmpty() || path.startsWith(QLatin1Char('/')) || path.contains(QLatin1Char('\\')) ||
        (path.size() >= 2 && path.at(1) == QLatin1Char(':')))
        return false;
    for (const QString &part : path.split(QLatin1Char('/'))) {
        if (part == QLatin1String(".."))
            return false;
    }
    return true;
}

// A killed export leaves its hidden ".NAME.partial-PID" folder; the next export of NAME removes
// those whose process is gone (kill(pid, 0) fails with ESRCH), never a running export's.
static void removeAbandonedPartials(const QString &dir, const QString &name)
{
    const QString prefix = QStringLiteral(".") + name + QStringLiteral(".partial-");
    const QStringList found = QDir(dir).entryList({prefix + QLatin1Char('*')}, QDir::Dirs | QDir::Hidden | QDir::NoDotAndDotDot);
    for (const QString &entry : found) {
        bool ok = false;
        const qint64 pid = entry.mid(prefix.size()).toLongLong(&ok);
        if (ok && pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH)
            QDir(dir + QLatin1Char('/') + entry).removeRecursively();
    }
}

BundleArchive::BundleArchive(const QString &path, Mode mode) : m_path(path), m_mode(mode)
{
    const bool zipPath = path.endsWith(QLatin1String(".zip"), Qt::CaseInsensitive);
    const QString name = QFileInfo(path).fileName();
    if (mode == Mode::Write) {
        if (QFileInfo::exists(path))
            throw BundleError(name, 0, QString(), QStringLiteral("already exists; not overwriting %1").arg(path));
        if (zipPath) {
            int error = 0;
            m_zip = zip_open(QFile::encodeName(path).constData(), ZIP_CREATE | ZIP_EXCL, &error);
            if (!m_zip) {
                zip_error_t ze;
                zip_error_init_with_code(&ze, error);
                const QString what = QString::fromUtf8(zip_error_strerror(&ze));
                zip_error_fini(&ze);
                throw BundleError(name, 0, QString(), QStringLiteral("cannot create zip: %1").arg(what));
            }
        } else {
            // Written next to its place under a hidden name and renamed by finish(): a failed
            // export (disk full) leaves no partial bundle behind.
            m_writeDir = QFileInfo(path).absolutePath() + QStringLiteral("/.") + name +
                         QStringLiteral(".partial-%1").arg(QCoreApplication::applicationPid());
            QDir(m_writeDir).removeRecursively();
            removeAbandonedPartials(QFileInfo(path).absolutePath(), name);
            if (!QDir().mkpath(m_writeDir)) {
                const int why = ::mkdir(QFile::encodeName(m_writeDir).constData(), 0777) == 0 ? 0 : errno;
                throw BundleError(name, 0, QString(),
                                  QStringLiteral("cannot create directory %1: %2")
                                      .arg(m_writeDir, QString::fromLocal8Bit(std::strerror(why ? why : EIO))));
            }
        }
        return;
    }
    const QFileInfo info(path);
    if (info.isDir()) {
        m_root = info.canonicalFilePath();
        return;
    }
    if (!info.exists())
        throw BundleError(name, 0, QString(), QStringLiteral("no such bundle directory or zip: %1").arg(path));
    int error = 0;
    m_zip = zip_open(QFile::encodeName(path).constData(), ZIP_RDONLY | ZIP_CHECKCONS, &error);
    if (!m_zip) {
        zip_error_t ze;
        zip_error_init_with_code(&ze, error);
        // Opening for reading, "file exists" is libzip's word for two entries of one name.
        const QString what = error == ZIP_ER_EXISTS ? QStringLiteral("two entries have the same name (which is the bundle's?)")
                                                    : QString::fromUtf8(zip_error_strerror(&ze));
        zip_error_fini(&ze);
        throw BundleError(name, 0, QString(), QStringLiteral("not a readable zip bundle: %1").arg(what));
    }
    const zip_int64_t n = zip_get_num_entries(m_zip, 0);
    QHash<QString, qint64> all;
    zip_uint64_t total = 0;
    for (zip_int64_t i = 0; i < n; ++i) {
        const char *raw = zip_get_name(m_zip, static_cast<zip_uint64_t>(i), ZIP_FL_ENC_GUESS);
        const QString entry = raw ? QString::fromUtf8(raw) : QString();
        if (!isSafeRelativePath(entry)) {
            zip_discard(m_zip);
            m_zip = nullptr;
            throw BundleError(name, 0, QStringLiteral("entry %1").arg(i),
                              QStringLiteral("unsafe zip entry name '%1' (absolute path or '..'): refused").arg(entry));
        }
        if (!entry.endsWith(QLatin1Char('/')))
            all.insert(entry, i);
        // Before anything is extracted: no entry may expand out of all proportion (a zip bomb),
        // nor the whole beyond what a bundle may hold.
        zip_stat_t st;
        zip_stat_init(&st);
        if (zip_stat_index(m_zip, static_cast<zip_uint64_t>(i), 0, &st) == 0 && (st.valid & ZIP_STAT_SIZE) &&
            (st.valid & ZIP_STAT_COMP_SIZE)) {
            total += st.size;
            if (st.size > kRatioCheckedBytes && st.size > kMaxRatio * std::max<zip_uint64_t>(st.comp_size, 1)) {
                zip_discard(m_zip);
                m_zip = nullptr;
                throw BundleError(name, 0, QStringLiteral("entry %1").arg(entry),
                                  QStringLiteral("expands from %1 to %2 bytes, more than %3 times (a zip bomb?): refused before "
                                                 "extracting anything")
                                      .arg(st.comp_size)
                                      .arg(st.size)
                                      .arg(kMaxRatio));
            }
        }
    }
    if (total > kMaxTotalBytes) {
        zip_discard(m_zip);
        m_zip = nullptr;
        throw BundleError(name, 0, QString(),
                          QStringLiteral("expands to %1 bytes, more than the %2 a bundle may hold: refused before extracting anything")
                              .arg(total)
                              .arg(kMaxTotalBytes));
    }
    // The bundle is at the root or in one top-level folder (a zipped NAME.bundle/).
    if (!all.contains(QStringLiteral("manifest.json"))) {
        for (auto it = all.cbegin(); it != all.cend(); ++it) {
            const QString &entry = it.key();
            if (entry.count(QLatin1Char('/')) == 1 && entry.endsWith(QLatin1String("/manifest.json"))) {
                m_prefix = entry.left(entry.size() - static_cast<int>(std::strlen("manifest.json")));
                break;
            }
        }
    }
    for (auto it = all.cbegin(); it != all.cend(); ++it) {
        if (it.key().startsWith(m_prefix))
            m_entries.insert(it.key().mid(m_prefix.size()), it.value());
    }
}

BundleArchive::~BundleArchive()
{
    if (m_zip)
        zip_discard(m_zip);
    if (!m_writeDir.isEmpty())
        QDir(m_writeDir).removeRecursively(); // not finished: nothing of it stays
}

bool BundleArchive::exists(const QString &relativePath) const
{
    if (!isSafeRelativePath(relativePath))
        return false;
    if (m_zip)
        return m_entries.contains(relativePath);
    // Present at all (a dangling link or a pipe too): read() then says what is wrong with it.
    const QFileInfo fi(QDir(m_path).filePath(relativePath));
    return (fi.exists() || fi.isSymLink()) && !fi.isDir();
}

QString BundleArchive::checkedFile(const QString &relativePath) const
{
    const QFileInfo fi(QDir(m_path).filePath(relativePath));
    if (!fi.exists() && !fi.isSymLink())
        throw BundleError(relativePath, 0, QString(), QStringLiteral("missing from the bundle"));
    // Whatever a link inside the bundle points to must be inside the bundle too.
    const QString canonical = fi.canonicalFilePath();
    if (canonical.isEmpty())
        throw BundleError(relativePath, 0, QString(), QStringLiteral("a symbolic link to nothing: refused"));
    if (m_root.isEmpty() || !canonical.startsWith(m_root + QLatin1Char('/')))
        throw BundleError(relativePath, 0, QString(),
                          QStringLiteral("resolves outside the bundle (a symbolic link?): refused, nothing read from it"));
    struct stat st {};
    if (::stat(QFile::encodeName(canonical).constData(), &st) != 0)
        throw BundleError(relativePath, 0, QString(), QStringLiteral("cannot read: %1").arg(QString::fromLocal8Bit(std::strerror(errno))));
    if (!S_ISREG(st.st_mode))
        throw BundleError(relativePath, 0, QString(),
                          QStringLiteral("not a regular file (a directory, pipe, socket or device): refused"));
    return canonical;
}

QByteArray BundleArchive::read(const QString &relativePath, qint64 maxBytes) const
{
    QByteArray data;
    readChunks(relativePath, maxBytes > 0 ? std::min(maxBytes, kMaxEntryBytes - 1) : kMaxEntryBytes - 1,
               [&data](const char *bytes, qint64 n) { data.append(bytes, static_cast<int>(n)); });
    return data;
}

void BundleArchive::readChunks(const QString &relativePath, qint64 maxBytes, const ChunkSink &sink) const
{
    const auto tooLarge = [&](qint64 size) {
        if (size > maxBytes)
            throw BundleError(relativePath, 0, QString(),
                              QStringLiteral("%1 bytes, more than the %2 this file may have: refused").arg(size).arg(maxBytes));
    };
    if (!isSafeRelativePath(relativePath))
        throw BundleError(relativePath, 0, QString(), QStringLiteral("unsafe path (absolute or '..'): refused"));
    constexpr qint64 kChunk = 1 << 20;
    QByteArray buffer(static_cast<int>(kChunk), Qt::Uninitialized);
    if (!m_zip) {
        QFile f(checkedFile(relativePath));
        tooLarge(f.size());
        if (!f.open(QIODevice::ReadOnly))
            throw BundleError(relativePath, 0, QString(), QStringLiteral("cannot read: %1").arg(f.errorString()));
        qint64 total = 0;
        for (;;) {
            const qint64 got = f.read(buffer.data(), kChunk);
            if (got < 0)
                throw BundleError(relativePath, 0, QString(), QStringLiteral("cannot read: %1").arg(f.errorString()));
            if (got == 0)
                break;
            total += got;
            tooLarge(total); // a file growing while it is read
            sink(buffer.constData(), got);
        }
        return;
    }
    const auto it = m_entries.constFind(relativePath);
    if (it == m_entries.cend())
        throw BundleError(relativePath, 0, QString(), QStringLiteral("missing from the bundle"));
    zip_stat_t st;
    zip_stat_init(&st);
    if (zip_stat_index(m_zip, static_cast<zip_uint64_t>(it.value()), 0, &st) != 0 || !(st.valid & ZIP_STAT_SIZE))
        throw BundleError(relativePath, 0, QString(), QStringLiteral("cannot stat zip entry: %1").arg(zipError(m_zip)));
    tooLarge(static_cast<qint64>(std::min<zip_uint64_t>(st.size, std::numeric_limits<qint64>::max())));
    zip_file_t *f = zip_fopen_index(m_zip, static_cast<zip_uint64_t>(it.value()), 0);
    if (!f)
        throw BundleError(relativePath, 0, QString(), QStringLiteral("cannot open zip entry: %1").arg(zipError(m_zip)));
    zip_uint64_t total = 0;
    zip_int64_t got = 0;
    try {
        // libzip compares the CRC only when a read reaches the end of the entry: read until a
        // read returns 0, one past the declared size.
        while ((got = zip_fread(f, buffer.data(), static_cast<zip_uint64_t>(kChunk))) > 0) {
            total += static_cast<zip_uint64_t>(got);
            if (total > st.size)
                break;
            sink(buffer.constData(), got);
        }
    } catch (...) {
        zip_fclose(f);
        throw;
    }
    const int readCode = zip_error_code_zip(zip_file_get_error(f));
    // libzip checks the CRC at the end of the data or when the entry is closed.
    const int closeCode = zip_fclose(f);
    if (got < 0 || total != st.size || closeCode != 0) {
        const int code = readCode != ZIP_ER_OK ? readCode : closeCode != 0 ? closeCode : ZIP_ER_EOF;
        QString why;
        if (code == ZIP_ER_CRC) {
            why = QStringLiteral("its data do not match the zip's checksum (CRC error): the zip is damaged");
        } else {
            zip_error_t ze;
            zip_error_init_with_code(&ze, code);
            why = QString::fromUtf8(zip_error_strerror(&ze));
            zip_error_fini(&ze);
        }
        throw BundleError(relativePath, 0, QString(), QStringLiteral("cannot read zip entry: %1").arg(why));
    }
}

void BundleArchive::write(const QString &relativePath, const QByteArray &data)
{
    if (!isSafeRelativePath(relativePath))
        throw BundleError(relativePath, 0, QString(), QStringLiteral("unsafe path (absolute or '..'): refused"));
    if (!m_zip) {
        const QString full = QDir(m_writeDir).filePath(relativePath);
        QDir().mkpath(QFileInfo(full).absolutePath());
        QFile f(full);
        errno = 0;
        bool ok = f.open(QIODevice::WriteOnly) && f.write(data) == data.size() && f.flush();
        f.close();
        ok = ok && f.error() == QFileDevice::NoError;
        if (!ok) // QFile says "Unknown error" for a full disk; errno says which
            throw BundleError(relativePath, 0, QString(),
                              QStringLiteral("cannot write: %1").arg(errno != 0 ? QString::fromLocal8Bit(std::strerror(errno)) : f.errorString()));
        return;
    }
    void *copy = std::malloc(static_cast<size_t>(std::max(1, data.size())));
    if (!copy)
        throw BundleError(relativePath, 0, QString(), QStringLiteral("out of memory"));
    std::memcpy(copy, data.constData(), static_cast<size_t>(data.size()));
    zip_source_t *src = zip_source_buffer(m_zip, copy, static_cast<zip_uint64_t>(data.size()), 1);
    if (!src) {
        std::free(copy);
        throw BundleError(relativePath, 0, QString(), QStringLiteral("cannot add to zip: %1").arg(zipError(m_zip)));
    }
    if (zip_file_add(m_zip, relativePath.toUtf8().constData(), src, ZIP_FL_ENC_UTF_8 | ZIP_FL_OVERWRITE) < 0) {
        zip_source_free(src);
        throw BundleError(relativePath, 0, QString(), QStringLiteral("cannot add to zip: %1").arg(zipError(m_zip)));
    }
}

void BundleArchive::writeChunks(const QString &relativePath, const ChunkProducer &produce)
{
    if (!isSafeRelativePath(relativePath))
        throw BundleError(relativePath, 0, QString(), QStringLiteral("unsafe path (absolute or '..'): refused"));
    std::unique_ptr<QTemporaryFile> spool;
    QFile plain;
    QFile *f = &plain;
    if (m_zip) {
        spool = std::make_unique<QTemporaryFile>(QFileInfo(m_path).absolutePath() + QStringLiteral("/.") + QFileInfo(m_path).fileName() +
                                                 QStringLiteral(".spool-XXXXXX"));
        f = spool.get();
    } else {
        const QString full = QDir(m_writeDir).filePath(relativePath);
        QDir().mkpath(QFileInfo(full).absolutePath());
        plain.setFileName(full);
    }
    const auto failed = [&]() {
        // QFile says "Unknown error" for a full disk; errno says which
        return BundleError(relativePath, 0, QString(),
                           QStringLiteral("cannot write: %1").arg(errno != 0 ? QString::fromLocal8Bit(std::strerror(errno)) : f->errorString()));
    };
    errno = 0;
    if (!(spool ? spool->open() : plain.open(QIODevice::WriteOnly)))
        throw failed();
    QByteArray chunk;
    for (;;) {
        chunk.clear();
        const bool more = produce(chunk);
        if (!chunk.isEmpty() && f->write(chunk) != chunk.size())
            throw failed();
        if (!more)
            break;
    }
    if (!f->flush())
        throw failed();
    const qint64 size = f->size();
    f->close();
    if (f->error() != QFileDevice::NoError)
        throw failed();
    if (!m_zip)
        return;
    zip_source_t *src = zip_source_file(m_zip, QFile::encodeName(spool->fileName()).constData(), 0, size);
    if (!src)
        throw BundleError(relativePath, 0, QString(), QStringLiteral("cannot add to zip: %1").arg(zipError(m_zip)));
    if (zip_file_add(m_zip, relativePath.toUtf8().constData(), src, ZIP_FL_ENC_UTF_8 | ZIP_FL_OVERWRITE) < 0) {
        zip_source_free(src);
        throw BundleError(relativePath, 0, QString(), QStringLiteral("cannot add to zip: %1").arg(zipError(m_zip)));
    }
    m_spool.push_back(std::move(spool)); // read by zip_close() in finish()
}

void BundleArchive::finish()
{
    if (m_mode != Mode::Write)
        return;
    if (!m_writeDir.isEmpty()) {
        if (QFileInfo::exists(m_path) || !QDir().rename(m_writeDir, m_path))
            throw BundleError(QFileInfo(m_path).fileName(), 0, QString(),
                              QStringLiteral("cannot move the written bundle into place at %1").arg(m_path));
        m_writeDir.clear();
        return;
    }
    if (!m_zip)
        return;
    if (zip_close(m_zip) != 0) {
        const QString what = zipError(m_zip);
        zip_discard(m_zip);
        m_zip = nullptr;
        m_spool.clear();
        throw BundleError(QFileInfo(m_path).fileName(), 0, QString(), QStringLiteral("cannot write zip: %1").arg(what));
    }
    m_zip = nullptr;
    m_spool.clear();
}

} // namespace driftlab
