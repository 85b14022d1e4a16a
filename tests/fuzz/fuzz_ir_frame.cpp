// libFuzzer harness: an infrared frame file (16-bit PNG, docs/recording-bundle.md) as import
// decodes it, and the same bytes as a stored frame blob (a damaged database) as review reads it.
#include "FuzzSupport.h"
#include "IrFrameCodec.h"
#include "StorageError.h"

using driftlab::IrFrameCodec;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz::ensureApp();
    const QByteArray in = fuzz::bytes(data, size);
    QVector<quint16> pixels;
    int width = 0;
    int height = 0;
    QString error;
    if (IrFrameCodec::fromImageFile(in, QStringLiteral("frame.png"), pixels, width, height, error)) {
        // Whatever import accepts must be storable and read back exactly.
        if (width <= 0 || height <= 0 || static_cast<qint64>(width) * height > IrFrameCodec::kMaxPixels ||
            pixels.size() != width * height)
            std::abort();
        if (IrFrameCodec::decompress(IrFrameCodec::compress(pixels, width, height), width, height, QStringLiteral("frame")) != pixels)
            std::abort();
    } else if (error.isEmpty()) {
        std::abort(); // a refusal must say why
    }
    if (size >= 2) {
        try {
            IrFrameCodec::decompress(in.mid(2), 1 + data[0] % 64, 1 + data[1] % 64, QStringLiteral("blob"));
        } catch (const driftlab::StorageError &) {
        }
    }
    return 0;
}
