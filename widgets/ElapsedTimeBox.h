#pragma once
// A spin box for an elapsed time or a duration, in h:mm:ss like every time on screen
// (issue 33 item 3). Its value is in seconds; it shows UnitLabels::clock and reads what
// UnitLabels::parseClock reads ("1:30:00", "90 min", "2 h", "5400"). The arrows step one
// minute, Page Up/Down ten. A special value text, when set, stands for the minimum as in
// QDoubleSpinBox ("start", "end", "until Stop"). An entry that is not a time, or lies outside
// the box's range, is not taken: the box keeps its value and says why in a tooltip under it
// (and entryRefused), so a typo never passes for a value nor vanishes without a word.

#include <QDoubleSpinBox>

namespace driftlab {

class ElapsedTimeBox : public QDoubleSpinBox {
    Q_OBJECT
public:
    explicit ElapsedTimeBox(QWidget *parent = nullptr);

    QString textFromValue(double seconds) const override;
    double valueFromText(const QString &text) const override;
    QValidator::State validate(QString &text, int &pos) const override;
    void fixup(QString &text) const override;

    // Why the last entry was not taken ("'1:75:00': minutes must be below 60 in H:MM:SS; kept
    // 2:01:00"); empty until one is refused.
    QString lastRefusal() const { return m_refusal; }

signals:
    void entryRefused(const QString &why) const;

private:
    mutable QString m_refusal;
};

} // namespace driftlab
