#pragma once
// An undoable edit of a session's name or notes in the open database (Edit > Undo).

#include <QString>
#include <QUndoCommand>

#include <functional>

namespace driftlab {

class SessionStore;

class SessionTextCommand : public QUndoCommand {
public:
    enum class Field { Name, Notes };
    // `changed` runs after every redo/undo (to refresh views). The store must outlive the
    // command: MainWindow clears its undo stack before it closes a database.
    SessionTextCommand(SessionStore &store, qint64 sessionId, Field field, const QString &before, const QString &after,
                       std::function<void(qint64)> changed);
    void redo() override;
    void undo() override;

private:
    void apply(const QString &value);

    SessionStore &m_store;
    qint64 m_session;
    Field m_field;
    QString m_before, m_after;
    std::function<void(qint64)> m_changed;
};

} // namespace driftlab
