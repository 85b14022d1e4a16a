// libFuzzer harness: events.csv of a recording bundle (docs/recording-bundle.md).
#include "BundleFileHarness.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return fuzz::readBundleWith("events.csv", data, size);
}
