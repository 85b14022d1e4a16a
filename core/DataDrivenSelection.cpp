#include "DataDrivenSelection.h"

#include "DataDrivenModelJson.h"
#include "DataDrivenSession.h"
#include "SessionStore.h"

#include <QJsonArray>

#include <algorithm>
#include <stdexcept>

namespace driftlab {

namespace {

[[noreturn]] void bad(const QString &message)
{
    throw std::invalid_argument(message.toStdString());
}

QJsonArray jsonStrings(const std::vector<std::string> &v)
{
    QJsonArray a;
    for (const std::string &s : v)
        a.append(QString::fromStdString(s));
    return a;
}

std::vector<std::string> toStd(const QStringList &list)
{
    std::vector<std::string> out;
    for (const QString &s : list)
        out.push_back(s.toStdString());
    return out;
}

} // namespace

DataDrivenSelection::DataDrivenSelection(const SessionStore &store) : m_store(store) {}

QJsonObject DataDrivenSelection::json(const SelectionResult &r)
{
    QJsonArray perK;
    for (const ClusteringForK &e : r.perK) {
        QJsonArray clusters;
        for (int c = 0; c < e.k; ++c) {
            QJsonArray members;
            for (std::size_t i = 0; i < e.labels.size(); ++i)
                if (e.labels[i] == c)
                    members.append(QString::fromStdString(r.channels[i]));
            clusters.append(members);
        }
        perK.append(QJsonObject{{QStringLiteral("k"), e.k},
                                {QStringLiteral("silhouette"), e.silhouette},
                                {QStringLiteral("compactness"), e.compactness},
                                {QStringLiteral("clusters"), clusters}});
    }
    QJsonArray channels;
    for (std::size_t i = 0; i < r.channels.size(); ++i) {
        const bool chosen = std::find(r.chosen.begin(), r.chosen.end(), r.channels[i]) != r.chosen.end();
        channels.append(QJsonObject{{QStringLiteral("channel"), QString::fromStdString(r.channels[i])},
                                    {QStringLiteral("cluster"), r.labels[i] + 1},
                                    {QStringLiteral("grade"), r.grade[i]},
                                    {QStringLiteral("grade_all"), r.gradeAll[i]},
                                    {QStringLiteral("correlation"), r.correlation[i]},
                                    {QStringLiteral("chosen"), chosen}});
    }
    QJsonArray excluded;
    for (const ExcludedChannel &e : r.excluded)
        excluded.append(QJsonObject{{QStringLiteral("channel"), QString::fromStdString(e.id)},
                                    {QStringLiteral("reason"), QString::fromStdString(e.reason)}});
    QJsonArray matrix;
    const std::size_t n = r.channels.size();
    for (std::size_t i = 0; i < n && r.correlationMatrix.size() == n * n; ++i)
        matrix.append(DataDrivenModelJson::numbers(std::vector<double>(r.correlationMatrix.begin() + static_cast<std::ptrdiff_t>(i * n),
                                                      r.correlationMatrix.begin() + static_cast<std::ptrdiff_t>((i + 1) * n))));
    QJsonArray clusters;
    for (const std::vector<int> &members : r.clusters) {
        QJsonArray m;
        for (int i : members)
            m.append(QString::fromStdString(r.channels[static_cast<std::size_t>(i)]));
        clusters.append(m);
    }
    return QJsonObject{{QStringLiteral("target"), QString::fromStdString(r.target)},
                       {QStringLiteral("samples"), static_cast<double>(r.rows)},
                       {QStringLiteral("from_s"), r.from_s},
                       {QStringLiteral("to_s"), r.to_s},
                       {QStringLiteral("k"), r.chosenK},
                       {QStringLiteral("silhouettes"), perK},
                       {QStringLiteral("clusters"), clusters},
                       {QStringLiteral("channels"), channels},
                       {QStringLiteral("chosen"), jsonStrings(r.chosen)},
                       {QStringLiteral("excluded"), excluded},
                       {QStringLiteral("correlation_matrix"), matrix},
                       {QStringLiteral("rule"), QString::fromStdString(r.rule)}};
}

SelectionResult DataDrivenSelection::select(const QList<qint64> &sessions, const QString &target, const HourRange &range,
                                            int kMin, int kMax, const QStringList &channels, const DataDrivenFit::Progress &progress) const
{
    if (sessions.isEmpty())
        bad(QStringLiteral("select-points: no session given"));
    std::vector<SignalTable> tables;
    std::vector<std::vector<char>> rows;
    std::vector<std::string> temperatures;
    for (qint64 id : sessions) {
        const DataDrivenSession s(m_store, id);
        if (!s.hasChannel(target))
            bad(QStringLiteral("--target: session %1 has no channel '%2'").arg(id).arg(target));
        for (const QString &c : channels)
            if (!s.hasChannel(c))
                bad(QStringLiteral("--channels: session %1 has no channel '%2'").arg(id).arg(c));
        if (progress && !progress(0.2 * static_cast<double>(tables.size()) / static_cast<double>(sessions.size()),
                                  QStringLiteral("reading session %1").arg(id)))
            throw std::runtime_error("cancelled");
        tables.push_back(s.table(target));
        rows.push_back(tables.back().rowsIn(range.from_h * 3600.0, range.to_h * 3600.0));
        if (temperatures.empty())
            temperatures = toStd(s.temperatureChannels());
    }
    SelectionOptions o;
    o.target = target.toStdString();
    o.channels = toStd(channels);
    o.kMin = kMin;
    o.kMax = kMax;
    SignalTable joined;
    const SignalTable *table = &tables.front();
    if (tables.size() == 1) {
        o.rows = rows.front();
    } else {
        std::vector<const SignalTable *> runs;
        for (const SignalTable &t : tables)
            runs.push_back(&t);
        joined = SignalTable::concatenate(runs, rows, 0.0, {}, temperatures, &o.rows);
        table = &joined;
    }
    return SensitivePointSelector::select(*table, o, [&](double f) {
        return !progress || progress(0.2 + 0.8 * f, QStringLiteral("K-means and grey grades"));
    });
}

} // namespace driftlab
