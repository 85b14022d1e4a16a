// libFuzzer harness: a rig file (docs/acquisition.md): rig, programme, effects and the device
// section with Modbus register maps, serial line protocols, cameras and MTConnect agents.
#include "FuzzSupport.h"
#include "RigConfigLoader.h"

#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz::ensureApp();
    try {
        const driftlab::RigConfig config = driftlab::RigConfigLoader::fromText(fuzz::bytes(data, size), QStringLiteral("rig.json"));
        // What is accepted is written back and read again to the same configuration.
        const QJsonObject again = driftlab::RigConfigLoader::toJson(driftlab::RigConfigLoader::fromJson(
            driftlab::RigConfigLoader::toJson(config), QStringLiteral("rig.json (written)")));
        if (again != driftlab::RigConfigLoader::toJson(config))
            std::abort();
    } catch (const std::invalid_argument &) {
    } catch (const std::runtime_error &) {
    }
    return 0;
}
