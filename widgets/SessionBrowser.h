#pragma once
// Lists the sessions of a store and the channels of the chosen session (checkable).

#include "StorageTypes.h"

#include <QWidget>

class QListWidget;
class QListWidgetItem;

namespace driftlab {

class SessionBrowser : public QWidget {
    Q_OBJECT
public:
    explicit SessionBrowser(QWidget *parent = nullptr);

    void setSessions(const QVector<SessionInfo> &sessions);
    void setChannels(const QVector<ChannelInfo> &channels, const QVector<qint64> &checked);
    qint64 currentSession() const;
    QVector<qint64> checkedChannels() const;
    void selectSession(qint64 sessionId);

signals:
    void sessionSelected(qint64 sessionId);
    void channelsChanged(const QVector<qint64> &channelIds);

private:
    QListWidget *m_sessions;
    QListWidget *m_channels;
    bool m_updating = false;
};

} // namespace driftlab
