#pragma once
// Incremental SHA-256 through OpenSSL's libcrypto (SHA-NI where the CPU has it: about 1.8 GB/s
// on the 2-core development machine against 177 MB/s for QCryptographicHash's portable code,
// which made hashing a 1 GB session for a push's verification take longer than sending it).

#include <QByteArray>
#include <QString>

#include <memory>

namespace driftlab {

class Sha256 {
public:
    Sha256();
    ~Sha256();
    Sha256(const Sha256 &) = delete;
    Sha256 &operator=(const Sha256 &) = delete;

    void add(const void *data, size_t size);
    void add(const QByteArray &bytes) { add(bytes.constData(), static_cast<size_t>(bytes.size())); }
    // The digest of everything added; the object is spent afterwards.
    QByteArray result();
    QString hex() { return QString::fromLatin1(result().toHex()); }

    static QByteArray of(const QByteArray &bytes);

private:
    struct Context;
    std::unique_ptr<Context> m_ctx;
};

} // namespace driftlab
