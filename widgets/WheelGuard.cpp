#include "WheelGuard.h"

#include <QAbstractSpinBox>
#include <QApplication>
#include <QComboBox>
#include <QEvent>

namespace driftlab {

namespace {
bool guarded(QObject *o)
{
    return qobject_cast<QComboBox *>(o) || qobject_cast<QAbstractSpinBox *>(o);
}
} // namespace

void WheelGuard::installOnApplication()
{
    if (!qApp || qApp->findChild<WheelGuard *>(QString(), Qt::FindDirectChildrenOnly))
        return;
    qApp->installEventFilter(new WheelGuard(qApp));
}

bool WheelGuard::eventFilter(QObject *watched, QEvent *event)
{
    if (event->type() == QEvent::Polish && guarded(watched)) {
        auto *w = static_cast<QWidget *>(watched);
        if (w->focusPolicy() == Qt::WheelFocus)
            w->setFocusPolicy(Qt::StrongFocus);
    } else if (event->type() == QEvent::Wheel && guarded(watched) && !static_cast<QWidget *>(watched)->hasFocus()) {
        // Not consumed: QApplication passes an ignored wheel event on to the parent.
        event->ignore();
        return true;
    }
    return QObject::eventFilter(watched, event);
}

} // namespace driftlab
