#pragma once
// Reads and validates a recording bundle (docs/recording-bundle.md, version 1)
// completely before anything is imported: every CSV cell is parsed and every frame decoded.

#include "BundleArchive.h"
#include "StorageTypes.h"

#include <QJsonObject>
#include <QString>
#include <QVector>

#include <memory>

namespace driftlab {

struct BundleContent {
    QJsonObject manifest;
    SessionInfo session;                  // complete = true
    QVector<ChannelInfo> channels;        // manifest order
    QVector<SampleBlock> samples;         // per channel, same order
    QVector<InterferometerPoint> interferometer;
    QVector<EventRecord> events;
    QVector<IrFrame> frames;              // without pixels; sourceName = bundle-relative file
};

class BundleReader {
public:
    // Opens and validates the bundle at path (directory or .zip). Throws BundleError naming
    // file, line and field of the first problem.
    explicit BundleReader(const QString &path);
    ~BundleReader();

    const BundleContent &content() const { return m_content; }
    // Frame i with its pixels (decoded again from the bundle).
    IrFrame frame(int i) const;
    // SHA-256 of the recorded content (session start, channel ids and samples, interferometer
    // points, events, frame times and sizes), independent of CSV number formatting and of
    // directory vs .zip; also in content().session.contentSha256 (hex). Name, operator and
    // notes are not part of it: a renamed copy of a recording is still the same recording.
    QByteArray contentHash() const;

private:
    void readManifest();
    void readChannels();
    void readInterferometer(const QString &file);
    void readEvents(const QString &file);
    void readFrames(const QString &file);

    std::unique_ptr<BundleArchive> m_archive;
    BundleContent m_content;
};

} // namespace driftlab
