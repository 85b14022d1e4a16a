#include "ScreenFit.h"

#include <QGuiApplication>
#include <QScreen>
#include <QWindow>
#include <QWidget>

#include <algorithm>

namespace driftlab {

namespace {
QSize g_simulated;

const QScreen *screenOf(const QWidget *window)
{
    const QWidget *parent = window ? window->parentWidget() : nullptr;
    if (parent && parent->window()->windowHandle() && parent->window()->windowHandle()->screen())
        return parent->window()->windowHandle()->screen();
    return QGuiApplication::primaryScreen();
}
} // namespace

void ScreenFit::simulateScreen(const QSize &size)
{
    g_simulated = size;
}

QSize ScreenFit::available(const QWidget *window)
{
    if (g_simulated.isValid())
        return g_simulated;
    const QScreen *screen = screenOf(window);
    return screen ? screen->availableGeometry().size() : QSize(1366, 768);
}

void ScreenFit::resize(QWidget *window, const QSize &preferred)
{
    const QScreen *screen = screenOf(window);
    if (!screen && !g_simulated.isValid()) {
        window->resize(preferred);
        return;
    }
    const QRect avail = g_simulated.isValid() ? QRect(QPoint(0, 0), g_simulated) : screen->availableGeometry();
    // Room for the window manager's frame and title bar.
    const QSize room(avail.width() - 16, avail.height() - 40);
    const QSize size(std::min(preferred.width(), room.width()), std::min(preferred.height(), room.height()));
    window->resize(size);
    window->move(avail.topLeft() + QPoint((avail.width() - size.width()) / 2, std::max(0, (avail.height() - size.height() - 30) / 2)));
}

} // namespace driftlab
