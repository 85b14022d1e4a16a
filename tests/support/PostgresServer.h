#pragma once
// A real PostgreSQL server for a test, started inside it and stopped at the end (issue 20):
// initdb + pg_ctl from Debian's postgresql package into a temporary directory, listening on a
// free loopback port, so CI needs no running service. As root the server runs as the
// 'postgres' system user (initdb refuses root), through runuser. skipReason() says what is
// missing (the postgresql binaries, Qt's QPSQL driver) so a test can QSKIP with it.

#include <QDir>
#include <QFile>
#include <QProcess>
#include <QSqlDatabase>
#include <QSqlError>
#include <QSqlQuery>
#include <QStandardPaths>
#include <QString>
#include <QStringList>
#include <QTcpServer>
#include <QTemporaryDir>

#include <memory>
#include <unistd.h>

namespace testpeers {

class PostgresServer {
public:
    ~PostgresServer() { stop(); }

    static QString binDir()
    {
        const QStringList versions = QDir(QStringLiteral("/usr/lib/postgresql")).entryList(QDir::Dirs | QDir::NoDotAndDotDot, QDir::Name);
        for (int i = versions.size() - 1; i >= 0; --i) {
            const QString bin = QStringLiteral("/usr/lib/postgresql/%1/bin").arg(versions[i]);
            if (QFile::exists(bin + QStringLiteral("/initdb")) && QFile::exists(bin + QStringLiteral("/pg_ctl")))
                return bin;
        }
        return QString();
    }
    static QString skipReason()
    {
        if (binDir().isEmpty())
            return QStringLiteral("PostgreSQL server binaries not installed (Debian package postgresql; scripts/setup-debian.sh)");
        if (!QSqlDatabase::isDriverAvailable(QStringLiteral("QPSQL")))
            return QStringLiteral("Qt's QPSQL driver not installed (Debian package libqt5sql5-psql; scripts/setup-debian.sh)");
        if (::geteuid() == 0 && QStandardPaths::findExecutable(QStringLiteral("runuser")).isEmpty())
            return QStringLiteral("running as root without runuser");
        return QString();
    }

    // Starts a server whose superuser is `user`. With a password, connections over TCP must
    // give it (scram-sha-256); without, they are trusted.
    bool start(QString *error, const QString &user = QStringLiteral("driftlab"), const QString &password = QString())
    {
        stop();
        m_user = user;
        m_dir = std::make_unique<QTemporaryDir>(QDir::tempPath() + QStringLiteral("/driftlab-pg-XXXXXX"));
        if (!m_dir->isValid())
            return fail(error, QStringLiteral("no temporary directory"));
        QFile::setPermissions(m_dir->path(), QFileDevice::ReadOwner | QFileDevice::WriteOwner | QFileDevice::ExeOwner | QFileDevice::ReadOther |
                                                 QFileDevice::WriteOther | QFileDevice::ExeOther | QFileDevice::ReadGroup |
                                                 QFileDevice::WriteGroup | QFileDevice::ExeGroup);
        QTcpServer probe;
        probe.listen(QHostAddress::LocalHost, 0);
        m_port = probe.serverPort();
        probe.close();
        QStringList initdb{binDir() + QStringLiteral("/initdb"), QStringLiteral("-D"), dataDir(), QStringLiteral("-U"), user,
                           QStringLiteral("--auth-local=trust"), QStringLiteral("-E"), QStringLiteral("UTF8"), QStringLiteral("--no-sync")};
        if (password.isEmpty()) {
            initdb << QStringLiteral("--auth-host=trust");
        } else {
            const QString pw = m_dir->filePath(QStringLiteral("pw"));
            QFile f(pw);
            f.open(QIODevice::WriteOnly);
            f.write(password.toUtf8() + '\n');
            f.close();
            QFile::setPermissions(pw, QFileDevice::ReadOwner | QFileDevice::ReadOther | QFileDevice::ReadGroup);
            initdb << QStringLiteral("--auth-host=scram-sha-256") << QStringLiteral("--pwfile=%1").arg(pw);
        }
        if (!runAsServer(initdb, error))
            return false;
        if (!runAsServer({binDir() + QStringLiteral("/pg_ctl"), QStringLiteral("-D"), dataDir(), QStringLiteral("-o"),
                          QStringLiteral("-p %1 -k %2 -c listen_addresses=127.0.0.1 -c fsync=off").arg(m_port).arg(m_dir->path()),
                          QStringLiteral("-l"), m_dir->filePath(QStringLiteral("server.log")), QStringLiteral("-w"), QStringLiteral("start")},
                         error))
            return false;
        m_running = true;
        return true;
    }
    // start() and CREATE DATABASE `database`; *url gets its address.
    bool startWithDatabase(const QString &database, QString *url, QString *error)
    {
        if (!start(error))
            return false;
        const QString failed = sql(QStringLiteral("CREATE DATABASE %1").arg(database));
        if (!failed.isEmpty())
            return fail(error, failed);
        *url = this->url(database);
        return true;
    }
    void stop()
    {
        if (m_running)
            runAsServer({binDir() + QStringLiteral("/pg_ctl"), QStringLiteral("-D"), dataDir(), QStringLiteral("-m"), QStringLiteral("immediate"),
                         QStringLiteral("-w"), QStringLiteral("stop")},
                        nullptr);
        m_running = false;
    }
    int port() const { return m_port; }
    QString url(const QString &database = QStringLiteral("postgres"), const QString &user = QString()) const
    {
        return QStringLiteral("postgresql://%1@127.0.0.1:%2/%3").arg(user.isEmpty() ? m_user : user).arg(m_port).arg(database);
    }
    // Runs SQL as the superuser on `database` (CREATE DATABASE, roles, ...); empty on success.
    QString sql(const QString &statement, const QString &database = QStringLiteral("postgres"), const QString &password = QString()) const
    {
        const QString name = QStringLiteral("pgtest-%1").arg(reinterpret_cast<quintptr>(this));
        QString result;
        {
            QSqlDatabase db = QSqlDatabase::addDatabase(QStringLiteral("QPSQL"), name);
            db.setHostName(QStringLiteral("127.0.0.1"));
            db.setPort(m_port);
            db.setDatabaseName(database);
            db.setUserName(m_user);
            db.setPassword(password);
            if (!db.open()) {
                result = db.lastError().text();
            } else {
                QSqlQuery q(db);
                if (!q.exec(statement))
                    result = q.lastError().text();
            }
            db.close();
        }
        QSqlDatabase::removeDatabase(name);
        return result;
    }
    QString log() const
    {
        QFile f(m_dir ? m_dir->filePath(QStringLiteral("server.log")) : QString());
        return f.open(QIODevice::ReadOnly) ? QString::fromLocal8Bit(f.readAll()) : QString();
    }

private:
    QString dataDir() const { return m_dir->filePath(QStringLiteral("data")); }
    static bool fail(QString *error, const QString &what)
    {
        if (error)
            *error = what;
        return false;
    }
    bool runAsServer(QStringList command, QString *error) const
    {
        QProcess p;
        p.setProcessChannelMode(QProcess::MergedChannels);
        if (::geteuid() == 0)
            command = QStringList{QStringLiteral("runuser"), QStringLiteral("-u"), QStringLiteral("postgres"), QStringLiteral("--")} + command;
        p.setWorkingDirectory(m_dir->path());
        p.start(command.takeFirst(), command);
        if (!p.waitForFinished(120000) || p.exitStatus() != QProcess::NormalExit || p.exitCode() != 0)
            return fail(error, QStringLiteral("%1 failed: %2").arg(command.value(0), QString::fromLocal8Bit(p.readAll())));
        return true;
    }

    std::unique_ptr<QTemporaryDir> m_dir;
    QString m_user;
    int m_port = 0;
    bool m_running = false;
};

} // namespace testpeers
