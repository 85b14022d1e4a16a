#pragma once
// The lab's central store in the GUI (issue 20): File > Open central store... asks for the
// address (postgresql://USER@HOST[:PORT]/DATABASE; remembered in QSettings without a password:
// libpq takes it from PGPASSWORD or ~/.pgpass) and opens it in the session browser like a file;
// File > Push session to central store... copies the selected session of the open local
// database there (SessionCopier: one transaction, verified, idempotent) with a progress dialog
// whose Cancel leaves nothing on the server. File > Push recordings automatically (a setting)
// pushes each recording the Acquisition panel finishes; a failure is said and the recording
// stays in the local file.

#include <QObject>
#include <QString>

#include <functional>

class QMenu;
class QWidget;

namespace driftlab {

class SessionStore;

class CentralStoreActions : public QObject {
    Q_OBJECT
public:
    using StoreFn = std::function<SessionStore *()>;
    using SessionFn = std::function<qint64()>;
    using OpenFn = std::function<bool(const QString &address)>;
    CentralStoreActions(QWidget *parent, StoreFn store, SessionFn session, OpenFn open);

    void addTo(QMenu *file);
    // The remembered address (empty: none yet); setAddress() drops any password before storing.
    static QString address();
    static void setAddress(const QString &address);
    // Pushes `sessionId` of the open store to `address`; false with *message on failure or
    // cancel. `interactive` shows a progress dialog with Cancel.
    bool push(const QString &address, qint64 sessionId, QString *message, bool interactive = true);
    QString lastMessage() const { return m_lastMessage; }
    // The automatic push after a recording (QSettings "pushAfterRecording").
    static bool autoPush();
    static void setAutoPush(bool on);
    // Called when a recording into the open (local) store has finished: pushes it when the
    // setting is on and an address is known; false when nothing was pushed (*message says why).
    bool afterRecording(qint64 sessionId, QString *message);

private:
    void askOpen();
    void askPush();

    QWidget *m_parent;
    StoreFn m_store;
    SessionFn m_session;
    OpenFn m_open;
    QString m_lastMessage;
};

} // namespace driftlab
