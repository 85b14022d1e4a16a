// libFuzzer harness: a Renishaw-style .rtl linear test file (docs/acquisition.md).
#include "FuzzSupport.h"
#include "RtlFile.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz::ensureApp();
    try {
        driftlab::RtlFile::parse(fuzz::bytes(data, size), QStringLiteral("test.rtl"));
    } catch (const driftlab::RtlError &) {
    }
    return 0;
}
