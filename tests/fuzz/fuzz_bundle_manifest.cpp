// libFuzzer harness: manifest.json of a recording bundle (docs/recording-bundle.md).
#include "BundleFileHarness.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return fuzz::readBundleWith("manifest.json", data, size);
}
