#include "ElapsedTimeBox.h"

#include "UnitLabels.h"

#include <QRegularExpression>
#include <QToolTip>

namespace driftlab {

ElapsedTimeBox::ElapsedTimeBox(QWidget *parent) : QDoubleSpinBox(parent)
{
    setDecimals(0); // whole seconds, as the clock shows them
    setRange(0.0, 7.0 * 24 * 3600);
    setSingleStep(60.0);
    setAccelerated(true);
    setKeyboardTracking(false); // "1:7" on the way to "1:75:00" is not a value
    setToolTip(tr("h:mm:ss, or a number with a unit: 90 min, 2 h, 45 s"));
}

QString ElapsedTimeBox::textFromValue(double seconds) const
{
    return UnitLabels::clock(seconds);
}

double ElapsedTimeBox::valueFromText(const QString &text) const
{
    if (!specialValueText().isEmpty() && text.trimmed() == specialValueText())
        return minimum();
    return UnitLabels::parseClock(text).value_or(value());
}

QValidator::State ElapsedTimeBox::validate(QString &text, int &) const
{
    const QString t = text.trimmed();
    if (!specialValueText().isEmpty() && t == specialValueText())
        return QValidator::Acceptable;
    if (const std::optional<double> v = UnitLabels::parseClock(t))
        return *v >= minimum() && *v <= maximum() ? QValidator::Acceptable : QValidator::Intermediate;
    // Half typed ("1:", "1:3", "90 m", the special text's start): allowed while editing, never accepted.
    static const QRegularExpression typing(QStringLiteral("^[0-9:.,]*\\s*[hmins]*$"));
    if (typing.match(t).hasMatch() || specialValueText().startsWith(t))
        return QValidator::Intermediate;
    return QValidator::Invalid;
}

void ElapsedTimeBox::fixup(QString &text) const
{
    // Called with an entry validate() did not accept when it is to be taken (Return, focus
    // out): it goes back to the value the box had, and the box says why.
    const QString typed = text.trimmed();
    const QString kept = textFromValue(value());
    text = kept;
    if (typed.isEmpty() || typed == kept)
        return;
    QString why;
    if (const std::optional<double> v = UnitLabels::parseClock(typed, &why))
        why = tr("'%1' is outside %2 to %3").arg(typed, specialValueText().isEmpty() ? textFromValue(minimum()) : specialValueText(),
                                                  textFromValue(maximum()));
    m_refusal = tr("%1; kept %2").arg(why, kept);
    if (isVisible())
        QToolTip::showText(mapToGlobal(QPoint(0, height())), m_refusal, const_cast<ElapsedTimeBox *>(this));
    emit entryRefused(m_refusal);
}

} // namespace driftlab
