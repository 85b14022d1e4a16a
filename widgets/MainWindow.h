#pragma once
// The main window: session browser on the left, time-series plot of the checked channels.

#include <QMainWindow>

#include <memory>

namespace driftlab {

class SessionBrowser;
class SessionStore;
class TimeSeriesPlot;

class MainWindow : public QMainWindow {
    Q_OBJECT
public:
    explicit MainWindow(QWidget *parent = nullptr);
    ~MainWindow() override;

    // Opens a session database; returns false and shows the reason in the status bar on failure.
    bool openDatabase(const QString &path);
    void showSession(qint64 sessionId);
    void showChannels(const QVector<qint64> &channelIds);

    TimeSeriesPlot *plot() const { return m_plot; }
    SessionBrowser *browser() const { return m_browser; }
    qint64 currentSession() const { return m_sessionId; }
    QString lastError() const { return m_lastError; }

private:
    void chooseDatabase();
    void reportError(const QString &message);

    std::unique_ptr<SessionStore> m_store;
    SessionBrowser *m_browser;
    TimeSeriesPlot *m_plot;
    qint64 m_sessionId = 0;
    QString m_lastError;
};

} // namespace driftlab
