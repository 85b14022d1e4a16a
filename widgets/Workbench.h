#pragma once
// The workbench (issue 34 item 2), in the manner of PulseView's Session: owns the open
// session database and the current session, and says when either, or the list of
// sessions, changes. Panels take the workbench and follow its signals instead of being
// pushed the store; MainWindow keeps the layout. The database lifecycle (new, open,
// recent files), the session edits (rename and notes undoable, delete) and bundle import
// and export live here; the dialogs that ask for them are in SessionActions.
//
// Jobs that read the store in the background (a fit, a diagnosis, a recording) register a
// guard: while a guard objects, the database is not replaced and the session is not deleted.

#include "StorageTypes.h"

#include <QObject>
#include <QPointer>
#include <QString>
#include <QStringList>
#include <QVector>

#include <functional>
#include <memory>
#include <vector>

class QUndoStack;

namespace driftlab {

class SessionStore;

class Workbench : public QObject {
    Q_OBJECT
public:
    explicit Workbench(QObject *parent = nullptr);
    ~Workbench() override;

    // The open database (nullptr: none). Valid until storeChanged.
    SessionStore *store() const { return m_store.get(); }
    // Absolute path of the open local database ("" for none or a central store).
    QString localPath() const;
    qint64 currentSession() const { return m_session; }
    // The sessions of the open database as read at the last change.
    const QVector<SessionInfo> &sessions() const { return m_sessions; }
    QUndoStack *undoStack() const { return m_undo; }
    QString lastError() const { return m_lastError; }

    // Opens a session database (a file or a central store address); false with lastError()
    // when it cannot, or while a guard objects. The last session becomes current.
    bool openDatabase(const QString &path);
    // Creates a new, empty database (its folder too) and opens it; refuses an existing file.
    bool newDatabase(const QString &path);
    // Makes a session of the open database current (0: none).
    void setCurrentSession(qint64 sessionId);
    // Re-reads the session list; `select` becomes current when it is there, else the current
    // one stays, else the last session.
    void refreshSessions(qint64 select = 0);

    // Undoable edits (Edit > Undo) and delete (not undoable: everything of the session goes).
    bool renameSession(qint64 sessionId, const QString &name);
    bool setSessionNotes(qint64 sessionId, const QString &notes);
    bool deleteSession(qint64 sessionId);
    // Imports a recording bundle; the new session id, or 0 with lastError(). A bundle already
    // in the database sets *duplicateOf to that session (and imports nothing) unless
    // allowDuplicate.
    qint64 importBundle(const QString &path, bool allowDuplicate = false, qint64 *duplicateOf = nullptr);
    // Any file the importer registry takes (core/ImporterRegistry: bundle, session database,
    // .rtl into the current session, ...), the same way; returns the last session imported.
    qint64 importFile(const QString &path, bool allowDuplicate = false, qint64 *duplicateOf = nullptr);
    bool exportSession(qint64 sessionId, const QString &out);

    // A recording into `databasePath` started or stopped: when it is the open database the
    // session list is re-read at once (the running session is listed while it records).
    void recordingChanged(const QString &databasePath, qint64 sessionId);

    // A guard returns why the store must not change now ("" when it may). `sessionId` is
    // the session about to be deleted, or 0 when the whole database is about to be replaced.
    using Guard = std::function<QString(qint64 sessionId)>;
    void addGuard(QObject *owner, Guard guard);
    QString objection(qint64 sessionId) const;

    static QStringList recentDatabases();
    // Sets lastError() and says it (failed()).
    void reportError(const QString &error);

signals:
    // Another database was opened (the store pointer of before is gone).
    void storeChanged(SessionStore *store);
    void sessionsChanged(const QVector<SessionInfo> &sessions);
    void sessionChanged(qint64 sessionId);
    void recentDatabasesChanged();
    // What happened, for the status line.
    void message(const QString &text);
    void failed(const QString &error);

private:
    static void rememberDatabase(const QString &path);

    std::unique_ptr<SessionStore> m_store;
    QVector<SessionInfo> m_sessions;
    qint64 m_session = 0;
    QUndoStack *m_undo;
    QString m_lastError;
    std::vector<std::pair<QPointer<QObject>, Guard>> m_guards;
};

} // namespace driftlab
