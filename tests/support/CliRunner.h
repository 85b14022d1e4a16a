#pragma once
// Runs driftlab-cli (the DRIFTLAB_CLI path of the test target) as a user would: a separate
// process, its exit code, standard output and standard error. A timed-out or crashed run
// has code -1. dataHome, when given, becomes the child's XDG_DATA_HOME so that a command
// run without --db writes its default database inside the test's folder, never the user's.

#include <QByteArray>
#include <QProcess>
#include <QProcessEnvironment>
#include <QString>
#include <QStringList>

namespace clirunner {

struct Result {
    int code = -1;
    QByteArray out, err;
};

inline Result run(const QStringList &args, const QString &dataHome = QString(), int timeout_ms = 120000)
{
    QProcess p;
    if (!dataHome.isEmpty()) {
        QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
        env.insert(QStringLiteral("XDG_DATA_HOME"), dataHome);
        p.setProcessEnvironment(env);
    }
    p.start(QStringLiteral(DRIFTLAB_CLI), args);
    if (!p.waitForFinished(timeout_ms)) {
        p.kill();
        p.waitForFinished(5000);
        return {};
    }
    return {p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1, p.readAllStandardOutput(), p.readAllStandardError()};
}

} // namespace clirunner
