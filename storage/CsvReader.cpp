#include "CsvReader.h"

namespace driftlab {

namespace {
const char kBom[3] = {'\xEF', '\xBB', '\xBF'};
} // namespace

CsvReader::CsvReader(const QString &fileName, char separator, int maxRecordBytes)
    : m_fileName(fileName), m_separator(separator), m_maxRecordBytes(maxRecordBytes)
{
    if (separator == '"' || separator == '\r' || separator == '\n' || separator == '\0')
        throw CsvError(fileName, 0, 0, QStringLiteral("separator"), QStringLiteral("cannot be a quote, a line break or NUL"));
}

void CsvReader::fail(const QString &what) const
{
    throw CsvError(m_fileName, m_line, static_cast<int>(m_record.fields.size()) + 1, QString(), what);
}

void CsvReader::endField()
{
    m_record.fields.push_back(m_field);
    m_field.clear();
}

void CsvReader::endRecord(const Sink &sink)
{
    m_state = State::FieldStart;
    m_recordBytes = 0;
    CsvRecord done;
    done.line = m_record.line;
    done.fields.swap(m_record.fields);
    sink(done);
}

void CsvReader::feed(const char *data, qint64 size, const Sink &sink)
{
    for (qint64 k = 0; k < size; ++k) {
        const char c = data[k];
        ++m_consumed;
        if (m_bomSeen >= 0) {
            if (c == kBom[m_bomSeen]) {
                if (++m_bomSeen == 3)
                    m_bomSeen = -1;
                continue;
            }
            if (m_bomSeen == 0 && (c == '\xFF' || c == '\xFE'))
                throw CsvError(m_fileName, 1, 0, QString(),
                               QStringLiteral("UTF-16 or UTF-32 text (byte-order mark): save the file as UTF-8 or an 8-bit encoding"));
            const int held = m_bomSeen;
            m_bomSeen = -1;
            m_consumed -= held + 1;
            feed(kBom, held, sink); // not a BOM after all: those bytes are data
            feed(&c, 1, sink);
            continue;
        }
        if (c == '\0')
            fail(QStringLiteral("NUL byte: not a text table (a UTF-16 file must be saved as UTF-8)"));
        const bool lineEnd = c == '\n' || c == '\r';
        if (m_afterCr) {
            m_afterCr = false;
            if (c == '\n')
                continue; // CRLF: the line was ended by the CR
        }
        if (m_state != State::FieldStart || !m_record.fields.isEmpty() || !lineEnd) {
            if (m_state == State::FieldStart && m_record.fields.isEmpty() && m_field.isEmpty())
                m_record.line = m_line;
            if (++m_recordBytes > m_maxRecordBytes)
                fail(QStringLiteral("record longer than %1 bytes: not a text table, or a quote left open").arg(m_maxRecordBytes));
        }
        switch (m_state) {
        case State::Quoted:
            if (c == '"') {
                m_state = State::QuoteInQuoted;
            } else {
                m_field += lineEnd ? '\n' : c; // a line break inside quotes reads as LF
                if (lineEnd) {
                    ++m_line;
                    m_afterCr = c == '\r';
                }
            }
            break;
        case State::QuoteInQuoted:
            if (c == '"') {
                m_field += '"';
                m_state = State::Quoted;
            } else if (c == m_separator) {
                endField();
                m_state = State::FieldStart;
            } else if (lineEnd) {
                endField();
                endRecord(sink);
                ++m_line;
                m_afterCr = c == '\r';
            } else if (c != ' ' && c != '\t') {
                fail(QStringLiteral("unexpected '%1' after a closing quote").arg(QChar::fromLatin1(c)));
            }
            break;
        case State::FieldStart:
        case State::Unquoted:
            if (c == m_separator) {
                endField();
                m_state = State::FieldStart;
            } else if (lineEnd) {
                if (m_state == State::Unquoted || !m_record.fields.isEmpty()) {
                    endField();
                    endRecord(sink);
                } // else: an empty line, no record
                ++m_line;
                m_afterCr = c == '\r';
            } else if (c == '"' && m_field.trimmed().isEmpty()) {
                m_field.clear(); // spaces before an opening quote are not data
                m_state = State::Quoted;
            } else {
                m_field += c;
                m_state = State::Unquoted;
            }
            break;
        }
    }
}

void CsvReader::finish(const Sink &sink)
{
    if (m_bomSeen > 0) { // a file of one or two bytes that began like a BOM
        const int held = m_bomSeen;
        m_bomSeen = -1;
        m_consumed -= held;
        feed(kBom, held, sink);
    }
    m_bomSeen = -1;
    if (m_state == State::Quoted)
        throw CsvError(m_fileName, m_record.line, static_cast<int>(m_record.fields.size()) + 1, QString(),
                       QStringLiteral("quoted field not closed before the end of the file"));
    if (m_state != State::FieldStart || !m_record.fields.isEmpty()) {
        endField();
        endRecord(sink);
    }
}

QVector<CsvRecord> CsvReader::parse(const QByteArray &data, const QString &fileName, char separator)
{
    QVector<CsvRecord> out;
    CsvReader reader(fileName, separator);
    const Sink sink = [&out](const CsvRecord &r) { out.push_back(r); };
    reader.feed(data, sink);
    reader.finish(sink);
    return out;
}

} // namespace driftlab
