#pragma once
// The column table of the CSV import dialog: one row per table column that can become a
// channel (the time and run columns are not offered), with import tick, header text, channel
// id, kind, unit in the file, role, target, scale and offset. Filled from a column map (its
// columns ticked, the others guessed from their header and unticked); read back as the map's
// column specs.

#include "CsvColumnMap.h"

#include <QSet>
#include <QStringList>
#include <QTableWidget>
#include <QVector>

class QComboBox;

namespace driftlab {

class CsvColumnTable : public QTableWidget {
    Q_OBJECT
public:
    enum Column { Use, Header, Id, Kind, Unit, Role, Target, Scale, Offset, Count };

    explicit CsvColumnTable(QWidget *parent = nullptr);

    // One row per entry of `header` (0-based columns in `skip` left out). With `hasHeader`,
    // specs refer to columns by header text, else by 1-based index.
    void fill(const QStringList &header, bool hasHeader, const QVector<CsvColumnSpec> &specs, const QSet<int> &skip);
    // The ticked rows.
    QVector<CsvColumnSpec> specs(const QStringList &header, bool hasHeader) const;
    int tickedCount() const;
    // A combo box holding `items` (and `current` if it is not one of them), showing `current`.
    static QComboBox *comboBox(const QStringList &items, bool editable, const QString &current);
};

} // namespace driftlab
