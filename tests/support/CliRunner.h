#pragma once
// Runs driftlab-cli (the DRIFTLAB_CLI path of the test target) as a user would: a separate
// process, its exit code, standard output and standard error. A run that outlives its
// timeout is killed and, like a crashed run, has code -1.
// The child never sees the user's folders: XDG_DATA_HOME, XDG_CONFIG_HOME and XDG_CACHE_HOME
// always point into a private temporary folder of the test process (kept for the whole test
// run, so that a command run without --db finds the default database an earlier run wrote).
// dataHome, when given, becomes XDG_DATA_HOME instead, inside the test's own folder.

#include <QByteArray>
#include <QDir>
#include <QProcess>
#include <QProcessEnvironment>
#include <QString>
#include <QStringList>
#include <QTemporaryDir>

namespace clirunner {

struct Result {
    int code = -1;
    QByteArray out, err;
};

// The private XDG folders of this test process.
inline QString privateHome()
{
    static QTemporaryDir home(QDir::tempPath() + QStringLiteral("/driftlab-test-home-XXXXXX"));
    return home.path();
}

// The environment of every child: the caller's, with private XDG folders and `extra` on top.
inline QProcessEnvironment environment(const QString &dataHome = QString(),
                                       const QProcessEnvironment &extra = QProcessEnvironment())
{
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    const QString home = privateHome();
    for (const char *sub : {"data", "config", "cache"})
        QDir(home).mkpath(QLatin1String(sub));
    env.insert(QStringLiteral("XDG_DATA_HOME"), dataHome.isEmpty() ? home + QStringLiteral("/data") : dataHome);
    env.insert(QStringLiteral("XDG_CONFIG_HOME"), home + QStringLiteral("/config"));
    env.insert(QStringLiteral("XDG_CACHE_HOME"), home + QStringLiteral("/cache"));
    for (const QString &key : extra.keys())
        env.insert(key, extra.value(key));
    return env;
}

// Runs any program (driftlab-cli, the GUI, a simulator script) the same way.
inline Result runProgram(const QString &program, const QStringList &args, const QString &dataHome = QString(),
                         int timeout_ms = 120000, const QProcessEnvironment &extra = QProcessEnvironment())
{
    QProcess p;
    p.setProcessEnvironment(environment(dataHome, extra));
    p.start(program, args);
    if (!p.waitForFinished(timeout_ms)) {
        p.kill();
        p.waitForFinished(5000);
        return {};
    }
    return {p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1, p.readAllStandardOutput(), p.readAllStandardError()};
}

#ifdef DRIFTLAB_CLI
inline Result run(const QStringList &args, const QString &dataHome = QString(), int timeout_ms = 120000)
{
    return runProgram(QStringLiteral(DRIFTLAB_CLI), args, dataHome, timeout_ms);
}
#endif

} // namespace clirunner
