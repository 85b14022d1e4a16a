#pragma once
// The sessions of a store as a table (issue 33 item 4: id, name, start, duration, operator,
// rig, notes, complete / incomplete / recording), searchable (every column) and sortable
// (numbers as numbers), and the channels of the chosen session (checkable) below it, in a
// splitter that never squeezes either away. In a narrow dock the less important columns
// hide instead of eliding (priority: name, state, start, duration, id, operator, rig,
// notes); every row's tooltip has them all.

#include "StorageTypes.h"

#include <QHash>
#include <QWidget>

class QLineEdit;
class QListWidget;
class QSortFilterProxyModel;
class QStandardItemModel;
class QTableView;

namespace driftlab {

class SessionStore;

class SessionBrowser : public QWidget {
    Q_OBJECT
public:
    enum Column { Id, Name, Started, Duration, Operator, Rig, Notes, State, Columns };

    explicit SessionBrowser(QWidget *parent = nullptr);

    // The sessions; with a local `store`, each one's duration is read from its channels'
    // coarsest mipmap (a central store's list shows none: thousands of sessions).
    void setSessions(const QVector<SessionInfo> &sessions, const SessionStore *store = nullptr);
    // The session being recorded (0: none): its state reads "recording".
    void setRecordingSession(qint64 sessionId);
    void setChannels(const QVector<ChannelInfo> &channels, const QVector<qint64> &checked);
    qint64 currentSession() const;
    QVector<qint64> checkedChannels() const;
    void selectSession(qint64 sessionId);

    // The table as shown (after search and sort): rows, their session ids and cell texts.
    int sessionCount() const;
    qint64 sessionAt(int row) const;
    QString text(int row, Column column) const;
    // Searches every column (case-insensitive, plain text); "" shows all.
    void setSearch(const QString &text);
    void sortBy(Column column, Qt::SortOrder order);
    // The table (MainWindow adds rename / notes / delete to its context menu).
    QTableView *sessionTable() const { return m_table; }
    QLineEdit *searchBox() const { return m_search; }
    // The rig a session was recorded with: the rig file's name, the simulated rig's, or the
    // machine and axis of the manifest.
    static QString rigName(const SessionInfo &session);

signals:
    void sessionSelected(qint64 sessionId);
    void channelsChanged(const QVector<qint64> &channelIds);

protected:
    bool eventFilter(QObject *watched, QEvent *event) override;

private:
    void fitColumns();
    void updateStates();

    QLineEdit *m_search;
    QStandardItemModel *m_model;
    QSortFilterProxyModel *m_proxy;
    QTableView *m_table;
    QListWidget *m_channels;
    QHash<qint64, bool> m_complete;
    qint64 m_recording = 0;
    bool m_updating = false;
};

} // namespace driftlab
