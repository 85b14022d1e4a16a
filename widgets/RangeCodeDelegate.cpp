#include "RangeCodeDelegate.h"

#include "ModbusPreset.h"
#include "UnitLabels.h"

#include <QComboBox>

namespace driftlab {

RangeCodeDelegate::RangeCodeDelegate(std::function<QVector<ModbusRange>()> ranges, QObject *parent)
    : QStyledItemDelegate(parent), m_ranges(std::move(ranges))
{
}

QString RangeCodeDelegate::rangeText(const ModbusRange &range)
{
    return QStringLiteral("%1  %2").arg(ModbusPreset::codeText(range.code), UnitLabels::inText(range.label));
}

QWidget *RangeCodeDelegate::createEditor(QWidget *parent, const QStyleOptionViewItem &option, const QModelIndex &index) const
{
    const QVector<ModbusRange> ranges = m_ranges ? m_ranges() : QVector<ModbusRange>();
    if (ranges.isEmpty())
        return QStyledItemDelegate::createEditor(parent, option, index);
    auto *box = new QComboBox(parent);
    box->setObjectName(QStringLiteral("RangeCodeEditor"));
    box->addItem(tr("(module default)"), QString());
    for (const ModbusRange &r : ranges)
        box->addItem(rangeText(r), ModbusPreset::codeText(r.code));
    return box;
}

void RangeCodeDelegate::setEditorData(QWidget *editor, const QModelIndex &index) const
{
    auto *box = qobject_cast<QComboBox *>(editor);
    if (!box) {
        QStyledItemDelegate::setEditorData(editor, index);
        return;
    }
    const QString text = index.data(Qt::EditRole).toString().trimmed();
    bool ok = false;
    const int code = text.startsWith(QLatin1String("0x"), Qt::CaseInsensitive) ? text.mid(2).toInt(&ok, 16) : text.toInt(&ok);
    const int i = ok ? box->findData(ModbusPreset::codeText(code)) : 0;
    box->setCurrentIndex(std::max(0, i));
}

void RangeCodeDelegate::setModelData(QWidget *editor, QAbstractItemModel *model, const QModelIndex &index) const
{
    auto *box = qobject_cast<QComboBox *>(editor);
    if (!box) {
        QStyledItemDelegate::setModelData(editor, model, index);
        return;
    }
    model->setData(index, box->currentData().toString(), Qt::EditRole);
}

} // namespace driftlab
