// libFuzzer harness: a compensation register map file (docs/export.md, "Live compensation
// loop") as OffsetRegisterMap reads it. What it accepts must encode and decode offsets exactly.
#include "FuzzSupport.h"
#include "JsonFields.h"
#include "OffsetRegisterMap.h"

#include <QJsonDocument>
#include <QJsonObject>

#include <cmath>
#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz::ensureApp();
    const QJsonDocument doc = QJsonDocument::fromJson(fuzz::bytes(data, size));
    if (!doc.isObject())
        return 0;
    try {
        driftlab::JsonFields f(doc.object(), QStringLiteral("map.json"));
        const driftlab::OffsetRegisterMap map = driftlab::OffsetRegisterMap::fromJson(f);
        if (map.axes.isEmpty())
            std::abort();
        for (int i = 0; i < map.axes.size(); ++i)
            for (int j = i + 1; j < map.axes.size(); ++j)
                if (std::abs(map.axes[i].address - map.axes[j].address) < 2)
                    std::abort(); // overlapping pairs must have been refused
        for (double offset : {0.0, 1.0, -1.0, 12.0, -250.0}) {
            const double q = map.quantised(offset);
            const QVector<quint16> w = map.words(q);
            if (w.size() != 2 || std::abs(map.offsetOf(w[0], w[1]) - q) > 1e-9 * std::max(1.0, std::abs(q)))
                std::abort();
        }
    } catch (const std::invalid_argument &) {
    } catch (const std::out_of_range &) {
    }
    return 0;
}
