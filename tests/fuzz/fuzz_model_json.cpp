// libFuzzer harness: a model JSON (docs/datadriven.md, docs/export.md) as export-model,
// simulate and the Export dialog read it: the exportable-model reader, and the data-driven
// model reader.
#include "DataDrivenModelJson.h"
#include "ExportableModelJson.h"
#include "FuzzSupport.h"

#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz::ensureApp();
    const QByteArray in = fuzz::bytes(data, size);
    try {
        driftlab::ExportableModelJson::parse(in, QStringLiteral("model.json"));
    } catch (const std::invalid_argument &) {
    }
    try {
        driftlab::DataDrivenModelJson::parse(in, QStringLiteral("model.json"));
    } catch (const std::invalid_argument &) {
    }
    return 0;
}
