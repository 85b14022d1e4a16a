#include "IrFrameCodec.h"

#include "StorageError.h"

#include <QBuffer>
#include <QImage>
#include <QImageReader>

#include <zlib.h>

#include <cstring>

namespace driftlab {

QByteArray IrFrameCodec::compress(const QVector<quint16> &pixels, int width, int height)
{
    const int n = width * height;
    QByteArray planes(2 * n, Qt::Uninitialized);
    char *lo = planes.data();
    char *hi = planes.data() + n;
    for (int y = 0; y < height; ++y) {
        quint16 prev = 0;
        for (int x = 0; x < width; ++x) {
            const int i = y * width + x;
            const quint16 d = static_cast<quint16>(pixels[i] - prev);
            prev = pixels[i];
            lo[i] = static_cast<char>(d & 0xff);
            hi[i] = static_cast<char>(d >> 8);
        }
    }
    // Huffman-only deflate: the delta planes have no long repeats worth LZ77 matching, and
    // entropy coding alone is both the smallest and the fastest here (see docs/storage.md).
    z_stream z{};
    if (deflateInit2(&z, Z_BEST_SPEED, Z_DEFLATED, 15, 8, Z_HUFFMAN_ONLY) != Z_OK)
        throw StorageError("zlib: cannot initialise deflate");
    QByteArray out(static_cast<int>(deflateBound(&z, static_cast<uLong>(planes.size()))), Qt::Uninitialized);
    z.next_in = reinterpret_cast<Bytef *>(planes.data());
    z.avail_in = static_cast<uInt>(planes.size());
    z.next_out = reinterpret_cast<Bytef *>(out.data());
    z.avail_out = static_cast<uInt>(out.size());
    const int rc = deflate(&z, Z_FINISH);
    const auto size = static_cast<int>(z.total_out);
    deflateEnd(&z);
    if (rc != Z_STREAM_END)
        throw StorageError("zlib: deflate of an infrared frame failed");
    out.resize(size);
    return out;
}

QVector<quint16> IrFrameCodec::decompress(const QByteArray &blob, int width, int height, const QString &what)
{
    const qint64 n64 = static_cast<qint64>(width) * height;
    const int n = n64 <= kMaxPixels ? static_cast<int>(n64) : 0;
    QByteArray planes;
    if (width > 0 && height > 0 && n64 <= kMaxPixels) {
        planes.resize(2 * n);
        z_stream z{};
        if (inflateInit(&z) != Z_OK)
            throw StorageError("zlib: cannot initialise inflate");
        z.next_in = reinterpret_cast<Bytef *>(const_cast<char *>(blob.constData()));
        z.avail_in = static_cast<uInt>(blob.size());
        z.next_out = reinterpret_cast<Bytef *>(planes.data());
        z.avail_out = static_cast<uInt>(planes.size());
        const int rc = inflate(&z, Z_FINISH);
        const bool ok = rc == Z_STREAM_END && z.total_out == static_cast<uLong>(planes.size());
        inflateEnd(&z);
        if (!ok)
            planes.clear();
    }
    if (width <= 0 || height <= 0 || planes.size() != 2 * n)
        throw StorageError(QStringLiteral("%1: infrared frame blob does not decode to %2 x %3 pixels")
                               .arg(what)
                               .arg(width)
                               .arg(height)
                               .toStdString());
    QVector<quint16> pixels(n);
    const auto *lo = reinterpret_cast<const unsigned char *>(planes.constData());
    const auto *hi = lo + n;
    for (int y = 0; y < height; ++y) {
        quint16 prev = 0;
        for (int x = 0; x < width; ++x) {
            const int i = y * width + x;
            prev = static_cast<quint16>(prev + (lo[i] | (hi[i] << 8)));
            pixels[i] = prev;
        }
    }
    return pixels;
}

QByteArray IrFrameCodec::toPng(const QVector<quint16> &pixels, int width, int height)
{
    QImage image(width, height, QImage::Format_Grayscale16);
    for (int y = 0; y < height; ++y)
        std::memcpy(image.scanLine(y), pixels.constData() + y * width, static_cast<size_t>(width) * 2);
    QByteArray out;
    QBuffer buffer(&out);
    buffer.open(QIODevice::WriteOnly);
    if (!image.save(&buffer, "PNG"))
        throw StorageError("cannot encode a 16-bit PNG frame");
    return out;
}

bool IrFrameCodec::fromImageFile(const QByteArray &data, const QString &fileName, QVector<quint16> &pixels, int &width,
                                 int &height, QString &error)
{
    const QString lower = fileName.toLower();
    const bool tiff = lower.endsWith(QLatin1String(".tif")) || lower.endsWith(QLatin1String(".tiff"));
    if (tiff && !QImageReader::supportedImageFormats().contains("tiff")) {
        error = QStringLiteral("TIFF frames need Qt's TIFF image plugin (Debian package qt5-image-formats-plugins)");
        return false;
    }
    if (data.isEmpty()) {
        error = QStringLiteral("empty image file");
        return false;
    }
    QBuffer buffer;
    buffer.setData(data);
    buffer.open(QIODevice::ReadOnly);
    QImageReader reader(&buffer, tiff ? QByteArray("tiff") : QByteArray("png"));
    const QSize declared = reader.size(); // from the header, nothing decoded yet
    if (declared.isValid() && static_cast<qint64>(declared.width()) * declared.height() > kMaxPixels) {
        error = QStringLiteral("declares %1 x %2 pixels, more than the %3 pixels (4096 x 4096) a frame may have")
                    .arg(declared.width())
                    .arg(declared.height())
                    .arg(kMaxPixels);
        return false;
    }
    QImage image;
    if (!reader.read(&image)) {
        error = QStringLiteral("cannot decode image: %1").arg(reader.errorString());
        return false;
    }
    if (image.format() != QImage::Format_Grayscale16) {
        error = QStringLiteral("not a 16-bit single-channel image (depth %1 bits, %2)")
                    .arg(image.depth())
                    .arg(image.isGrayscale() ? QStringLiteral("grayscale") : QStringLiteral("colour"));
        return false;
    }
    width = image.width();
    height = image.height();
    pixels.resize(width * height);
    for (int y = 0; y < height; ++y)
        std::memcpy(pixels.data() + y * width, image.constScanLine(y), static_cast<size_t>(width) * 2);
    return true;
}

} // namespace driftlab
