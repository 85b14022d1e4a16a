#pragma once
// The main window: a dockable session browser, the review workspace of the chosen
// session, and optionally a second workspace beside it to compare two sessions; docks for
// acquisition, models and diagnosis. Session management (new / open database, import by
// menu or by dropping a bundle or a .sqlite, rename, notes, delete), undo for renames and
// notes, recent files, Help. Laid out for 1366 x 768 and up: every dock scrolls, the
// sessions dock runs the full height; geometry and dock state persist (QSettings).

#include <QMainWindow>
#include <QStringList>

#include <memory>

class QAction;
class QMenu;
class QSplitter;
class QUndoStack;

namespace driftlab {

class AcquisitionPanel;
class AnalysisPanel;
class CentralStoreActions;
class CompensationPanel;
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
    // Creates a new, empty database (its folder too) and opens it; refuses an existing file.
    bool newDatabase(const QString &path);
    void showSession(qint64 sessionId);
    void showChannels(const QVector<qint64> &channelIds);
    // Shows a second session beside the first (0 closes the comparison).
    void compareWith(qint64 sessionId);
    // Imports a recording bundle (directory or .zip) into the open database. A bundle that is
    // already there (same session UUID or content) asks whether to import a second copy.
    bool importBundle(const QString &path);
    // Undoable edits of the open database's sessions (Edit > Undo).
    bool renameSession(qint64 sessionId, const QString &name);
    bool setSessionNotes(qint64 sessionId, const QString &notes);
    // Deletes a session and everything recorded, fitted and analysed with it, in one
    // transaction; not undoable, so the Edit menu asks first (this call does not).
    bool deleteSession(qint64 sessionId);

    // The window as on screen, with the 3-D view's OpenGL surface drawn in (QWidget::grab
    // leaves a native OpenGL window blank).
    QImage snapshot();
    // Adds a panel as a dock: scrolls when the window is small, listed in the View menu.
    // Other panels (analysis, rig setup, ...) join the window through this.
    QDockWidget *addPanelDock(const QString &title, const QString &objectName, QWidget *panel, Qt::DockWidgetArea area,
                              const QKeySequence &shortcut = {});
    QDockWidget *dock(const QString &objectName) const;
    // Folder opened by Help > Documentation.
    void setDocumentationDirectory(const QString &dir) { m_docs = dir; }

    TimeSeriesPlot *plot() const;
    ReviewWorkspace *workspace() const { return m_workspace; }
    ReviewWorkspace *comparison() const { return m_comparison; }
    AcquisitionPanel *acquisition() const { return m_acquisition; }
    ModelsPanel *models() const { return m_models; }
    DiagnosisPanel *diagnosis() const { return m_diagnosis; }
    AnalysisPanel *analysis() const { return m_analysis; }
    CompensationPanel *compensation() const { return m_compensation; }
    SessionBrowser *browser() const { return m_browser; }
    QUndoStack *undoStack() const { return m_undo; }
    const SessionStore *store() const { return m_store.get(); }
    qint64 currentSession() const { return m_sessionId; }
    // File > Test report: the application connects it to the report dialog (report/ sits above widgets/).
    QAction *reportAction() const { return m_reportAction; }
    CentralStoreActions *centralStore() const { return m_central; }
    QString lastError() const { return m_lastError; }
    QStringList recentDatabases() const;

protected:
    void closeEvent(QCloseEvent *event) override;
    void dragEnterEvent(QDragEnterEvent *event) override;
    void dropEvent(QDropEvent *event) override;

private:
    void buildMenus();
    void chooseDatabase();
    void chooseNewDatabase();
    void chooseBundle();
    void importCsv();
    void exportSession();
    void exportView();
    void chooseComparison();
    void askRename();
    void askNotes();
    void askDelete();
    void showAbout();
    void showDocumentation();
    void rememberDatabase(const QString &path);
    void refreshRecentMenu();
    void reportError(const QString &message);
    void refreshSessions(qint64 select);
    bool importBundle(const QString &path, bool allowDuplicate);
    void fitToScreen();

    std::unique_ptr<SessionStore> m_store;
    SessionBrowser *m_browser;
    QSplitter *m_split;
    ReviewWorkspace *m_workspace;
    ReviewWorkspace *m_comparison;
    AcquisitionPanel *m_acquisition;
    ModelsPanel *m_models;
    DiagnosisPanel *m_diagnosis;
    QUndoStack *m_undo;
    AnalysisPanel *m_analysis;
    CompensationPanel *m_compensation;
    QMenu *m_recentMenu = nullptr;
    QMenu *m_viewMenu = nullptr;
    QAction *m_reportAction = nullptr;
    CentralStoreActions *m_central = nullptr;
    QAction *m_viewDocksEnd = nullptr;
    qint64 m_sessionId = 0;
    QString m_lastError;
    QString m_docs;
};

} // namespace driftlab
