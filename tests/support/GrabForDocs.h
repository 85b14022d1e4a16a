#pragma once
// Screenshots for the docs taken by a widget test (tst_surfacecursors, tst_infraredview): with
// DRIFTLAB_GRAB_DIR=DIR set (run under Xvfb + openbox), the widget is shown maximised,
// `prepare` runs once it is drawn (set cursors, say), and the grab is written as
// DIR/<screen width>x<screen height>-NAME.png, to be looked at.

#include <QScreen>
#include <QString>
#include <QTest>
#include <QWidget>

#include <functional>

namespace grabfordocs {

// Where the pictures go ("": no pictures wanted).
inline QString dir()
{
    return qEnvironmentVariable("DRIFTLAB_GRAB_DIR");
}

// False when the widget never became visible or the file could not be written.
inline bool maximised(QWidget &widget, const QString &name, const std::function<void()> &prepare)
{
    widget.showMaximized();
    if (!QTest::qWaitForWindowExposed(&widget))
        return false;
    QTest::qWait(500); // the window manager's final size
    prepare();
    QTest::qWait(200);
    const QSize screen = widget.screen()->size();
    return widget.grab().save(QStringLiteral("%1/%2x%3-%4.png").arg(dir()).arg(screen.width()).arg(screen.height()).arg(name));
}

} // namespace grabfordocs
