#include "SessionBrowser.h"

#include "UnitLabels.h"

#include <QLabel>
#include <QListWidget>
#include <QSplitter>
#include <QVBoxLayout>

namespace driftlab {

namespace {
constexpr int kIdRole = Qt::UserRole + 1;
}

SessionBrowser::SessionBrowser(QWidget *parent)
    : QWidget(parent), m_sessions(new QListWidget(this)), m_channels(new QListWidget(this))
{
    auto *layout = new QVBoxLayout(this);
    layout->setContentsMargins(4, 4, 4, 4);
    auto *split = new QSplitter(Qt::Vertical, this);
    auto *top = new QWidget(split);
    auto *topLayout = new QVBoxLayout(top);
    topLayout->setContentsMargins(0, 0, 0, 0);
    auto *heading = new QLabel(tr("Sessions (right-click: rename, notes, delete)"), top);
    heading->setWordWrap(true); // a narrow dock must not scroll sideways for it
    topLayout->addWidget(heading);
    topLayout->addWidget(m_sessions);
    auto *bottom = new QWidget(split);
    auto *bottomLayout = new QVBoxLayout(bottom);
    bottomLayout->setContentsMargins(0, 0, 0, 0);
    bottomLayout->addWidget(new QLabel(tr("Channels"), bottom));
    bottomLayout->addWidget(m_channels);
    split->addWidget(top);
    split->addWidget(bottom);
    split->setChildrenCollapsible(false);
    split->setStretchFactor(0, 1);
    split->setStretchFactor(1, 2);
    m_sessions->setMinimumHeight(110);
    m_channels->setMinimumHeight(110);
    setMinimumWidth(220);
    layout->addWidget(split);
    connect(m_sessions, &QListWidget::currentItemChanged, this, [this](QListWidgetItem *item) {
        if (!m_updating && item)
            emit sessionSelected(item->data(kIdRole).toLongLong());
    });
    connect(m_channels, &QListWidget::itemChanged, this, [this] {
        if (!m_updating)
            emit channelsChanged(checkedChannels());
    });
}

void SessionBrowser::setSessions(const QVector<SessionInfo> &sessions)
{
    m_updating = true;
    m_sessions->clear();
    for (const SessionInfo &s : sessions) {
        const QString label = QStringLiteral("#%1  %2%3").arg(s.id).arg(s.name, s.complete ? QString() : tr("  (incomplete)"));
        auto *item = new QListWidgetItem(label, m_sessions);
        item->setData(kIdRole, s.id);
        QString tip = tr("session %1, started %2\nUUID %3").arg(s.id).arg(s.started, s.uuid);
        if (!s.operatorName.isEmpty())
            tip += tr("\noperator: %1").arg(s.operatorName);
        if (!s.notes.isEmpty())
            tip += tr("\nnotes: %1").arg(s.notes);
        item->setToolTip(tip);
    }
    m_updating = false;
}

void SessionBrowser::setChannels(const QVector<ChannelInfo> &channels, const QVector<qint64> &checked)
{
    m_updating = true;
    m_channels->clear();
    for (const ChannelInfo &c : channels) {
        auto *item = new QListWidgetItem(QStringLiteral("%1 [%2]  %3").arg(c.key, UnitLabels::display(c.unit), c.location),
                                         m_channels);
        item->setToolTip(tr("%1: %2, %3, role %4").arg(c.key, c.kind, c.sensor.isEmpty() ? tr("sensor unknown") : c.sensor,
                                                        c.role.isEmpty() ? tr("none") : c.role));
        item->setData(kIdRole, c.id);
        item->setFlags(item->flags() | Qt::ItemIsUserCheckable);
        item->setCheckState(checked.contains(c.id) ? Qt::Checked : Qt::Unchecked);
    }
    m_updating = false;
}

qint64 SessionBrowser::currentSession() const
{
    const QListWidgetItem *item = m_sessions->currentItem();
    return item ? item->data(kIdRole).toLongLong() : 0;
}

QVector<qint64> SessionBrowser::checkedChannels() const
{
    QVector<qint64> ids;
    for (int i = 0; i < m_channels->count(); ++i) {
        const QListWidgetItem *item = m_channels->item(i);
        if (item->checkState() == Qt::Checked)
            ids.push_back(item->data(kIdRole).toLongLong());
    }
    return ids;
}

void SessionBrowser::selectSession(qint64 sessionId)
{
    for (int i = 0; i < m_sessions->count(); ++i) {
        if (m_sessions->item(i)->data(kIdRole).toLongLong() == sessionId) {
            m_updating = true;
            m_sessions->setCurrentRow(i);
            m_updating = false;
            return;
        }
    }
}

} // namespace driftlab
