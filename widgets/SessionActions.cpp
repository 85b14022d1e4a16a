#include "SessionActions.h"

#include "CsvImportDialog.h"
#include "ImporterRegistry.h"
#include "SessionStore.h"
#include "Workbench.h"

#include <QAction>
#include <QApplication>
#include <QFileDialog>
#include <QFileInfo>
#include <QInputDialog>
#include <QMenu>
#include <QMessageBox>
#include <QUndoStack>
#include <QWidget>

namespace driftlab {

SessionActions::SessionActions(Workbench *workbench, QWidget *window)
    : QObject(window), m_workbench(workbench), m_window(window)
{
    connect(m_workbench, &Workbench::recentDatabasesChanged, this, &SessionActions::refreshRecentMenu);
}

void SessionActions::addDatabaseActions(QMenu *file, const std::function<void(QMenu *)> &centralStore)
{
    file->addAction(tr("&New database..."), this, &SessionActions::chooseNewDatabase, QKeySequence::New);
    file->addAction(tr("&Open database..."), this, &SessionActions::chooseDatabase, QKeySequence::Open);
    m_recentMenu = file->addMenu(tr("Open &recent"));
    refreshRecentMenu();
    if (centralStore)
        centralStore(file);
}

void SessionActions::addImportExportActions(QMenu *file)
{
    file->addAction(tr("&Import recording bundle..."), this, &SessionActions::chooseBundle, QKeySequence(Qt::CTRL + Qt::Key_I));
    file->addAction(tr("Import &CSV table..."), this, &SessionActions::importCsv)->setObjectName(QStringLiteral("ImportCsvAction"));
    file->addAction(tr("&Export session as bundle..."), this, &SessionActions::exportSession, QKeySequence(Qt::CTRL + Qt::Key_E));
}

QList<QAction *> SessionActions::addEditActions(QMenu *edit)
{
    QAction *undo = m_workbench->undoStack()->createUndoAction(this, tr("&Undo"));
    undo->setShortcut(QKeySequence::Undo);
    QAction *redo = m_workbench->undoStack()->createRedoAction(this, tr("&Redo"));
    redo->setShortcut(QKeySequence::Redo);
    edit->addAction(undo);
    edit->addAction(redo);
    edit->addSeparator();
    QAction *rename = edit->addAction(tr("Re&name session..."), this, &SessionActions::askRename, QKeySequence(Qt::Key_F2));
    QAction *notes = edit->addAction(tr("Session &notes..."), this, &SessionActions::askNotes,
                                     QKeySequence(Qt::CTRL + Qt::SHIFT + Qt::Key_N));
    QAction *remove = edit->addAction(tr("&Delete session..."), this, &SessionActions::askDelete, QKeySequence::Delete);
    return {rename, notes, remove};
}

void SessionActions::refreshRecentMenu()
{
    if (!m_recentMenu)
        return;
    m_recentMenu->clear();
    for (const QString &path : Workbench::recentDatabases())
        m_recentMenu->addAction(path, this, [this, path] { m_workbench->openDatabase(path); });
    m_recentMenu->setEnabled(!m_recentMenu->isEmpty());
}

void SessionActions::chooseDatabase()
{
    const QString path = QFileDialog::getOpenFileName(m_window, tr("Open session database"), QString(),
                                                      tr("DriftLab databases (*.sqlite *.db);;All files (*)"));
    if (!path.isEmpty())
        m_workbench->openDatabase(path);
}

void SessionActions::chooseNewDatabase()
{
    QString path = QFileDialog::getSaveFileName(m_window, tr("New session database"), QStringLiteral("sessions.sqlite"),
                                                tr("DriftLab databases (*.sqlite)"), nullptr,
                                                QFileDialog::DontConfirmOverwrite);
    if (path.isEmpty())
        return;
    if (QFileInfo(path).suffix().isEmpty())
        path += QStringLiteral(".sqlite");
    m_workbench->newDatabase(path);
}

bool SessionActions::importFile(const QString &path)
{
    const ImporterRegistry registry;
    const SessionImporter *importer = registry.find(path);
    if (importer && importer->needsColumnMap()) {
        importCsvFile(path);
        return false; // the dialog imports when the user accepts the map
    }
    QApplication::setOverrideCursor(Qt::WaitCursor);
    qint64 existing = 0;
    qint64 id = m_workbench->importFile(path, false, &existing);
    QApplication::restoreOverrideCursor();
    if (existing > 0) {
        const QMessageBox::StandardButton answer = QMessageBox::question(
            m_window, tr("Already in this database"),
            tr("%1.\n\nImport a second copy as a new session?").arg(m_workbench->lastError()),
            QMessageBox::Yes | QMessageBox::No, QMessageBox::No);
        if (answer == QMessageBox::Yes) {
            QApplication::setOverrideCursor(Qt::WaitCursor);
            id = m_workbench->importFile(path, true);
            QApplication::restoreOverrideCursor();
        } else {
            m_workbench->setCurrentSession(existing);
            m_workbench->reportError(tr("%1 not imported: it is already session %2").arg(path).arg(existing));
            return false;
        }
    }
    if (id == 0 && existing == 0 && m_window->isVisible() && m_workbench->store())
        QMessageBox::warning(m_window, tr("Import failed"), m_workbench->lastError());
    return id > 0;
}

void SessionActions::chooseBundle()
{
    const QString path = QFileDialog::getOpenFileName(m_window, tr("Import recording bundle"), QString(),
                                                      tr("Bundles (manifest.json *.zip);;All files (*)"));
    if (path.isEmpty())
        return;
    importBundle(QFileInfo(path).fileName() == QLatin1String("manifest.json") ? QFileInfo(path).absolutePath() : path);
}

void SessionActions::importCsv()
{
    if (!m_workbench->store()) {
        m_workbench->reportError(tr("Open a database first (File > Open database): the table is imported into it"));
        return;
    }
    const QString path = QFileDialog::getOpenFileName(m_window, tr("Import CSV table"), QString(),
                                                      tr("Tables (*.csv *.txt *.tsv *.dat);;All files (*)"));
    if (!path.isEmpty())
        importCsvFile(path);
}

void SessionActions::importCsvFile(const QString &path)
{
    if (!m_workbench->store()) {
        m_workbench->reportError(tr("Open a database first (File > Open database): the table is imported into it"));
        return;
    }
    auto *dialog = new CsvImportDialog(m_workbench->store()->path(), m_window);
    dialog->setAttribute(Qt::WA_DeleteOnClose);
    connect(dialog, &CsvImportDialog::imported, m_workbench, [this](qint64 id) { m_workbench->refreshSessions(id); });
    dialog->openFile(path);
    dialog->open();
}

void SessionActions::exportSession()
{
    const qint64 id = m_workbench->currentSession();
    if (!m_workbench->store() || id == 0)
        return;
    const QString out = QFileDialog::getSaveFileName(m_window, tr("Export session"), QStringLiteral("session.zip"),
                                                     tr("Zipped bundle (*.zip);;Bundle folder (*.bundle)"));
    if (!out.isEmpty())
        m_workbench->exportSession(id, out);
}

void SessionActions::askRename()
{
    const qint64 id = m_workbench->currentSession();
    if (!m_workbench->store() || id == 0)
        return;
    bool ok = false;
    const QString name = QInputDialog::getText(m_window, tr("Rename session"), tr("Name of session %1:").arg(id),
                                               QLineEdit::Normal, m_workbench->store()->session(id).name, &ok);
    if (ok)
        m_workbench->renameSession(id, name);
}

void SessionActions::askNotes()
{
    const qint64 id = m_workbench->currentSession();
    if (!m_workbench->store() || id == 0)
        return;
    bool ok = false;
    const QString notes = QInputDialog::getMultiLineText(m_window, tr("Session notes"), tr("Notes of session %1:").arg(id),
                                                         m_workbench->store()->session(id).notes, &ok);
    if (ok)
        m_workbench->setSessionNotes(id, notes);
}

void SessionActions::askDelete()
{
    const qint64 id = m_workbench->currentSession();
    if (!m_workbench->store() || id == 0)
        return;
    const QString name = m_workbench->store()->session(id).name;
    const auto answer = QMessageBox::warning(
        m_window, tr("Delete session"),
        tr("Delete session %1 '%2' with everything recorded, fitted and analysed with it?\n\n"
           "This cannot be undone (export it as a bundle first to keep a copy).")
            .arg(id)
            .arg(name),
        QMessageBox::Yes | QMessageBox::Cancel, QMessageBox::Cancel);
    if (answer == QMessageBox::Yes)
        m_workbench->deleteSession(id);
}

} // namespace driftlab
