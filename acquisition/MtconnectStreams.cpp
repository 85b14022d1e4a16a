#include "MtconnectStreams.h"

#include <QDateTime>
#include <QXmlStreamReader>

#include <stdexcept>

namespace driftlab {

qint64 MtconnectStreams::parseTime(const QString &text, double *fraction_ms)
{
    // Split off fractional seconds ourselves: agents give up to microseconds.
    QString t = text.trimmed();
    bool utc = t.endsWith(QLatin1Char('Z'));
    if (utc)
        t.chop(1);
    QString frac;
    const int dot = t.indexOf(QLatin1Char('.'));
    if (dot >= 0) {
        frac = t.mid(dot + 1);
        t = t.left(dot);
    }
    QDateTime dt = QDateTime::fromString(t, Qt::ISODate);
    if (!dt.isValid())
        return 0;
    dt.setTimeSpec(Qt::UTC);
    double ms = 0.0;
    if (!frac.isEmpty()) {
        bool ok = false;
        // Fraction digits only: "0." + "5e30" would parse as a huge number (fuzzing found it).
        bool digits = true;
        for (const QChar c : frac)
            digits = digits && c.isDigit() && c.unicode() < 128;
        const double f = digits ? (QStringLiteral("0.") + frac).toDouble(&ok) : 0.0;
        if (ok && f >= 0.0 && f < 1.0)
            ms = f * 1000.0;
    }
    const qint64 whole = static_cast<qint64>(ms);
    if (fraction_ms)
        *fraction_ms = ms - static_cast<double>(whole);
    return dt.toMSecsSinceEpoch() + whole;
}

MtconnectDocument MtconnectStreams::parse(const QByteArray &xml, const QString &source)
{
    MtconnectDocument doc;
    if (xml.trimmed().isEmpty())
        throw std::invalid_argument(QStringLiteral("%1: empty document").arg(source).toStdString());
    QXmlStreamReader r(xml);
    QString component, componentName, category;
    int depthInCategory = 0;
    bool sawRoot = false;
    while (!r.atEnd()) {
        r.readNext();
        if (r.isStartElement()) {
            const QString name = r.name().toString();
            const QXmlStreamAttributes a = r.attributes();
            if (!sawRoot) {
                sawRoot = true;
                if (name == QLatin1String("MTConnectError"))
                    doc.error = true;
                else if (name != QLatin1String("MTConnectStreams"))
                    throw std::invalid_argument(QStringLiteral("%1: line %2: expected an MTConnectStreams or MTConnectError document, got <%3>")
                                                    .arg(source)
                                                    .arg(r.lineNumber())
                                                    .arg(name)
                                                    .toStdString());
                continue;
            }
            if (name == QLatin1String("Header")) {
                doc.instanceId = a.value(QLatin1String("instanceId")).toString();
                doc.firstSequence = a.value(QLatin1String("firstSequence")).toLongLong();
                doc.lastSequence = a.value(QLatin1String("lastSequence")).toLongLong();
                doc.nextSequence = a.value(QLatin1String("nextSequence")).toLongLong();
                doc.creationTime_ms = parseTime(a.value(QLatin1String("creationTime")).toString());
            } else if (name == QLatin1String("Error")) {
                doc.errorCode = a.value(QLatin1String("errorCode")).toString();
                doc.errorText = r.readElementText(QXmlStreamReader::IncludeChildElements).trimmed();
            } else if (name == QLatin1String("ComponentStream")) {
                component = a.value(QLatin1String("component")).toString();
                componentName = a.value(QLatin1String("name")).toString();
            } else if (depthInCategory == 0 && (name == QLatin1String("Samples") || name == QLatin1String("Events") || name == QLatin1String("Condition"))) {
                category = name;
                depthInCategory = 1;
            } else if (depthInCategory == 1) {
                MtconnectObservation o;
                o.element = name;
                o.category = category;
                o.component = component;
                o.componentName = componentName;
                o.dataItemId = a.value(QLatin1String("dataItemId")).toString();
                o.name = a.value(QLatin1String("name")).toString();
                o.subType = a.value(QLatin1String("subType")).toString();
                o.sequence = a.value(QLatin1String("sequence")).toLongLong();
                o.timestamp_ms = parseTime(a.value(QLatin1String("timestamp")).toString(), &o.timestampFraction_ms);
                if (category == QLatin1String("Condition"))
                    o.value = name; // Normal / Warning / Fault / Unavailable
                const QString text = r.readElementText(QXmlStreamReader::IncludeChildElements).trimmed();
                if (category != QLatin1String("Condition"))
                    o.value = text;
                if (r.hasError())
                    break;
                doc.observations.push_back(o);
            }
        } else if (r.isEndElement()) {
            const QString name = r.name().toString();
            if (depthInCategory == 1 && name == category)
                depthInCategory = 0;
        }
    }
    if (r.hasError())
        throw std::invalid_argument(QStringLiteral("%1: line %2, column %3: malformed XML: %4")
                                        .arg(source)
                                        .arg(r.lineNumber())
                                        .arg(r.columnNumber())
                                        .arg(r.errorString())
                                        .toStdString());
    if (!sawRoot)
        throw std::invalid_argument(QStringLiteral("%1: empty document").arg(source).toStdString());
    return doc;
}

} // namespace driftlab
