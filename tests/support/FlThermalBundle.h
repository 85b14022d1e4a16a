#pragma once
// The FL_THERMAL spindle test of ../shared/extdata (one CSV: time_s, spindle_rpm, ch1_um ..
// ch5_um, t1_C .. t16_C) written as a thermal-error bundle folder that `driftlab-cli import`
// reads: channels.csv with the same rows, manifest.json with a channel each (temperature in
// degC, displacement in um, the spindle speed in rpm with role "spindle"). Shared by the CLI
// tests that run on this data set; each still decides what it checks.

#include <QDir>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QString>
#include <QStringList>
#include <QTextStream>

namespace flthermal {

// The CSV; DRIFTLAB_SHARED_DIR in the environment overrides the checkout's ../shared (worktrees).
inline QString sourcePath()
{
    return qEnvironmentVariable("DRIFTLAB_SHARED_DIR", QStringLiteral(DRIFTLAB_SHARED_DIR)) +
           QStringLiteral("/extdata/fl_thermal/fl_thermal_data.csv");
}

struct Bundle {
    QStringList header; // as written to channels.csv, time_s first
    int rows = 0;       // data rows written
    QString error;      // empty when the bundle was written
};

// Writes `source` as the bundle folder `bundle`. shortIds: channel ids without the unit suffix
// (t1, ch3, spindle_rpm) instead of the CSV's column names (t1_C, ch3_um, spindle_rpm).
inline Bundle writeBundle(const QString &source, const QString &bundle, const QString &sessionName, bool shortIds)
{
    Bundle b;
    QFile in(source);
    if (!in.open(QIODevice::ReadOnly | QIODevice::Text) || !QDir().mkpath(bundle)) {
        b.error = QStringLiteral("cannot read %1 or make %2").arg(source, bundle);
        return b;
    }
    QFile channels(bundle + QStringLiteral("/channels.csv"));
    if (!channels.open(QIODevice::WriteOnly | QIODevice::Text)) {
        b.error = channels.fileName() + QStringLiteral(": ") + channels.errorString();
        return b;
    }
    QTextStream src(&in), dst(&channels);
    b.header = src.readLine().trimmed().split(QLatin1Char(','));
    QJsonArray list;
    for (int i = 1; i < b.header.size(); ++i) {
        const bool temp = b.header[i].endsWith(QLatin1String("_C")), disp = b.header[i].endsWith(QLatin1String("_um"));
        if (shortIds)
            b.header[i] = b.header[i].section(QLatin1Char('_'), 0, temp || disp ? 0 : 1);
        list.append(QJsonObject{{QStringLiteral("id"), b.header[i]},
                                {QStringLiteral("kind"), temp ? "temperature" : (disp ? "displacement" : "other")},
                                {QStringLiteral("sensor"), QStringLiteral("unknown")},
                                {QStringLiteral("unit"), temp ? "degC" : (disp ? "um" : "rpm")},
                                {QStringLiteral("role"), temp || disp ? "" : "spindle"}});
    }
    dst << b.header.join(QLatin1Char(',')) << '\n';
    while (!src.atEnd()) {
        const QString line = src.readLine().trimmed();
        if (!line.isEmpty()) {
            dst << line << '\n';
            ++b.rows;
        }
    }
    dst.flush();
    if (!channels.flush()) {
        b.error = channels.fileName() + QStringLiteral(": ") + channels.errorString();
        return b;
    }
    channels.close();
    const QJsonObject manifest{
        {QStringLiteral("format"), QStringLiteral("thermal-error-bundle")},
        {QStringLiteral("version"), 1},
        {QStringLiteral("session"), QJsonObject{{QStringLiteral("name"), sessionName},
                                                {QStringLiteral("started"), QStringLiteral("2024-05-23T00:00:00Z")}}},
        {QStringLiteral("machine"), QJsonObject{{QStringLiteral("name"), QStringLiteral("CNC spindle (FL_THERMAL)")}}},
        {QStringLiteral("channels"), list}};
    QFile m(bundle + QStringLiteral("/manifest.json"));
    if (!m.open(QIODevice::WriteOnly) || m.write(QJsonDocument(manifest).toJson()) < 0)
        b.error = m.fileName() + QStringLiteral(": ") + m.errorString();
    return b;
}

} // namespace flthermal
