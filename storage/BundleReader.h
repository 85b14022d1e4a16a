#pragma once
// Reads and validates a recording bundle (docs/recording-bundle.md, version 1)
// completely before anything is imported: every CSV cell is parsed and every frame decoded.

#include "BundleArchive.h"
#include "BundleCsv.h"
#include "StorageTypes.h"

#include <QJsonObject>
#include <QString>
#include <QVector>

#include <functional>
#include <memory>

namespace driftlab {

struct BundleContent {
    QJsonObject manifest;
    SessionInfo session;                  // complete = true
    QVector<ChannelInfo> channels;        // manifest order
    QVector<SampleBlock> samples;         // per channel, same order (empty with a SampleSink)
    QVector<InterferometerPoint> interferometer;
    QVector<EventRecord> events;
    QVector<IrFrame> frames;              // without pixels; sourceName = bundle-relative file
};

class BundleReader {
public:
    // Receives the samples of channels.csv in chunks (per channel, manifest order, about a
    // million samples at a time) while the file is read; content holds the manifest, session
    // and channels already. Whatever it throws stops the reading.
    using SampleSink = std::function<void(const BundleContent &content, const QVector<SampleBlock> &chunk)>;

    // Opens and validates the bundle at path (directory or .zip). Throws BundleError naming
    // file, line and field of the first problem. Without a sink every sample is kept in
    // content().samples and content().session.contentSha256 is set; with one the samples
    // go to the sink (memory does not grow with channels.csv) and the hash is left empty:
    // the caller computes it from where the samples went (contentHash(content, source)).
    explicit BundleReader(const QString &path, SampleSink sink = SampleSink());
    ~BundleReader();

    const BundleContent &content() const { return m_content; }
    // Frame i with its pixels (decoded again from the bundle).
    IrFrame frame(int i) const;
    // SHA-256 of the recorded content (session start, channel ids and samples, interferometer
    // points, events, frame times and sizes), independent of CSV number formatting and of
    // directory vs .zip; also in content().session.contentSha256 (hex). Name, operator and
    // notes are not part of it: a renamed copy of a recording is still the same recording.
    QByteArray contentHash() const;
    // The same hash with the samples read from elsewhere (a store), block by block.
    using BlockVisitor = std::function<void(const QVector<double> &t, const QVector<double> &v)>;
    struct SampleSource {
        std::function<qint64(int channel)> count;
        std::function<void(int channel, const BlockVisitor &visit)> forEachBlock; // in time order
    };
    static QByteArray contentHash(const BundleContent &content, const SampleSource &samples);

private:
    void readManifest();
    void readChannels();
    void readInterferometer(const QString &file);
    void readEvents(const QString &file);
    void readFrames(const QString &file);
    void readCsv(const QString &file, qint64 maxBytes, const std::function<void(const BundleCsv &, const BundleCsv::Line &)> &each);

    std::unique_ptr<BundleArchive> m_archive;
    BundleContent m_content;
    SampleSink m_sink;
};

} // namespace driftlab
