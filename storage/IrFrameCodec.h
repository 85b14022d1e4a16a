#pragma once
// Lossless codecs of 16-bit infrared frames.
//
// Store encoding "d16p-zlib": each row is delta-coded from its left neighbour (mod 2^16),
// the deltas are split into a low-byte plane and a high-byte plane (all low bytes, then all
// high bytes) and the planes are one zlib stream (RFC 1950; Huffman-only deflate). Bundle encoding: 16-bit grayscale PNG through QImage
// (Format_Grayscale16); TIFF only if Qt's TIFF plugin (qt5-image-formats-plugins) is installed.

#include <QByteArray>
#include <QString>
#include <QVector>

namespace driftlab {

class IrFrameCodec {
public:
    static QString storeEncoding() { return QStringLiteral("d16p-zlib"); }
    // The largest frame DriftLab imports, stores and reads back (4096 x 4096 pixels: thermal
    // cameras have 640 x 512 or 1280 x 1024). A file declaring more is refused before decoding.
    static constexpr int kMaxPixels = 4096 * 4096;
    static QByteArray compress(const QVector<quint16> &pixels, int width, int height);
    // Throws StorageError naming `what` if the blob does not decode to width * height pixels.
    static QVector<quint16> decompress(const QByteArray &blob, int width, int height, const QString &what);

    static QByteArray toPng(const QVector<quint16> &pixels, int width, int height);
    // Decodes a 16-bit single-channel image (PNG, or TIFF with the plugin) of at most
    // kMaxPixels (checked on the size its header declares, before decoding). On failure
    // returns false and sets error (what is wrong, without the file name).
    static bool fromImageFile(const QByteArray &data, const QString &fileName, QVector<quint16> &pixels, int &width,
                              int &height, QString &error);
};

} // namespace driftlab
