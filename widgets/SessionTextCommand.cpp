#include "SessionTextCommand.h"

#include "SessionStore.h"

#include <QCoreApplication>

namespace driftlab {

SessionTextCommand::SessionTextCommand(SessionStore &store, qint64 sessionId, Field field, const QString &before,
                                       const QString &after, std::function<void(qint64)> changed)
    : m_store(store), m_session(sessionId), m_field(field), m_before(before), m_after(after), m_changed(std::move(changed))
{
    setText(field == Field::Name ? QCoreApplication::translate("SessionTextCommand", "rename session %1").arg(sessionId)
                                 : QCoreApplication::translate("SessionTextCommand", "notes of session %1").arg(sessionId));
}

void SessionTextCommand::apply(const QString &value)
{
    if (m_field == Field::Name)
        m_store.renameSession(m_session, value);
    else
        m_store.setSessionNotes(m_session, value);
    if (m_changed)
        m_changed(m_session);
}

void SessionTextCommand::redo()
{
    apply(m_after);
}

void SessionTextCommand::undo()
{
    apply(m_before);
}

} // namespace driftlab
