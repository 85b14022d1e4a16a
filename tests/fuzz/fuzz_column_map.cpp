// libFuzzer harness: a CSV column map (docs/csv-import.md), then the map applied to a small
// table so that whatever the map accepts is also exercised by the row decoder.
#include "CsvColumnMap.h"
#include "CsvError.h"
#include "CsvReader.h"
#include "CsvRowDecoder.h"
#include "FuzzSupport.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz::ensureApp();
    try {
        const driftlab::CsvColumnMap map = driftlab::CsvColumnMap::fromJson(fuzz::bytes(data, size), QStringLiteral("map.json"));
        // A run column ("run") too, for maps that split the table into sessions.
        static const QByteArray table = "time_s,run,spindle_rpm,ch1_um,t1\n0,A,0,0.0,20.1\n15,A,1250,1.5,20.4\n0,B,1250,2.5,20.9\n"
                                        "30,A,1250,2.6,21.0\n";
        driftlab::CsvRowDecoder decoder(map, QStringLiteral("data.csv"));
        for (const driftlab::CsvRecord &r : driftlab::CsvReader::parse(table, QStringLiteral("data.csv"), map.separator))
            decoder.accept(r);
        (void)map.startFromFileName(QStringLiteral("log_20250301_081500.csv")); // the file-name start pattern
        (void)decoder.runs();
    } catch (const driftlab::StorageError &) {
    }
    return 0;
}
