#pragma once
// Sizes a top-level window (dialog) to what it prefers, but never larger than the screen it
// opens on: issue 33 saw dialogs open 1429 and 1400 px wide on a 1366 x 768 laptop, with
// their buttons off screen.

#include <QSize>

class QWidget;

namespace driftlab {

class ScreenFit {
public:
    // Resizes `window` to `preferred` bounded by the available geometry of its screen (the
    // parent's, else the primary one), and centres it there.
    static void resize(QWidget *window, const QSize &preferred);
    // The available geometry a window would open on.
    static QSize available(const QWidget *window);
    // Tests: act as if every screen offered `size` (an empty size: the real screens again).
    // The offscreen platform's screen is 800 x 600, the laptop of issue 33 1366 x 768.
    static void simulateScreen(const QSize &size);
};

} // namespace driftlab
