// libFuzzer harness: a batch job file (docs/batch.md) as 'driftlab-cli batch' reads it.
#include "BatchJob.h"
#include "CliCommand.h"
#include "FuzzSupport.h"

#include <QFileInfo>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz::ensureApp();
    // Next to a copy of the example bundle, so that "bundles": ["example.bundle"] and
    // "bundle_folder": "." name something real.
    const QString path = QFileInfo(fuzz::exampleBundle()).path() + QStringLiteral("/job.json");
    fuzz::writeFile(path, fuzz::bytes(data, size));
    try {
        driftlab::BatchJob::read(path);
    } catch (const driftlab::UsageError &) {
    }
    return 0;
}
