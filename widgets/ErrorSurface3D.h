#pragma once
// The thermal error surface over position and time as a rotatable 3-D surface
// (Qt DataVisualization). Needs OpenGL: under Xvfb, Mesa's software renderer serves it.
// A click on the surface selects a grid point; a line below reads it with units (position mm,
// elapsed time h:mm:ss, thermal error µm). A right click without dragging (dragging rotates)
// opens a menu: Copy image, Save image (PNG, SVG, PDF; the off-screen render), Export the
// table as CSV.

#include "ThermalErrorTable.h"

#include <QImage>
#include <QPoint>
#include <QWidget>

#include <optional>

class QLabel;
class QMenu;
class QTextStream;

namespace QtDataVisualization {
class Q3DSurface;
class QSurfaceDataProxy;
class QSurface3DSeries;
}

namespace driftlab {

class ErrorSurface3D : public QWidget {
    Q_OBJECT
public:
    explicit ErrorSurface3D(QWidget *parent = nullptr);
    ~ErrorSurface3D() override;

    void setTable(const ThermalErrorTable &table);
    // The OpenGL surface rendered off screen at the size of its place in this widget, graphRect()
    // (null if OpenGL is missing): screenshots draw it in there, since grabbing the widget leaves
    // its native window blank (the readout line below it is an ordinary widget).
    QImage renderImage() const;
    QRect graphRect() const;
    // Rows = runs (time), columns = targets (position); x = position mm, z = elapsed time s
    // (labelled h:mm:ss), y = thermal error µm. Missing cells take the nearest measured target
    // of the run.
    static void fillProxy(QtDataVisualization::QSurfaceDataProxy &proxy, const ThermalErrorTable &table);
    // The readout of the grid point (row = run, column = target) a click selected.
    static QString selectionText(const ThermalErrorTable &table, QPoint rowColumn);
    // The table as CSV: position_mm, time_s, thermal_error_um, one row per run and target
    // (runs in time order; a target not measured has an empty error).
    static int writeCsv(const ThermalErrorTable &table, QTextStream &out);
    QString readout() const;
    // Selects a grid point as a click on it would (row = run, column = target).
    void select(QPoint rowColumn);
    // Cursors A and B on grid points, as on the 2-D plots: Shift+click sets A, the next
    // Shift+click B, a third starts again at A; the readout then gives both points and their
    // delta (position mm, elapsed time h:mm:ss, thermal error µm). Cleared from the menu.
    void setCursor(int which, QPoint rowColumn); // which: 0 = A, 1 = B
    void clearCursors();
    static QString cursorsText(const ThermalErrorTable &table, const std::optional<QPoint> &a, const std::optional<QPoint> &b);
    // The camera as the view opened (the 3-D view's "Reset zoom": the wheel zooms, the right
    // button rotates).
    void resetView();
    // The right button's menu (the caller owns it).
    QMenu *createMenu(QWidget *parent);

protected:
    bool eventFilter(QObject *watched, QEvent *event) override;

private:
    ThermalErrorTable m_table;
    QWidget *m_container = nullptr; // the graph's window in this widget
    QLabel *m_readout = nullptr;
    QPoint m_rightPress;
    bool m_shiftPress = false; // the last left press held Shift: its selection places a cursor
    std::optional<QPoint> m_cursor[2];
    QtDataVisualization::Q3DSurface *m_graph = nullptr;
    QtDataVisualization::QSurfaceDataProxy *m_proxy = nullptr;
    QtDataVisualization::QSurface3DSeries *m_series = nullptr;
};

} // namespace driftlab
