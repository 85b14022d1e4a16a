#pragma once
// What a device hands to the recorder in one piece: samples of each of its channels
// (session-clock seconds), and the non-scalar records some instruments produce.

#include "StorageTypes.h"

#include <QVector>

namespace driftlab {

struct DeviceBlock {
    int device = -1;                    // index of the device in its engine / recording
    QVector<SampleBlock> channels;      // one per channel of the device, in its channel order
    QVector<IrFrame> frames;
    QVector<InterferometerPoint> points;
    QVector<EventRecord> events;
    bool empty() const
    {
        for (const SampleBlock &b : channels)
            if (!b.t.isEmpty())
                return false;
        return frames.isEmpty() && points.isEmpty() && events.isEmpty();
    }
};

} // namespace driftlab
