#include "Workbench.h"

#include "BundleTransfer.h"
#include "ImporterRegistry.h"
#include "DuplicateSessionError.h"
#include "SessionStore.h"
#include "SessionTextCommand.h"

#include <QDir>
#include <QFileInfo>
#include <QSettings>
#include <QUndoStack>

namespace driftlab {

namespace {
constexpr int kMaxRecent = 8;
const char *kRecentKey = "recentDatabases";

bool containsSession(const QVector<SessionInfo> &sessions, qint64 id)
{
    for (const SessionInfo &s : sessions)
        if (s.id == id)
            return true;
    return false;
}
} // namespace

Workbench::Workbench(QObject *parent) : QObject(parent), m_undo(new QUndoStack(this)) {}

Workbench::~Workbench()
{
    m_undo->clear(); // commands refer to the store
}

QString Workbench::localPath() const
{
    if (!m_store || m_store->isCentralStore())
        return QString();
    return QFileInfo(m_store->path()).absoluteFilePath();
}

void Workbench::reportError(const QString &error)
{
    m_lastError = error;
    emit failed(error);
}

void Workbench::addGuard(QObject *owner, Guard guard)
{
    m_guards.emplace_back(QPointer<QObject>(owner), std::move(guard));
}

QString Workbench::objection(qint64 sessionId) const
{
    for (const auto &g : m_guards) {
        if (!g.first)
            continue;
        const QString why = g.second(sessionId);
        if (!why.isEmpty())
            return why;
    }
    return QString();
}

bool Workbench::newDatabase(const QString &path)
{
    if (QFileInfo::exists(path)) {
        reportError(tr("%1 already exists: open it with File > Open database, or choose a new name").arg(path));
        return false;
    }
    if (!QDir().mkpath(QFileInfo(path).absolutePath())) {
        reportError(tr("Cannot create the folder %1").arg(QFileInfo(path).absolutePath()));
        return false;
    }
    return openDatabase(path);
}

bool Workbench::openDatabase(const QString &path)
{
    const QString why = objection(0);
    if (!why.isEmpty()) {
        reportError(why);
        return false;
    }
    std::unique_ptr<SessionStore> store;
    try {
        store = std::make_unique<SessionStore>(path);
    } catch (const std::exception &e) {
        reportError(QString::fromStdString(e.what()));
        return false;
    }
    m_undo->clear();
    m_session = 0;
    m_sessions.clear();
    // Those holding the old store let go of it before it closes.
    emit sessionChanged(0);
    emit storeChanged(nullptr);
    m_store = std::move(store);
    rememberDatabase(path);
    emit recentDatabasesChanged();
    emit storeChanged(m_store.get());
    refreshSessions(0);
    emit message(tr("Opened %1").arg(m_store->path())); // the count is the window's permanent summary
    return true;
}

void Workbench::refreshSessions(qint64 select)
{
    if (!m_store)
        return;
    try {
        m_sessions = m_store->sessions();
    } catch (const std::exception &e) {
        reportError(QString::fromStdString(e.what()));
        return;
    }
    emit sessionsChanged(m_sessions);
    qint64 id = 0;
    if (containsSession(m_sessions, select))
        id = select;
    else if (containsSession(m_sessions, m_session))
        id = m_session;
    else if (!m_sessions.isEmpty())
        id = m_sessions.back().id;
    m_session = -1; // says it again: views re-read the session after a change of the list
    setCurrentSession(id);
}

void Workbench::setCurrentSession(qint64 sessionId)
{
    if (sessionId != 0 && !containsSession(m_sessions, sessionId))
        return;
    if (sessionId == m_session)
        return;
    m_session = sessionId;
    emit sessionChanged(sessionId);
}

void Workbench::recordingChanged(const QString &databasePath, qint64 sessionId)
{
    if (!m_store || localPath() != QFileInfo(databasePath).absoluteFilePath())
        return;
    refreshSessions(sessionId);
}

bool Workbench::renameSession(qint64 sessionId, const QString &name)
{
    if (!m_store)
        return false;
    try {
        const QString before = m_store->session(sessionId).name;
        if (name.trimmed() == before)
            return true;
        if (name.trimmed().isEmpty()) {
            reportError(tr("A session name must not be empty"));
            return false;
        }
        m_undo->push(new SessionTextCommand(*m_store, sessionId, SessionTextCommand::Field::Name, before, name.trimmed(),
                                            [this](qint64 id) { refreshSessions(id); }));
        return true;
    } catch (const std::exception &e) {
        reportError(QString::fromStdString(e.what()));
        return false;
    }
}

bool Workbench::setSessionNotes(qint64 sessionId, const QString &notes)
{
    if (!m_store)
        return false;
    try {
        const QString before = m_store->session(sessionId).notes;
        if (notes == before)
            return true;
        m_undo->push(new SessionTextCommand(*m_store, sessionId, SessionTextCommand::Field::Notes, before, notes,
                                            [this](qint64) {
                                                m_sessions = m_store->sessions();
                                                emit sessionsChanged(m_sessions);
                                            }));
        return true;
    } catch (const std::exception &e) {
        reportError(QString::fromStdString(e.what()));
        return false;
    }
}

bool Workbench::deleteSession(qint64 sessionId)
{
    if (!m_store)
        return false;
    const QString why = objection(sessionId);
    if (!why.isEmpty()) {
        reportError(why);
        return false;
    }
    try {
        const QString name = m_store->session(sessionId).name;
        m_store->deleteSession(sessionId);
        m_undo->clear(); // earlier edits may refer to the deleted session
        if (m_session == sessionId) {
            m_session = 0;
            emit sessionChanged(0);
        }
        refreshSessions(m_session);
        emit message(tr("Deleted session %1 '%2'").arg(sessionId).arg(name));
        return true;
    } catch (const std::exception &e) {
        reportError(QString::fromStdString(e.what()));
        return false;
    }
}

qint64 Workbench::importBundle(const QString &path, bool allowDuplicate, qint64 *duplicateOf)
{
    return importFile(path, allowDuplicate, duplicateOf);
}

qint64 Workbench::importFile(const QString &path, bool allowDuplicate, qint64 *duplicateOf)
{
    if (duplicateOf)
        *duplicateOf = 0;
    if (!m_store) {
        reportError(tr("Open a database before importing %1 (File > New database or Open database)").arg(path));
        return 0;
    }
    try {
        const ImporterRegistry registry;
        const SessionImporter *importer = registry.find(path);
        if (!importer) {
            reportError(tr("%1: not a file DriftLab imports (a bundle, a session database, an .rtl or CSV file)").arg(path));
            return 0;
        }
        SessionImporter::Options options;
        options.allowDuplicate = allowDuplicate;
        options.session = m_session;
        const QList<qint64> ids = importer->import(path, *m_store, options);
        const qint64 id = ids.isEmpty() ? 0 : ids.back();
        refreshSessions(id);
        emit message(tr("Imported %1 as session %2").arg(path).arg(id));
        return id;
    } catch (const DuplicateSessionError &e) {
        if (duplicateOf)
            *duplicateOf = e.existingSession();
        m_lastError = QString::fromStdString(e.what());
        return 0;
    } catch (const std::exception &e) {
        // Nothing was imported: the store rolls the whole bundle back.
        reportError(QString::fromStdString(e.what()));
        return 0;
    }
}

bool Workbench::exportSession(qint64 sessionId, const QString &out)
{
    if (!m_store || sessionId <= 0)
        return false;
    try {
        BundleTransfer::exportBundle(*m_store, sessionId, out);
        emit message(tr("Exported session %1 to %2").arg(sessionId).arg(out));
        return true;
    } catch (const std::exception &e) {
        reportError(QString::fromStdString(e.what()));
        return false;
    }
}

QStringList Workbench::recentDatabases()
{
    return QSettings().value(QLatin1String(kRecentKey)).toStringList();
}

void Workbench::rememberDatabase(const QString &path)
{
    QSettings settings;
    QStringList recent = settings.value(QLatin1String(kRecentKey)).toStringList();
    const QString abs = SessionStore::isCentral(path) ? SessionStore::displayPath(path) : QFileInfo(path).absoluteFilePath();
    recent.removeAll(abs);
    recent.prepend(abs);
    while (recent.size() > kMaxRecent)
        recent.removeLast();
    settings.setValue(QLatin1String(kRecentKey), recent);
    settings.setValue(QStringLiteral("lastDatabase"), abs);
}

} // namespace driftlab
