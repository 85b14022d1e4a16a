#pragma once
// File access to a recording bundle: a directory or a .zip of it (libzip), for reading or
// writing. Zip entries with absolute paths, '..' components or backslashes are refused.

#include <QByteArray>
#include <QHash>
#include <QString>
#include <QStringList>

#include <functional>
#include <memory>
#include <vector>

class QTemporaryFile;

struct zip;

namespace driftlab {

class BundleArchive {
public:
    enum class Mode { Read, Write };
    // Read: path is a bundle directory or a .zip (the bundle at the root or in one top-level
    // folder). Write: creates the directory or .zip, which must not exist yet. Throws BundleError.
    BundleArchive(const QString &path, Mode mode);
    ~BundleArchive();
    BundleArchive(const BundleArchive &) = delete;
    BundleArchive &operator=(const BundleArchive &) = delete;

    bool isZip() const { return m_zip != nullptr; }
    bool exists(const QString &relativePath) const;
    // Throws BundleError naming the file if it is missing, unreadable or (maxBytes > 0) larger
    // than maxBytes, checked before reading.
    QByteArray read(const QString &relativePath, qint64 maxBytes = 0) const;
    // The same in chunks of at most 1 MiB, for files too large to hold (channels.csv): memory
    // does not grow with the file. A damaged zip entry (CRC) is reported after its last chunk.
    using ChunkSink = std::function<void(const char *data, qint64 size)>;
    void readChunks(const QString &relativePath, qint64 maxBytes, const ChunkSink &sink) const;
    void write(const QString &relativePath, const QByteArray &data);
    // The same for a file too large to hold (channels.csv of a long session): `produce` is
    // called until it returns false, each call filling `chunk` (emptied before each call),
    // which is written at once; memory holds one chunk. A zip gets the file through a hidden
    // spool file next to it, removed by finish() or when the archive is dropped.
    using ChunkProducer = std::function<bool(QByteArray &chunk)>;
    void writeChunks(const QString &relativePath, const ChunkProducer &produce);
    // Writes the zip's central directory, or moves the written directory into place (Write
    // mode); throws BundleError on failure. Without finish() nothing written stays.
    void finish();

    // True for a safe bundle-relative path: not empty, not absolute, no '..', no backslash.
    static bool isSafeRelativePath(const QString &path);

private:
    // Directory bundles: the canonical path of a regular file of the bundle, after refusing a
    // missing file, anything resolving outside the bundle (symbolic links), anything that is
    // not a regular file (a pipe would block, a device never ends).
    QString checkedFile(const QString &relativePath) const;

    QString m_path;
    QString m_root;                    // directory: canonical bundle path
    QString m_writeDir;                // directory being written (renamed to m_path by finish())
    Mode m_mode;
    zip *m_zip = nullptr;
    QString m_prefix;                  // zip: top-level folder holding manifest.json, with '/'
    QHash<QString, qint64> m_entries;  // zip: bundle-relative name -> entry index
    std::vector<std::unique_ptr<QTemporaryFile>> m_spool; // zip: files zip_close() still reads
};

} // namespace driftlab
