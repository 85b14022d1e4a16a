#include "SessionBrowser.h"

#include "SessionStore.h"
#include "UnitLabels.h"

#include <QDateTime>
#include <QHeaderView>
#include <QJsonObject>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QEvent>
#include <QSortFilterProxyModel>
#include <QSplitter>
#include <QStandardItemModel>
#include <QStyle>
#include <QTableView>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>

namespace driftlab {

namespace {
constexpr int kIdRole = Qt::UserRole + 1;
constexpr int kSortRole = Qt::UserRole + 2;

QString hms(double s)
{
    const qint64 t = static_cast<qint64>(std::llround(s));
    return QStringLiteral("%1:%2:%3").arg(t / 3600).arg((t / 60) % 60, 2, 10, QLatin1Char('0')).arg(t % 60, 2, 10, QLatin1Char('0'));
}

// Elapsed time of the last sample of any channel (-1: no samples). Cheap: one bucket of the
// coarsest mipmap level per channel.
double lastSample(const SessionStore &store, qint64 sessionId)
{
    double last = -1.0;
    for (const ChannelInfo &c : store.channels(sessionId)) {
        const DecimatedSeries d = store.decimated(c.id, -1e300, 1e300, 1);
        if (!d.tLast.isEmpty())
            last = std::max(last, *std::max_element(d.tLast.begin(), d.tLast.end()));
    }
    return last;
}

// Columns in the order they give way when the dock is narrow (last hides first).
const SessionBrowser::Column kPriority[] = {SessionBrowser::Name,     SessionBrowser::State, SessionBrowser::Started,
                                            SessionBrowser::Duration, SessionBrowser::Id,    SessionBrowser::Operator,
                                            SessionBrowser::Rig,      SessionBrowser::Notes};
} // namespace

SessionBrowser::SessionBrowser(QWidget *parent)
    : QWidget(parent),
      m_search(new QLineEdit(this)),
      m_model(new QStandardItemModel(0, Columns, this)),
      m_proxy(new QSortFilterProxyModel(this)),
      m_table(new QTableView(this)),
      m_channels(new QListWidget(this))
{
    m_model->setHorizontalHeaderLabels({tr("id"), tr("name"), tr("start (UTC)"), tr("duration"), tr("operator"), tr("rig"),
                                        tr("notes"), tr("state")});
    m_proxy->setSourceModel(m_model);
    m_proxy->setSortRole(kSortRole);
    m_proxy->setFilterKeyColumn(-1);
    m_proxy->setFilterCaseSensitivity(Qt::CaseInsensitive);
    m_search->setObjectName(QStringLiteral("SessionSearch"));
    m_search->setPlaceholderText(tr("Search sessions (name, operator, rig, notes...)"));
    m_search->setClearButtonEnabled(true);
    m_table->setObjectName(QStringLiteral("SessionTable"));
    m_table->setModel(m_proxy);
    m_table->setSortingEnabled(true);
    m_table->sortByColumn(Id, Qt::AscendingOrder);
    m_table->setSelectionBehavior(QAbstractItemView::SelectRows);
    m_table->setSelectionMode(QAbstractItemView::SingleSelection);
    m_table->setEditTriggers(QAbstractItemView::NoEditTriggers);
    m_table->setWordWrap(false);
    m_table->verticalHeader()->hide();
    m_table->verticalHeader()->setDefaultSectionSize(fontMetrics().height() + 6);
    m_table->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
    m_table->horizontalHeader()->setSectionResizeMode(Name, QHeaderView::Stretch);
    m_table->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff); // columns hide instead (fitColumns)
    m_table->setMinimumHeight(110);
    m_channels->setMinimumHeight(110);

    auto *layout = new QVBoxLayout(this);
    layout->setContentsMargins(4, 4, 4, 4);
    auto *split = new QSplitter(Qt::Vertical, this);
    auto *top = new QWidget(split);
    auto *topLayout = new QVBoxLayout(top);
    topLayout->setContentsMargins(0, 0, 0, 0);
    auto *heading = new QLabel(tr("Sessions (right-click: rename, notes, delete)"), top);
    heading->setWordWrap(true); // a narrow dock must not scroll sideways for it
    topLayout->addWidget(heading);
    topLayout->addWidget(m_search);
    topLayout->addWidget(m_table);
    auto *bottom = new QWidget(split);
    auto *bottomLayout = new QVBoxLayout(bottom);
    bottomLayout->setContentsMargins(0, 0, 0, 0);
    bottomLayout->addWidget(new QLabel(tr("Channels"), bottom));
    bottomLayout->addWidget(m_channels);
    split->addWidget(top);
    split->addWidget(bottom);
    split->setChildrenCollapsible(false);
    split->setStretchFactor(0, 1);
    split->setStretchFactor(1, 1);
    // Wide enough for name, state and start without eliding (tst_sessionbrowser); the other
    // columns show when the dock is made wider.
    const QFontMetrics fm = fontMetrics();
    setMinimumWidth(std::max(220, 120 + fm.horizontalAdvance(QStringLiteral("2026-11-27 06:05")) +
                                      fm.horizontalAdvance(tr("incomplete")) + 60 + style()->pixelMetric(QStyle::PM_ScrollBarExtent)));
    layout->addWidget(split);

    m_table->viewport()->installEventFilter(this);
    connect(m_search, &QLineEdit::textChanged, this, &SessionBrowser::setSearch);
    connect(m_table->selectionModel(), &QItemSelectionModel::currentRowChanged, this, [this](const QModelIndex &current) {
        if (!m_updating && current.isValid())
            emit sessionSelected(current.siblingAtColumn(Id).data(kIdRole).toLongLong());
    });
    connect(m_channels, &QListWidget::itemChanged, this, [this] {
        if (!m_updating)
            emit channelsChanged(checkedChannels());
    });
}

QString SessionBrowser::rigName(const SessionInfo &s)
{
    for (const char *key : {"rig", "simulated_rig"}) {
        const QString name = s.manifest.value(QLatin1String(key)).toObject().value(QStringLiteral("name")).toString();
        if (!name.isEmpty())
            return name;
    }
    const QString machine = s.machine.value(QStringLiteral("name")).toString();
    const QString axis = s.machine.value(QStringLiteral("axis")).toString();
    return axis.isEmpty() ? machine : machine.isEmpty() ? axis : QStringLiteral("%1, %2").arg(machine, axis);
}

void SessionBrowser::setSessions(const QVector<SessionInfo> &sessions, const SessionStore *store)
{
    const qint64 current = currentSession();
    m_updating = true;
    m_model->removeRows(0, m_model->rowCount());
    m_complete.clear();
    const bool durations = store && !store->isCentralStore();
    for (const SessionInfo &s : sessions) {
        double last = -1.0;
        if (durations) {
            try {
                last = lastSample(*store, s.id);
            } catch (const std::exception &) {
                last = -1.0; // a session the store cannot read lists without a duration
            }
        }
        const QString rig = rigName(s);
        const QString notes = QString(s.notes).replace(QLatin1Char('\n'), QLatin1Char(' '));
        QList<QStandardItem *> row;
        const auto add = [&row](const QString &text, const QVariant &sort) {
            auto *item = new QStandardItem(text);
            item->setData(sort, kSortRole);
            row << item;
        };
        add(QString::number(s.id), s.id);
        add(s.name, s.name.toLower());
        add(UnitLabels::startTime(s.started), s.started);
        add(last >= 0 ? hms(last) : QStringLiteral("-"), last);
        add(s.operatorName, s.operatorName.toLower());
        add(rig, rig.toLower());
        add(notes, notes.toLower());
        add(QString(), 0); // state: updateStates()
        row[Id]->setData(s.id, kIdRole);
        row[Id]->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
        row[Duration]->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
        QString tip = tr("session %1 \"%2\", started %3\nduration %4, rig %5\nUUID %6")
                          .arg(s.id)
                          .arg(s.name, s.started, last >= 0 ? hms(last) : tr("unknown"), rig.isEmpty() ? tr("unknown") : rig, s.uuid);
        if (!s.operatorName.isEmpty())
            tip += tr("\noperator: %1").arg(s.operatorName);
        if (!s.notes.isEmpty())
            tip += tr("\nnotes: %1").arg(s.notes);
        for (QStandardItem *item : row)
            item->setToolTip(tip);
        m_model->appendRow(row);
        m_complete.insert(s.id, s.complete);
    }
    updateStates();
    m_updating = false;
    selectSession(current);
    fitColumns();
}

void SessionBrowser::setRecordingSession(qint64 sessionId)
{
    m_recording = sessionId;
    updateStates();
}

void SessionBrowser::updateStates()
{
    for (int r = 0; r < m_model->rowCount(); ++r) {
        const qint64 id = m_model->item(r, Id)->data(kIdRole).toLongLong();
        QStandardItem *state = m_model->item(r, State);
        const bool recording = id == m_recording;
        const bool complete = m_complete.value(id);
        state->setText(recording ? tr("recording") : complete ? tr("complete") : tr("incomplete"));
        state->setData(recording ? 2 : complete ? 0 : 1, kSortRole);
        state->setForeground(recording ? QBrush(QColor(200, 30, 30)) : complete ? QBrush() : QBrush(QColor(150, 100, 0)));
    }
}

bool SessionBrowser::eventFilter(QObject *watched, QEvent *event)
{
    // The table's own width, whenever it changes (a splitter or dock resizes it after us).
    if (watched == m_table->viewport() && event->type() == QEvent::Resize)
        fitColumns();
    return QWidget::eventFilter(watched, event);
}

void SessionBrowser::fitColumns()
{
    // As many columns as fit the table's width at their full contents, in priority order;
    // the name stretches into what is left (and needs at least its header).
    // The name keeps what it needs (leaving room for state and start, at least 120 px)
    // before any column after them is shown.
    const int width = m_table->viewport()->width();
    int need[Columns];
    for (int c = 0; c < Columns; ++c) {
        // A hidden section's size hint is 1 px: on an empty table (no cells to measure) every
        // column then "fitted" and the first start's table scrolled sideways by 293 px.
        m_table->setColumnHidden(c, false);
        need[c] = std::max(static_cast<const QAbstractItemView *>(m_table)->sizeHintForColumn(c),
                           m_table->horizontalHeader()->sectionSizeHint(c));
    }
    const int nameReserve = std::max(120, std::min(need[Name], width - need[State] - need[Started]));
    int used = 0;
    for (const Column c : kPriority) {
        const bool fits = c == Name || used + need[c] <= width;
        m_table->setColumnHidden(c, !fits);
        if (fits)
            used += c == Name ? nameReserve : need[c];
    }
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
    const QModelIndex current = m_table->selectionModel()->currentIndex();
    return current.isValid() ? current.siblingAtColumn(Id).data(kIdRole).toLongLong() : 0;
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
    for (int r = 0; r < m_proxy->rowCount(); ++r) {
        if (m_proxy->index(r, Id).data(kIdRole).toLongLong() == sessionId) {
            m_updating = true;
            m_table->selectionModel()->setCurrentIndex(m_proxy->index(r, Name),
                                                       QItemSelectionModel::ClearAndSelect | QItemSelectionModel::Rows);
            m_updating = false;
            return;
        }
    }
}

int SessionBrowser::sessionCount() const
{
    return m_proxy->rowCount();
}

qint64 SessionBrowser::sessionAt(int row) const
{
    return m_proxy->index(row, Id).data(kIdRole).toLongLong();
}

QString SessionBrowser::text(int row, Column column) const
{
    return m_proxy->index(row, column).data().toString();
}

void SessionBrowser::setSearch(const QString &text)
{
    if (m_search->text() != text)
        m_search->setText(text); // comes back here through textChanged
    m_proxy->setFilterFixedString(text);
}

void SessionBrowser::sortBy(Column column, Qt::SortOrder order)
{
    m_table->sortByColumn(column, order);
}

} // namespace driftlab
