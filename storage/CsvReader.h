#pragma once
// Streaming CSV tokenizer: bytes in (in chunks of any size), records out, in bounded memory.
// It knows separators, RFC 4180 quotes (a quoted field may hold separators, quotes as "" and
// line breaks), LF / CRLF / CR line ends and a UTF-8 byte-order mark; it refuses what is not a
// text table (UTF-16/32, NUL bytes, an unterminated quote, a record longer than the limit)
// with a CsvError naming file, line and column. Fields stay raw bytes: decoding text and
// numbers is the caller's job. Empty lines yield no record.

#include "CsvError.h"

#include <QByteArray>
#include <QString>
#include <QVector>

#include <functional>

namespace driftlab {

struct CsvRecord {
    qint64 line = 0;            // line the record starts on (1-based, counting every line)
    QVector<QByteArray> fields; // unquoted; surrounding spaces kept
};

class CsvReader {
public:
    using Sink = std::function<void(const CsvRecord &)>;
    static constexpr int kDefaultMaxRecordBytes = 1 << 20;

    CsvReader(const QString &fileName, char separator = ',', int maxRecordBytes = kDefaultMaxRecordBytes);

    // Tokenizes the next chunk; every completed record goes to sink (which may throw to stop).
    void feed(const char *data, qint64 size, const Sink &sink);
    void feed(const QByteArray &data, const Sink &sink) { feed(data.constData(), data.size(), sink); }
    // End of input: completes a last record without a line break. Throws CsvError for an
    // unterminated quoted field.
    void finish(const Sink &sink);
    // The whole text at once (tests, previews, fuzzing).
    static QVector<CsvRecord> parse(const QByteArray &data, const QString &fileName, char separator = ',');

    qint64 bytesConsumed() const { return m_consumed; }

private:
    enum class State { FieldStart, Unquoted, Quoted, QuoteInQuoted };
    void endField();
    void endRecord(const Sink &sink);
    [[noreturn]] void fail(const QString &what) const;

    QString m_fileName;
    char m_separator;
    int m_maxRecordBytes;
    State m_state = State::FieldStart;
    bool m_afterCr = false;    // the previous byte was a CR ending a line
    int m_bomSeen = 0;         // bytes of a leading UTF-8 BOM matched so far (-1: done)
    qint64 m_consumed = 0;
    qint64 m_line = 1;         // current physical line
    qint64 m_recordBytes = 0;
    QByteArray m_field;
    CsvRecord m_record;
};

} // namespace driftlab
