#pragma once
// The column assignments the CSV import dialog remembers (QSettings), one per header
// signature (separator + header texts), so that the next file from the same logger opens
// with it. A file's own name and start are not remembered.

#include "CsvColumnMap.h"

#include <QString>
#include <QStringList>

namespace driftlab {

class CsvMapMemory {
public:
    static QString signature(char separator, const QStringList &header);
    static void remember(const CsvColumnMap &map, const QStringList &header);
    // The map remembered for this header (and map.separator), into `map`; false if none.
    static bool recall(CsvColumnMap &map, const QStringList &header);
};

} // namespace driftlab
