#pragma once
// Combo boxes and spin boxes take the mouse wheel only when they have the keyboard focus
// (issue 33): scrolling a dock or dialog with the wheel no longer changes a value that
// happens to pass under the pointer; the wheel goes on to the scroll area around it.
// Installed once on the application (MainWindow does); it also gives every such box
// Qt::StrongFocus, so the wheel does not focus it either.

#include <QObject>

namespace driftlab {

class WheelGuard : public QObject {
    Q_OBJECT
public:
    explicit WheelGuard(QObject *parent = nullptr) : QObject(parent) {}
    // Installs one guard on the application (a second call does nothing).
    static void installOnApplication();

protected:
    bool eventFilter(QObject *watched, QEvent *event) override;
};

} // namespace driftlab
