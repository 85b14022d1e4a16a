#pragma once
// Set-up shared by the widget tests that open a window on a recorded database (tst_mainwindow,
// tst_sessionbrowser, tst_layout1366, tst_iso230view): the user's settings kept out of the
// test, and short recordings of the baseline simulated rig; and by the tests that diagnose
// recordings of the rig with a concealed structure drift (tst_diagnosispanel, tst_facesagree).

#include "RigConfig.h"
#include "RigConfigLoader.h"
#include "RigRecorder.h"
#include "SessionStore.h"
#include "SimulatedRig.h"

#include <QDockWidget>
#include <QScrollArea>
#include <QSettings>
#include <QTest>
#include <QString>
#include <QTemporaryDir>

namespace widgettest {

// QSettings (recent databases, window state, dock layout) in INI files under dir/settings.
inline void privateSettings(const QTemporaryDir &dir)
{
    QSettings::setDefaultFormat(QSettings::IniFormat);
    QSettings::setPath(QSettings::IniFormat, QSettings::UserScope, dir.filePath(QStringLiteral("settings")));
}

// The baseline rig running the seed-000 programme at 6000 mm/min; `rigName` as stored with the
// session (empty: the preset's default).
inline driftlab::RigConfig baselineRig(const QString &rigName = QString())
{
    driftlab::RigConfig config;
    if (!rigName.isEmpty())
        config.name = rigName;
    config.program = driftlab::FeedProgram::seed000Table2(6000.0);
    return config;
}

// The "structure-offset" preset (a structure drift the screw model does not explain) running
// the seed-000 programme at `feed_mm_min` over its travel, its noise seed advanced by `seedStep`.
inline driftlab::RigConfig structureOffsetRig(double feed_mm_min, unsigned seedStep = 0)
{
    driftlab::RigConfig config = driftlab::RigConfigLoader::preset(QStringLiteral("structure-offset"));
    config.program = driftlab::FeedProgram::seed000Table2(feed_mm_min, config.travelLow_mm, config.travelHigh_mm);
    config.seed += seedStep;
    return config;
}

// Records `seconds` of `config` as a session named `name`; its id (0 on failure).
inline qint64 record(driftlab::SessionStore &store, const driftlab::RigConfig &config, const QString &name, double seconds)
{
    driftlab::SimulatedRig rig(config);
    driftlab::RigRecorder recorder(store, rig);
    return recorder.record(name, seconds);
}

// Shows dock `d` in front (a tab of its area raised) and returns the scroll area its panel
// lies in (MainWindow::addPanelDock), or nullptr.
inline QScrollArea *raiseDock(QDockWidget *d)
{
    if (!d)
        return nullptr;
    d->show();
    d->raise();
    QTest::qWait(50);
    return qobject_cast<QScrollArea *>(d->widget());
}

} // namespace widgettest
