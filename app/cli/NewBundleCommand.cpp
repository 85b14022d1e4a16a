#include "NewBundleCommand.h"

#include "CliSupport.h"

#include <QCommandLineParser>
#include <QDir>
#include <QDirIterator>
#include <QFile>
#include <QFileInfo>
#include <QSaveFile>
#include <QTextStream>

namespace driftlab {

QString NewBundleCommand::summary() const
{
    return QStringLiteral("Write a template recording bundle to DIR (which must not exist): manifest.json,\n"
                          "channels.csv, interferometer.csv, events.csv and ir/ with example data (1.5 h of the\n"
                          "simulated rig) and a README. Replace the data with your own and check it with\n"
                          "'driftlab-cli import DIR'. The format is described in docs/recording-bundle.md.");
}

int NewBundleCommand::run(const QStringList &args)
{
    QCommandLineParser p;
    p.addPositionalArgument(QStringLiteral("DIR"), QStringLiteral("Bundle folder to create, e.g. x-axis-warmup.bundle."));
    if (!parse(p, args))
        return 0;
    if (p.positionalArguments().size() != 1)
        throw UsageError(QStringLiteral("new-bundle: expected one DIR argument, got %1").arg(p.positionalArguments().size()));
    const QString dir = p.positionalArguments().first();
    CliSupport::checkOutput(dir, QStringLiteral("DIR"), true);
    const QString root = QStringLiteral(":/bundles/bundles/");
    QDirIterator it(root + QStringLiteral("example.bundle"), QDir::Files, QDirIterator::Subdirectories);
    QStringList files;
    while (it.hasNext())
        files << it.next();
    files << root + QStringLiteral("README.txt");
    for (const QString &from : files) {
        const QString rel = from.startsWith(root + QStringLiteral("example.bundle/"))
                                ? from.mid(root.size() + QStringLiteral("example.bundle/").size())
                                : QFileInfo(from).fileName();
        const QString to = QDir(dir).filePath(rel);
        QFile in(from);
        if (!QDir().mkpath(QFileInfo(to).absolutePath()) || !in.open(QIODevice::ReadOnly))
            throw std::runtime_error(QStringLiteral("new-bundle: cannot create %1").arg(to).toStdString());
        QSaveFile out(to);
        const QByteArray data = in.readAll();
        if (!out.open(QIODevice::WriteOnly) || out.write(data) != data.size() || !out.flush() || !out.commit())
            throw std::runtime_error(QStringLiteral("new-bundle: cannot write %1: %2").arg(to, out.errorString()).toStdString());
    }
    QTextStream(stdout) << "template bundle written to " << dir << " (" << files.size()
                        << " files); fill it in, then check it with: driftlab-cli import " << dir << '\n';
    return 0;
}

} // namespace driftlab
