#pragma once
// A spin box for an elapsed time or a duration, in h:mm:ss like every time on screen
// (issue 33 item 3). Its value is in seconds; it shows UnitLabels::clock and reads what
// UnitLabels::parseClock reads ("1:30:00", "90 min", "2 h", "5400"). The arrows step one
// minute, Page Up/Down ten. A special value text, when set, stands for the minimum as in
// QDoubleSpinBox ("start", "end", "until Stop").

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
};

} // namespace driftlab
