#pragma once
// The line protocol of a serial instrument, described in the rig file: how one text line
// becomes values of the instrument's channels. Three ways to find a value in a line:
//   "regex":  a regular expression; each channel names its capture group (number or name,
//             default: the group named like the channel)
//   "split":  fields separated by "separator" (default: whitespace); channels pick "field" (0-based)
//   "fixed":  fixed columns; channels pick "start" and "length" (characters)
// Each channel: value = number * scale + offset in its unit; "invalid" lists texts the
// instrument prints for no valid value (e.g. "OVER", "----"), which become gaps. A line the
// protocol does not recognise is reported, never turned into numbers.
// Optional "request": text sent to poll the instrument ("\r" and "\n" escapes allowed).
// fromJson() and parse() are plain functions (fuzzable).

#include "JsonFields.h"
#include "StorageTypes.h"

#include <QRegularExpression>
#include <QVector>

#include <optional>

namespace driftlab {

class LineProtocol {
public:
    enum class Mode { Regex, Split, Fixed };
    struct Channel {
        ChannelInfo info;
        QString group;      // regex: capture group name, or its number as text
        int field = 0;      // split
        int start = 0;      // fixed
        int length = 0;     // fixed
        double scale = 1.0;
        double offset = 0.0;
        QStringList invalid;
    };
    struct Value {
        bool valid = false;
        double value = 0.0;
        QString text;       // the field as found
    };
    // nullopt: the line is not one of the instrument's data lines.
    using Result = std::optional<QVector<Value>>;

    static LineProtocol fromJson(JsonFields &protocol);
    Result parse(const QString &line) const;

    Mode mode() const { return m_mode; }
    const QVector<Channel> &channels() const { return m_channels; }
    QVector<ChannelInfo> channelInfos() const;
    QByteArray request() const { return m_request; }

private:
    Mode m_mode = Mode::Split;
    QRegularExpression m_regex;
    QString m_separator;    // empty: whitespace
    QByteArray m_request;
    QVector<Channel> m_channels;
};

} // namespace driftlab
