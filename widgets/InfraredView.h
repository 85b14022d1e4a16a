#pragma once
// An infrared frame in a colour map with a °C scale bar, the calibrated screw axis and
// band drawn on it, and the temperature under the mouse pointer.
// Cursors as on the plots (issue 33 item 3): Shift+click puts cursor A on a pixel, the next
// Shift+click cursor B (a third starts again at A), Shift+right click or Shift+Esc clears them,
// a placed cursor is dragged with the left button. A box reads each cursor's temperature and
// its position along the calibrated screw axis, then ΔT, the distance along the screw and the
// gradient ΔT/Δx. The right button opens a menu: Copy image, Save image (PNG, SVG, PDF), Export
// the frame's temperatures as CSV (every pixel with its position along the screw: the raw frame
// a lab re-evaluates; the screw's profile is exported from the profile plot beside it).

#include "InfraredFrame.h"

#include <QImage>
#include <QPoint>
#include <QWidget>

#include <optional>

class QMenu;
class QTextStream;

namespace driftlab {

class InfraredView : public QWidget {
    Q_OBJECT
public:
    explicit InfraredView(QWidget *parent = nullptr);

    // temperature: CV_32F degC. The colour scale spans the frame's min..max unless fixed.
    void setFrame(const cv::Mat &temperature, const InfraredCalibration &calibration);
    void setFixedRange(double low_C, double high_C);
    double low_C() const { return m_low; }
    double high_C() const { return m_high; }
    // Temperature at image pixel (x, y); NaN outside.
    double temperatureAt(int x, int y) const;
    QImage colourImage() const { return m_image; }

    enum Which { A = 0, B = 1 };
    void setCursorPixel(Which which, QPoint pixel);
    void clearCursors();
    std::optional<QPoint> cursorPixel(Which which) const { return m_cursor[which]; }
    // What the cursors' box shows ("" without cursors).
    QString cursorText() const;
    // The position along the screw axis (mm from the fixed end) that a pixel projects onto;
    // none when the calibration gives no axis (its two image points less than 2 px apart).
    std::optional<double> axialPosition_mm(QPoint pixel) const;
    // The image pixel under a widget point (none off the image), and back (the pixel's centre).
    std::optional<QPoint> pixelAt(QPoint widgetPos) const;
    QPointF widgetPos(QPoint pixel) const;
    // The frame as CSV: x_px, y_px, axial_position_mm (empty without an axis), temperature_C.
    bool exportCsv(const QString &path, QString *error, int *rows = nullptr) const;
    // The right button's menu (the caller owns it).
    QMenu *createMenu(QWidget *parent);
    QSize sizeHint() const override { return {720, 420}; }

signals:
    void readout(const QString &text);

protected:
    void paintEvent(QPaintEvent *event) override;
    void mouseMoveEvent(QMouseEvent *event) override;
    void mousePressEvent(QMouseEvent *event) override;
    void mouseReleaseEvent(QMouseEvent *event) override;
    void keyPressEvent(QKeyEvent *event) override;
    void contextMenuEvent(QContextMenuEvent *event) override;

private:
    QRectF imageRect() const;
    void rebuildImage();
    void paintCursors(QPainter &p) const;
    int writeCsv(QTextStream &out) const;

    cv::Mat m_temperature;
    InfraredCalibration m_calibration;
    QImage m_image;
    double m_low = 0.0, m_high = 1.0;
    bool m_fixedRange = false;
    std::optional<QPoint> m_cursor[2];
    int m_dragging = -1; // cursor being dragged, -1 none
};

} // namespace driftlab
