#pragma once
// The rig of the ISO 230 tests (tst_iso230cli, tst_iso230view): the seed002-instruments preset
// (laser runs every 0.5 h, 3 bidirectional cycles) with a 10 min cold phase and a 100 min
// warm-up at 6000 mm/min, the infrared camera off (not needed: saves time). Empty when the
// preset cannot be read.

#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QString>

namespace testrigs {

inline QJsonObject iso230WarmUpRig()
{
    QFile preset(QStringLiteral(DRIFTLAB_SOURCE_DIR "/resources/rigs/seed002-instruments.json"));
    if (!preset.open(QIODevice::ReadOnly))
        return QJsonObject();
    QJsonObject rig = QJsonDocument::fromJson(preset.readAll()).object();
    rig.insert(QStringLiteral("programme"),
               QJsonObject{{QStringLiteral("phases"),
                            QJsonArray{QJsonObject{{QStringLiteral("name"), QStringLiteral("cold")}, {QStringLiteral("duration_s"), 600}},
                                       QJsonObject{{QStringLiteral("name"), QStringLiteral("warm-up")},
                                                   {QStringLiteral("duration_s"), 6000},
                                                   {QStringLiteral("feed_mm_min"), 6000}}}}});
    QJsonObject sensors = rig.value(QStringLiteral("sensors")).toObject();
    sensors.insert(QStringLiteral("infrared"), QJsonObject{{QStringLiteral("enabled"), false}});
    rig.insert(QStringLiteral("sensors"), sensors);
    return rig;
}

} // namespace testrigs
