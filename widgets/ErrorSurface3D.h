#pragma once
// The thermal error surface over position and time as a rotatable 3-D surface
// (Qt DataVisualization). Needs OpenGL: under Xvfb, Mesa's software renderer serves it.

#include <QImage>
#include <QWidget>

namespace QtDataVisualization {
class Q3DSurface;
class QSurfaceDataProxy;
}

namespace driftlab {

class ThermalErrorTable;

class ErrorSurface3D : public QWidget {
    Q_OBJECT
public:
    explicit ErrorSurface3D(QWidget *parent = nullptr);
    ~ErrorSurface3D() override;

    void setTable(const ThermalErrorTable &table);
    // The OpenGL surface rendered off screen at this widget's size (null if OpenGL is missing):
    // screenshots draw it in, since grabbing the widget leaves its native window blank.
    QImage renderImage() const;
    // Rows = runs (time), columns = targets (position); x = position mm, z = time min,
    // y = thermal error um. Missing cells take the nearest measured target of the run.
    static void fillProxy(QtDataVisualization::QSurfaceDataProxy &proxy, const ThermalErrorTable &table);

private:
    QtDataVisualization::Q3DSurface *m_graph = nullptr;
    QtDataVisualization::QSurfaceDataProxy *m_proxy = nullptr;
};

} // namespace driftlab
