#include "CentralStoreActions.h"

#include "SessionCopier.h"
#include "SessionStore.h"
#include "StorageError.h"

#include <QAction>
#include <QApplication>
#include <QInputDialog>
#include <QMenu>
#include <QMessageBox>
#include <QProgressDialog>
#include <QSettings>
#include <QUrl>
#include <QWidget>

namespace driftlab {

CentralStoreActions::CentralStoreActions(QWidget *parent, StoreFn store, SessionFn session, OpenFn open)
    : QObject(parent), m_parent(parent), m_store(std::move(store)), m_session(std::move(session)), m_open(std::move(open))
{
}

void CentralStoreActions::addTo(QMenu *file)
{
    file->addAction(tr("Open &central store..."), this, &CentralStoreActions::askOpen)->setObjectName(QStringLiteral("OpenCentralAction"));
    file->addAction(tr("&Push session to central store..."), this, &CentralStoreActions::askPush)
        ->setObjectName(QStringLiteral("PushSessionAction"));
    QAction *automatic = file->addAction(tr("Push recordings &automatically"));
    automatic->setObjectName(QStringLiteral("AutoPushAction"));
    automatic->setCheckable(true);
    automatic->setChecked(autoPush());
    automatic->setToolTip(tr("After each recording, push the session to the central store last used"));
    connect(automatic, &QAction::toggled, this, [this](bool on) {
        if (on && address().isEmpty()) {
            QMessageBox::information(m_parent, tr("Push recordings automatically"),
                                     tr("Push a session once (File > Push session to central store) so that DriftLab knows where to."));
        }
        setAutoPush(on);
    });
}

bool CentralStoreActions::autoPush()
{
    return QSettings().value(QStringLiteral("pushAfterRecording"), false).toBool();
}

void CentralStoreActions::setAutoPush(bool on)
{
    QSettings().setValue(QStringLiteral("pushAfterRecording"), on);
}

bool CentralStoreActions::afterRecording(qint64 sessionId, QString *message)
{
    if (!autoPush() || address().isEmpty()) {
        if (message)
            *message = tr("Automatic push is off");
        return false;
    }
    return push(address(), sessionId, message, false);
}

QString CentralStoreActions::address()
{
    return QSettings().value(QStringLiteral("centralStore")).toString();
}

void CentralStoreActions::setAddress(const QString &address)
{
    QSettings().setValue(QStringLiteral("centralStore"), SessionStore::displayPath(address)); // never a password
}

void CentralStoreActions::askOpen()
{
    bool ok = false;
    const QString a = QInputDialog::getText(m_parent, tr("Open central store"),
                                            tr("Address of the lab's PostgreSQL store\n(the password comes from PGPASSWORD or ~/.pgpass):"),
                                            QLineEdit::Normal,
                                            address().isEmpty() ? QStringLiteral("postgresql://USER@HOST:5432/driftlab") : address(), &ok)
                            .trimmed();
    if (!ok || a.isEmpty())
        return;
    if (!SessionStore::isCentral(a)) {
        QMessageBox::warning(m_parent, tr("Open central store"), tr("Expected postgresql://USER@HOST[:PORT]/DATABASE, got '%1'").arg(a));
        return;
    }
    if (m_open(a))
        setAddress(a);
}

void CentralStoreActions::askPush()
{
    SessionStore *store = m_store();
    const qint64 session = m_session();
    if (!store || session <= 0 || store->isCentralStore()) {
        QMessageBox::information(m_parent, tr("Push session"),
                                 tr("Open a local database and select the session to push (File > Open database)."));
        return;
    }
    bool ok = false;
    const QString a = QInputDialog::getText(m_parent, tr("Push session to central store"), tr("Central store:"), QLineEdit::Normal,
                                            address().isEmpty() ? QStringLiteral("postgresql://USER@HOST:5432/driftlab") : address(), &ok)
                            .trimmed();
    if (!ok || a.isEmpty())
        return;
    QString message;
    const bool done = push(a, session, &message);
    if (done)
        setAddress(a);
    if (done)
        QMessageBox::information(m_parent, tr("Push session"), message);
    else
        QMessageBox::warning(m_parent, tr("Push session"), message);
}

bool CentralStoreActions::push(const QString &address, qint64 sessionId, QString *message, bool interactive)
{
    SessionStore *store = m_store();
    QString text;
    bool ok = false;
    if (!store || !SessionStore::isCentral(address)) {
        text = tr("Expected postgresql://USER@HOST[:PORT]/DATABASE, got '%1'").arg(SessionStore::displayPath(address));
    } else {
        QProgressDialog progress(tr("Pushing session %1 to %2...").arg(sessionId).arg(SessionStore::displayPath(address)), tr("Cancel"), 0,
                                 1000, m_parent);
        progress.setWindowModality(Qt::WindowModal);
        progress.setMinimumDuration(interactive ? 300 : 1000000000);
        try {
            QApplication::setOverrideCursor(Qt::WaitCursor);
            SessionStore central(address);
            const SessionCopier::Result r = SessionCopier::copy(*store, sessionId, central, [&](double f) {
                progress.setValue(static_cast<int>(1000.0 * f));
                QApplication::processEvents();
                return !progress.wasCanceled();
            });
            text = r.alreadyThere ? tr("Session %1 is already in %2 (session %3, same content): nothing changed.")
                                        .arg(sessionId)
                                        .arg(central.path())
                                        .arg(r.targetId)
                                  : tr("Session %1 pushed to %2 as session %3: %4 samples, %5 frames; verified.")
                                        .arg(sessionId)
                                        .arg(central.path())
                                        .arg(r.targetId)
                                        .arg(r.counts.samples)
                                        .arg(r.counts.frames);
            ok = true;
        } catch (const StorageError &e) {
            text = tr("Push failed, nothing was written to the central store; the session stays here.\n%1").arg(QString::fromUtf8(e.what()));
        }
        QApplication::restoreOverrideCursor();
    }
    m_lastMessage = text;
    if (message)
        *message = text;
    return ok;
}

} // namespace driftlab
