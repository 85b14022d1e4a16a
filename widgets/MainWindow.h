#pragma once
// The main window: the layout only. A dockable session browser, the review workspace of the
// workbench's current session and optionally a second workspace beside it to compare two
// sessions; docks for acquisition, models, diagnosis, analysis and compensation; the menus.
// The open database, the current session and their edits belong to the Workbench; the
// dialogs that ask for them to SessionActions. Laid out for 1366 x 768 and up: every dock
// scrolls, docks tabify, the sessions dock runs the full height; geometry and dock state
// persist (QSettings) and View > Reset layout brings back the first arrangement.

#include <QByteArray>
#include <QMainWindow>
#include <QStringList>

class QAction;
class QLabel;
class QMenu;
class QSplitter;
class QStackedWidget;
class QTabWidget;

namespace driftlab {

class AcquisitionPanel;
class AnalysisPanel;
class CentralStoreActions;
class CompensationPanel;
class DiagnosisPanel;
class Iso230View;
class ModelsPanel;
class ReviewWorkspace;
class SessionActions;
class SessionBrowser;
class TimeSeriesPlot;
class WelcomePage;
class Workbench;

class MainWindow : public QMainWindow {
    Q_OBJECT
public:
    explicit MainWindow(QWidget *parent = nullptr);
    ~MainWindow() override;

    Workbench *workbench() const { return m_workbench; }
    SessionActions *sessionActions() const { return m_actions; }
    void showChannels(const QVector<qint64> &channelIds);
    // The first-start offers (WelcomePage): open the acquisition target database when none is
    // open, then record 10 min of the simulated baseline rig, or import the example bundle.
    bool recordSimulatedSession();
    bool openExampleBundle();
    WelcomePage *welcome() const { return m_welcome; }
    // Shows a second session beside the first (0 closes the comparison).
    void compareWith(qint64 sessionId);
    // Draws other sessions on the current session's time plot (View > Overlay sessions...).
    void overlaySessions(const QVector<qint64> &sessionIds);

    // The window as on screen, with the 3-D view's OpenGL surface drawn in (QWidget::grab
    // leaves a native OpenGL window blank).
    QImage snapshot();
    // Adds a panel as a dock: scrolls when the window is small, listed in the View menu.
    // Other panels (analysis, rig setup, ...) join the window through this.
    QDockWidget *addPanelDock(const QString &title, const QString &objectName, QWidget *panel, Qt::DockWidgetArea area,
                              const QKeySequence &shortcut = {});
    QDockWidget *dock(const QString &objectName) const;
    // View > Reset layout: the docks as on the first start, hidden ones hidden.
    void resetLayout();
    // Where Help > Documentation finds the .md files (default: the resources, :/docs).
    void setDocumentationDirectory(const QString &dir) { m_docs = dir; }

    TimeSeriesPlot *plot() const;
    ReviewWorkspace *workspace() const { return m_workspace; }
    ReviewWorkspace *comparison() const { return m_comparison; }
    // The central area's tabs: Session (the review workspace), ISO 230, Model fit, Diagnosis, Analysis.
    QTabWidget *centralViews() const { return m_views; }
    Iso230View *iso230() const { return m_iso230; }
    AcquisitionPanel *acquisition() const { return m_acquisition; }
    ModelsPanel *models() const { return m_models; }
    DiagnosisPanel *diagnosis() const { return m_diagnosis; }
    AnalysisPanel *analysis() const { return m_analysis; }
    CompensationPanel *compensation() const { return m_compensation; }
    SessionBrowser *browser() const { return m_browser; }
    // File > Test report: the application connects it to the report dialog (report/ sits above widgets/).
    QAction *reportAction() const { return m_reportAction; }
    CentralStoreActions *centralStore() const { return m_central; }
    // The permanent status-bar text: open database and its number of sessions.
    QString storeSummary() const;

protected:
    void closeEvent(QCloseEvent *event) override;
    void dragEnterEvent(QDragEnterEvent *event) override;
    void dropEvent(QDropEvent *event) override;

private:
    void buildMenus();
    void exportView();
    void chooseComparison();
    void chooseOverlay();
    void showAbout();
    void showDocumentation();
    void fitToScreen();
    void onStoreChanged();
    void onSessionChanged(qint64 sessionId);
    void onSessionsChanged();
    void onRecordingStopped(qint64 sessionId);
    void markRecording();
    void say(const QString &message);
    bool ensureDatabase();

    Workbench *m_workbench;
    SessionActions *m_actions;
    QTabWidget *m_views;
    QStackedWidget *m_sessionPage;
    WelcomePage *m_welcome;
    SessionBrowser *m_browser;
    QSplitter *m_split;
    ReviewWorkspace *m_workspace;
    ReviewWorkspace *m_comparison;
    Iso230View *m_iso230;
    AcquisitionPanel *m_acquisition;
    ModelsPanel *m_models;
    DiagnosisPanel *m_diagnosis;
    AnalysisPanel *m_analysis;
    CompensationPanel *m_compensation;
    QLabel *m_summary = nullptr;
    QMenu *m_viewMenu = nullptr;
    QAction *m_reportAction = nullptr;
    CentralStoreActions *m_central = nullptr;
    QAction *m_viewDocksEnd = nullptr;
    QByteArray m_defaultLayout;
    QString m_docs = QStringLiteral(":/docs");
};

} // namespace driftlab
