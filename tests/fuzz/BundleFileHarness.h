#pragma once
// A bundle harness: the example bundle with one of its files replaced by the fuzzed bytes,
// read and validated whole by BundleReader (every cell parsed, every frame decoded).

#include "BundleReader.h"
#include "FuzzSupport.h"
#include "StorageError.h"

namespace fuzz {

inline int readBundleWith(const char *file, const uint8_t *data, size_t size)
{
    ensureApp();
    const QString bundle = exampleBundle();
    const QString path = bundle + QLatin1Char('/') + QLatin1String(file);
    static const QByteArray original = [&] {
        QFile f(path);
        return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
    }();
    writeFile(path, bytes(data, size));
    try {
        driftlab::BundleReader reader(bundle);
        for (int i = 0; i < reader.content().frames.size(); ++i)
            reader.frame(i);
        reader.contentHash();
    } catch (const driftlab::StorageError &) {
        // refused with file, line and field: expected
    }
    writeFile(path, original);
    return 0;
}

} // namespace fuzz
