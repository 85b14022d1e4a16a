#pragma once
// Edits a Modbus module's input range code with a list of the codes the module's preset
// knows ("0x0020  Pt100 -50..150 °C"), instead of free hex text (issue 33, Rig setup).

#include <QStyledItemDelegate>

#include <functional>

namespace driftlab {

struct ModbusRange;

class RangeCodeDelegate : public QStyledItemDelegate {
    Q_OBJECT
public:
    // `ranges` gives the ranges of the preset of the device being edited (empty: free text).
    RangeCodeDelegate(std::function<QVector<ModbusRange>()> ranges, QObject *parent = nullptr);

    QWidget *createEditor(QWidget *parent, const QStyleOptionViewItem &option, const QModelIndex &index) const override;
    void setEditorData(QWidget *editor, const QModelIndex &index) const override;
    void setModelData(QWidget *editor, QAbstractItemModel *model, const QModelIndex &index) const override;
    // The text shown for a range: code and label.
    static QString rangeText(const ModbusRange &range);

private:
    std::function<QVector<ModbusRange>()> m_ranges;
};

} // namespace driftlab
