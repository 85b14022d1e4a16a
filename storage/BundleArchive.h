#pragma once
// File access to a recording bundle: a directory or a .zip of it (libzip), for reading or
// writing. Zip entries with absolute paths, '..' components or backslashes are refused.

#include <QByteArray>
#include <QHash>
#include <QString>
#include <QStringList>

#include <functional>

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
};

} // namespace driftlab
