#pragma once
// An infrared frame in a colour map with a degC scale bar, the calibrated screw axis and
// band drawn on it, and the temperature under the cursor.

#include "InfraredFrame.h"

#include <QImage>
#include <QWidget>

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
    QSize sizeHint() const override { return {720, 420}; }

signals:
    void readout(const QString &text);

protected:
    void paintEvent(QPaintEvent *event) override;
    void mouseMoveEvent(QMouseEvent *event) override;

private:
    QRectF imageRect() const;
    void rebuildImage();

    cv::Mat m_temperature;
    InfraredCalibration m_calibration;
    QImage m_image;
    double m_low = 0.0, m_high = 1.0;
    bool m_fixedRange = false;
};

} // namespace driftlab
