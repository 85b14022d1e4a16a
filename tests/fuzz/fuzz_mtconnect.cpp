// libFuzzer harness: an MTConnect agent's response (streams or error document), which
// DriftLab reads from the network.
#include "FuzzSupport.h"
#include "MtconnectStreams.h"

#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz::ensureApp();
    try {
        driftlab::MtconnectStreams::parse(fuzz::bytes(data, size), QStringLiteral("agent"));
    } catch (const std::invalid_argument &) {
    }
    return 0;
}
