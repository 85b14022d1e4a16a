// libFuzzer harness: a CSV file imported with the shipped FL_THERMAL column map
// (resources/maps/fl_thermal.json): tokenizer and row decoder, as import-csv runs them.
#include "CsvColumnMap.h"
#include "CsvError.h"
#include "CsvReader.h"
#include "CsvRowDecoder.h"
#include "FuzzSupport.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz::ensureApp();
    static const driftlab::CsvColumnMap map =
        driftlab::CsvColumnMap::load(QStringLiteral(DRIFTLAB_SOURCE_DIR "/resources/maps/fl_thermal.json"));
    try {
        driftlab::CsvRowDecoder decoder(map, QStringLiteral("data.csv"));
        driftlab::CsvReader reader(QStringLiteral("data.csv"), map.separator);
        const auto sink = [&](const driftlab::CsvRecord &r) { decoder.accept(r); };
        // Fed in two chunks split at a byte the input chooses: records across chunk borders.
        const size_t split = size > 0 ? data[0] % (size + 1) : 0;
        reader.feed(reinterpret_cast<const char *>(data), static_cast<qint64>(split), sink);
        reader.feed(reinterpret_cast<const char *>(data) + split, static_cast<qint64>(size - split), sink);
        reader.finish(sink);
    } catch (const driftlab::StorageError &) {
    }
    return 0;
}
