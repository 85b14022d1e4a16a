#include "CsvMapMemory.h"

#include "CsvError.h"

#include <QCryptographicHash>
#include <QJsonDocument>
#include <QSettings>

namespace driftlab {

namespace {
const QString kPrefix = QStringLiteral("csvImport/maps/");
} // namespace

QString CsvMapMemory::signature(char separator, const QStringList &header)
{
    const QByteArray text = QByteArray(1, separator) + header.join(QChar(0x1f)).toUtf8();
    return QString::fromLatin1(QCryptographicHash::hash(text, QCryptographicHash::Sha1).toHex());
}

void CsvMapMemory::remember(const CsvColumnMap &given, const QStringList &header)
{
    CsvColumnMap map = given; // the assignment, not this file's name and start
    map.session.remove(QStringLiteral("name"));
    map.session.remove(QStringLiteral("started"));
    QSettings().setValue(kPrefix + signature(map.separator, header),
                         QString::fromUtf8(QJsonDocument(map.toJson()).toJson(QJsonDocument::Compact)));
}

bool CsvMapMemory::recall(CsvColumnMap &map, const QStringList &header)
{
    const QString json = QSettings().value(kPrefix + signature(map.separator, header)).toString();
    if (json.isEmpty())
        return false;
    try {
        map = CsvColumnMap::fromJson(json.toUtf8(), QStringLiteral("remembered map"));
        return true;
    } catch (const CsvError &) {
        return false; // from another version: guess instead
    }
}

} // namespace driftlab
