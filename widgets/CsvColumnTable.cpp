#include "CsvColumnTable.h"

#include "CsvMapGuesser.h"

#include <QComboBox>
#include <QHeaderView>

namespace driftlab {

QComboBox *CsvColumnTable::comboBox(const QStringList &items, bool editable, const QString &current)
{
    auto *c = new QComboBox;
    c->setEditable(editable);
    c->addItems(items);
    if (c->findText(current) < 0 && !current.isEmpty())
        c->addItem(current);
    c->setCurrentText(current);
    return c;
}

CsvColumnTable::CsvColumnTable(QWidget *parent) : QTableWidget(0, Count, parent)
{
    setObjectName(QStringLiteral("CsvColumns"));
    setHorizontalHeaderLabels({tr("Import"), tr("Column"), tr("Channel id"), tr("Kind"), tr("Unit in file"), tr("Role"), tr("Target"),
                               tr("Scale"), tr("Offset")});
    horizontalHeader()->setSectionResizeMode(Header, QHeaderView::Stretch);
    verticalHeader()->hide();
}

void CsvColumnTable::fill(const QStringList &header, bool hasHeader, const QVector<CsvColumnSpec> &specs, const QSet<int> &skip)
{
    setRowCount(0);
    for (int c = 0; c < header.size(); ++c) {
        if (skip.contains(c))
            continue;
        const CsvColumnSpec *spec = nullptr;
        for (const CsvColumnSpec &s : specs) {
            if ((s.index > 0 && s.index == c + 1) || (s.index == 0 && s.column == header[c]))
                spec = &s;
        }
        const CsvColumnSpec s = spec ? *spec : CsvMapGuesser::guessColumn(hasHeader ? header[c] : QString(), c + 1);
        const int row = rowCount();
        insertRow(row);
        auto *use = new QTableWidgetItem;
        use->setCheckState(spec ? Qt::Checked : Qt::Unchecked);
        setItem(row, Use, use);
        auto *text = new QTableWidgetItem(header[c]);
        text->setFlags(text->flags() & ~Qt::ItemIsEditable);
        text->setData(Qt::UserRole, c);
        setItem(row, Header, text);
        setItem(row, Id, new QTableWidgetItem(s.id));
        auto *kind = comboBox(CsvColumnMap::kinds(), false, s.kind);
        auto *unit = comboBox(CsvColumnMap::units(s.kind), true, s.unit);
        auto *role = comboBox(QStringList{QString()} + CsvColumnMap::knownRoles(), true, s.role);
        setCellWidget(row, Kind, kind);
        setCellWidget(row, Unit, unit);
        setCellWidget(row, Role, role);
        auto *target = new QTableWidgetItem;
        target->setCheckState(s.target ? Qt::Checked : Qt::Unchecked);
        setItem(row, Target, target);
        setItem(row, Scale, new QTableWidgetItem(QString::number(s.scale, 'g', 12)));
        setItem(row, Offset, new QTableWidgetItem(QString::number(s.offset, 'g', 12)));
        connect(kind, &QComboBox::currentTextChanged, unit, [unit, target](const QString &k) {
            unit->clear();
            unit->addItems(CsvColumnMap::units(k));
            target->setCheckState(k == QLatin1String("displacement") ? Qt::Checked : Qt::Unchecked);
        });
    }
    resizeColumnsToContents();
}

QVector<CsvColumnSpec> CsvColumnTable::specs(const QStringList &header, bool hasHeader) const
{
    QVector<CsvColumnSpec> out;
    for (int row = 0; row < rowCount(); ++row) {
        if (item(row, Use)->checkState() != Qt::Checked)
            continue;
        CsvColumnSpec s;
        const int c = item(row, Header)->data(Qt::UserRole).toInt();
        if (hasHeader)
            s.column = header.value(c);
        else
            s.index = c + 1;
        s.id = item(row, Id)->text().trimmed();
        s.kind = qobject_cast<QComboBox *>(cellWidget(row, Kind))->currentText();
        s.unit = qobject_cast<QComboBox *>(cellWidget(row, Unit))->currentText().trimmed();
        s.role = qobject_cast<QComboBox *>(cellWidget(row, Role))->currentText().trimmed();
        s.target = item(row, Target)->checkState() == Qt::Checked && s.kind == QLatin1String("displacement");
        s.scale = item(row, Scale)->text().toDouble();
        s.offset = item(row, Offset)->text().toDouble();
        out.push_back(s);
    }
    return out;
}

int CsvColumnTable::tickedCount() const
{
    int n = 0;
    for (int row = 0; row < rowCount(); ++row)
        n += item(row, Use)->checkState() == Qt::Checked ? 1 : 0;
    return n;
}

} // namespace driftlab
