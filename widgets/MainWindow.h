#pragma once
// The main window: a dockable session browser, the review workspace of the chosen
// session, and optionally a second workspace beside it to compare two sessions. Layout,
// recent databases and the last database persist (QSettings); recording bundles dropped
// on the window are imported.

#include <QMainWindow>
#include <QStringList>

#include <memory>

class QMenu;
class QSplitter;

namespace driftlab {

class AcquisitionPanel;
class AnalysisPanel;
class DiagnosisPanel;
class ModelsPanel;
class ReviewWorkspace;
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
    // Shows a second session beside the first (0 closes the comparison).
    void compareWith(qint64 sessionId);
    // Imports a recording bundle (directory or .zip) into the open database.
    bool importBundle(const QString &path);

    TimeSeriesPlot *plot() const;
    ReviewWorkspace *workspace() const { return m_workspace; }
    ReviewWorkspace *comparison() const { return m_comparison; }
    AcquisitionPanel *acquisition() const { return m_acquisition; }
    ModelsPanel *models() const { return m_models; }
    DiagnosisPanel *diagnosis() const { return m_diagnosis; }
    AnalysisPanel *analysis() const { return m_analysis; }
    SessionBrowser *browser() const { return m_browser; }
    qint64 currentSession() const { return m_sessionId; }
    QString lastError() const { return m_lastError; }
    QStringList recentDatabases() const;

protected:
    void closeEvent(QCloseEvent *event) override;
    void dragEnterEvent(QDragEnterEvent *event) override;
    void dropEvent(QDropEvent *event) override;

private:
    void buildMenus();
    void chooseDatabase();
    void chooseBundle();
    void exportSession();
    void exportView();
    void chooseComparison();
    void rememberDatabase(const QString &path);
    void refreshRecentMenu();
    void reportError(const QString &message);
    void refreshSessions(qint64 select);

    std::unique_ptr<SessionStore> m_store;
    SessionBrowser *m_browser;
    QSplitter *m_split;
    ReviewWorkspace *m_workspace;
    ReviewWorkspace *m_comparison;
    AcquisitionPanel *m_acquisition;
    ModelsPanel *m_models;
    DiagnosisPanel *m_diagnosis;
    AnalysisPanel *m_analysis;
    QMenu *m_recentMenu = nullptr;
    qint64 m_sessionId = 0;
    QString m_lastError;
};

} // namespace driftlab
