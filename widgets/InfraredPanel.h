#pragma once
// Infrared review: a frame viewer with a frame slider, the axial screw temperature
// profile of the shown frame (nut region masked), and the profile over time as a surface.

#include <QWidget>

#include <memory>
#include <vector>

class QLabel;
class QSlider;

namespace driftlab {

class ErrorSurfacePlot;
class InfraredView;
class SessionReviewData;
class TimeSeriesPlot;

class InfraredPanel : public QWidget {
    Q_OBJECT
public:
    explicit InfraredPanel(QWidget *parent = nullptr);
    ~InfraredPanel() override;

    // Shows the session's frames (the data must outlive the panel's use of it).
    void setSession(std::shared_ptr<const SessionReviewData> data);
    void showFrame(int index);
    int frameCount() const;
    InfraredView *view() const { return m_view; }
    TimeSeriesPlot *profilePlot() const { return m_profile; }
    ErrorSurfacePlot *profileSurface() const { return m_surface; }

    // Profiles of every frame on `points` axial stations: rows = frames. NaN under the nut.
    static void profileGrid(const SessionReviewData &data, int points, std::vector<double> &x_m,
                            std::vector<double> &t_s, std::vector<double> &temperature_C);

private:
    std::shared_ptr<const SessionReviewData> m_data;
    InfraredView *m_view;
    QSlider *m_slider;
    QLabel *m_label;
    TimeSeriesPlot *m_profile;
    ErrorSurfacePlot *m_surface;
};

} // namespace driftlab
