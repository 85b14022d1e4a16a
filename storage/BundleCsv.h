#pragma once
// The CSV files of a recording bundle (channels.csv, interferometer.csv, events.csv,
// ir/index.csv; docs/recording-bundle.md), read as a stream: feed() takes the file in chunks
// and hands over each complete record, so memory does not grow with the file. RFC 4180
// quotes are allowed, with line breaks inside them (event labels); a record's number is the
// line it starts on; blank lines are skipped; a record longer than kMaxLineBytes is refused as
// soon as it gets that long. Problems are BundleErrors naming the file, line and field.

#include <QByteArray>
#include <QHash>
#include <QString>
#include <QStringList>
#include <QVector>

#include <functional>

namespace driftlab {

class BundleCsv {
public:
    // Longest record (header included) a bundle may have: 1 MiB holds 10,000 channels.
    static constexpr int kMaxLineBytes = 1 << 20;

    struct Line {
        int number = 0;
        QVector<QByteArray> fields;
        int span = 1; // lines of the file (more when a quoted field holds line breaks)
    };
    using Sink = std::function<void(const Line &)>;

    explicit BundleCsv(const QString &name) : m_name(name) {}
    const QString &name() const { return m_name; }

    void feed(const char *data, qint64 size, const Sink &sink);
    // End of the file: hands over a last record without a line break; an empty file is an error.
    void finish(const Sink &sink);

    // Column index of each required header name (throws if one is missing, duplicated or
    // unknown); optional ones absent give -1.
    QHash<QString, int> header(const Line &h, const QStringList &required, const QStringList &optional) const;
    // Throws unless the record has width fields (with a hint when a quote spans lines).
    void checkWidth(const Line &line, int width) const;

private:
    void complete(const Sink &sink);
    QVector<QByteArray> split(const QByteArray &record, int lineNo) const;

    QString m_name;
    QByteArray m_record; // the record read so far
    bool m_quoted = false;
    bool m_blank = true;
    int m_breaks = 0;    // line breaks inside quotes in m_record
    int m_lineNo = 1;    // line the current record starts on
    bool m_any = false;  // a record was handed over
};

} // namespace driftlab
