#pragma once
// The menu actions that ask the user about the workbench's database and sessions: File >
// New / Open / Open recent / Import recording bundle / Import CSV table / Export session;
// Edit > Undo / Redo / Rename / Notes / Delete (also on the session list's context menu).
// They run on the Workbench; MainWindow only places them in its menus.

#include <QList>
#include <QObject>

#include <functional>

class QAction;
class QMenu;
class QWidget;

namespace driftlab {

class Workbench;

class SessionActions : public QObject {
    Q_OBJECT
public:
    SessionActions(Workbench *workbench, QWidget *window);

    // File menu: database and import/export entries (centralStore: entries of the lab's
    // central store, placed after Open recent).
    void addDatabaseActions(QMenu *file, const std::function<void(QMenu *)> &centralStore);
    void addImportExportActions(QMenu *file);
    // Edit menu: undo, redo, rename, notes, delete; returns the three session edits.
    QList<QAction *> addEditActions(QMenu *edit);

    // Imports a bundle; a bundle already in the database asks whether to import a copy.
    bool importBundle(const QString &path) { return importFile(path); }
    // Any file of the importer registry (drag and drop); a table opens the CSV import dialog.
    bool importFile(const QString &path);
    void chooseDatabase();
    void chooseNewDatabase();
    void chooseBundle();
    void importCsv();
    void importCsvFile(const QString &path);
    void exportSession();
    void askRename();
    void askNotes();
    void askDelete();

private:
    void refreshRecentMenu();

    Workbench *m_workbench;
    QWidget *m_window;
    QMenu *m_recentMenu = nullptr;
};

} // namespace driftlab
