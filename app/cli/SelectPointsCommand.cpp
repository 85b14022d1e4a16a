#include "SelectPointsCommand.h"

#include "CliSupport.h"
#include "CliOptions.h"
#include "OutputTarget.h"
#include "SessionArgument.h"
#include "DataDrivenFitCommand.h"
#include "PointSelection.h"
#include "SessionStore.h"

#include <QCommandLineParser>
#include <QJsonArray>
#include <QTextStream>

#include <stdexcept>

namespace driftlab {

QString SelectPointsCommand::summary() const
{
    return QStringLiteral(
        "Select temperature-sensitive points for a displacement channel (seed 003 Algorithm 1): z-scored\n"
        "temperature rises, K-means (k-means++, 10 attempts) for every K in --k-range, K by the silhouette\n"
        "coefficient, in each cluster the channel with the highest Deng grey relational grade (rho 0.5).\n"
        "Prints the silhouette of every K, the clusters, every grade and the chosen points; stores the result\n"
        "with the session for 'plot --view selection-grades|selection-clusters|selection-points'.");
}

int SelectPointsCommand::run(const QStringList &args)
{
    const QString cmd = name();
    QCommandLineParser p;
    const QCommandLineOption db = CliOptions::db();
    const QCommandLineOption target(QStringLiteral("target"), QStringLiteral("Displacement channel."), QStringLiteral("channel"));
    const QCommandLineOption kRange(QStringLiteral("k-range"), QStringLiteral("Range of K (default 2:8)."), QStringLiteral("K:K"),
                                    QStringLiteral("2:8"));
    const QCommandLineOption channels(QStringLiteral("channels"),
                                      QStringLiteral("Candidate channels ID,ID,... (default: every temperature)."),
                                      QStringLiteral("ids"));
    const QCommandLineOption range(QStringLiteral("range"), QStringLiteral("Use hours H:H of the session."),
                                   QStringLiteral("H:H"));
    const QCommandLineOption json = CliOptions::json();
    const QCommandLineOption force = CliOptions::force();
    p.addOptions({db, target, kRange, channels, range, json, force});
    p.addPositionalArgument(QStringLiteral("SESSION"),
                            QStringLiteral("Sessions (ids, UUIDs, A:B ranges, comma lists); several: their samples one "
                                           "after another, temperatures as rises from each session's start."),
                            QStringLiteral("SESSION..."));
    if (!parse(p, args))
        return 0;
    if (p.positionalArguments().isEmpty())
        throw UsageError(QStringLiteral("%1: give at least one SESSION id").arg(cmd));
    if (!p.isSet(target))
        throw UsageError(QStringLiteral("%1: --target CHANNEL is required").arg(cmd));
    int kMin = 2, kMax = 8;
    DataDrivenFitCommand::parseKRange(p.value(kRange), kMin, kMax, cmd);
    OutputTarget::checkJson(p, json, force);
    const QString path = CliSupport::databasePath(p.value(db), QString(), true);
    SessionStore store(path);
    PointSelectionRequest q;
    q.sessions = DataDrivenFitCommand::sessionArgs(store, p.positionalArguments(), QStringLiteral("SESSION"), cmd);
    q.target = p.value(target);
    q.kMin = kMin;
    q.kMax = kMax;
    q.channels = p.value(channels).split(QLatin1Char(','), Qt::SkipEmptyParts);
    const qint64 session = q.sessions.front();
    PointSelection::Result selected;
    try {
        q.hours = p.isSet(range) ? HourRange::parse(p.value(range), QStringLiteral("--range")) : HourRange();
        PointSelection::check(store, q);
        CliSupport::progress(QStringLiteral("selecting sensitive points of session %1 for %2...").arg(session).arg(p.value(target)));
        selected = PointSelection(store).run(q);
    } catch (const std::invalid_argument &e) {
        throw UsageError(QStringLiteral("%1: %2").arg(cmd, QString::fromUtf8(e.what())));
    }
    const SelectionResult &r = selected.selection;
    const QJsonObject &result = selected.record;
    if (p.isSet(json))
        CliSupport::writeJson(QJsonDocument(result), p.value(json));
    if (!p.isSet(json) || p.value(json) != QLatin1String("-")) {
        QTextStream o(stdout);
        o << "session " << session << ", target " << p.value(target) << ": " << r.channels.size() << " channels, " << r.rows
          << " samples\n  silhouette:";
        for (const ClusteringForK &e : r.perK)
            o << "  K=" << e.k << ' ' << QString::number(e.silhouette, 'f', 3);
        o << "\n  K* = " << r.chosenK << '\n';
        for (std::size_t c = 0; c < r.clusters.size(); ++c) {
            o << "  cluster " << c + 1 << ':';
            for (int i : r.clusters[c])
                o << ' ' << QString::fromStdString(r.channels[static_cast<std::size_t>(i)]) << " ("
                  << QString::number(r.grade[static_cast<std::size_t>(i)], 'f', 3) << ')';
            o << "  -> " << QString::fromStdString(r.chosen[c]) << '\n';
        }
        for (const ExcludedChannel &e : r.excluded)
            o << "  excluded " << QString::fromStdString(e.id) << ": " << QString::fromStdString(e.reason) << '\n';
        QStringList chosen;
        for (const std::string &c : r.chosen)
            chosen << QString::fromStdString(c);
        o << "chosen points: " << chosen.join(QLatin1Char(',')) << '\n';
    }
    return 0;
}

} // namespace driftlab
