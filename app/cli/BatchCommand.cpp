#include "BatchCommand.h"

#include "BatchJob.h"
#include "CliOptions.h"
#include "CliSupport.h"
#include "DiagnoseCommand.h"
#include "ExportModelCommand.h"
#include "FitCommand.h"
#include "ImportCommand.h"
#include "OutputTarget.h"
#include "PlotCommand.h"
#include "ReportCommand.h"
#include "SelectPointsCommand.h"

#include <QCommandLineParser>
#include <QCoreApplication>
#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QProcess>
#include <QSaveFile>
#include <QThread>

#include <atomic>
#include <memory>
#include <mutex>
#include <thread>

namespace driftlab {

namespace {

struct StepResult {
    QString step, label, status = QStringLiteral("skipped"), message, log;
    int exitCode = -1;
    double seconds = 0.0;
    QStringList outputs;
};

struct InputResult {
    QString database;
    qint64 session = 0;
    QVector<StepResult> steps;
};

// Runs one recording's steps in order; a failed import skips the rest, other failures do not.
class Pipeline {
public:
    Pipeline(const BatchJob &job, int index, std::mutex &progressMutex)
        : m_job(job), m_in(job.inputs[index]), m_index(index), m_progressMutex(progressMutex)
    {
    }

    InputResult run()
    {
        InputResult r;
        const QDir dir(QDir(m_job.output).filePath(m_in.label));
        QDir().mkpath(dir.path());
        r.database = m_in.bundle.isEmpty() ? m_in.database : dir.filePath(QStringLiteral("session.sqlite"));
        r.session = m_in.session;
        bool imported = m_in.bundle.isEmpty();
        for (const BatchStep &step : m_job.steps) {
            StepResult s;
            s.step = step.name;
            s.label = step.label;
            if (!imported && step.name != QLatin1String("import")) {
                s.message = QStringLiteral("not run: the import failed");
                report(s);
                r.steps.push_back(s);
                continue;
            }
            if (!step.source.isEmpty() && !succeeded(r, step.source)) {
                s.message = QStringLiteral("not run: %1 did not write the model").arg(step.source);
                report(s);
                r.steps.push_back(s);
                continue;
            }
            QStringList options;
            QString format;
            for (int i = 0; i < step.options.size(); i += 2) {
                if (step.options[i] == QLatin1String("%format"))
                    format = step.options[i + 1];
                else
                    options << step.options[i] << step.options[i + 1];
            }
            const QString id = QString::number(r.session);
            QStringList args{step.name};
            const auto output = [&](const QString &name) {
                s.outputs << name;
                return dir.filePath(name);
            };
            if (step.name == QLatin1String("import")) {
                for (const char *suffix : {"", "-wal", "-shm"}) // the previous run's copy of this recording
                    QFile::remove(r.database + QLatin1String(suffix));
                args << m_in.bundle << QStringLiteral("--json") << output(QStringLiteral("import.json"));
                s.outputs << QStringLiteral("session.sqlite");
            } else if (step.name == QLatin1String("select-points")) {
                args << id << options << QStringLiteral("--json") << output(QStringLiteral("select-points.json"));
            } else if (step.name == QLatin1String("fit")) {
                const int m = options.indexOf(QStringLiteral("--model"));
                const bool physical = m < 0 || options.value(m + 1) == QLatin1String("fdm");
                args << id << options << (physical ? QStringLiteral("--json") : QStringLiteral("--out"))
                     << output(step.label + QStringLiteral(".json"));
            } else if (step.name == QLatin1String("diagnose")) {
                args << QStringLiteral("--train") << id << options << QStringLiteral("--json") << output(QStringLiteral("diagnosis.json"));
            } else if (step.name == QLatin1String("export-model")) {
                args << dir.filePath(step.source + QStringLiteral(".json")) << options << QStringLiteral("--out")
                     << output(step.label) << QStringLiteral("--json") << output(step.label + QStringLiteral(".json"));
            } else if (step.name == QLatin1String("plot")) {
                args << id << options << QStringLiteral("--out")
                     << output(step.label + QLatin1Char('.') + (format.isEmpty() ? QStringLiteral("svg") : format));
            } else if (step.name == QLatin1String("report")) {
                args << id << options << QStringLiteral("--out")
                     << output(QStringLiteral("report.") + (format.isEmpty() ? QStringLiteral("pdf") : format));
            }
            if (step.name != QLatin1String("export-model")) // reads only its MODEL.json
                args << QStringLiteral("--db") << r.database;
            args << QStringLiteral("--force"); // the batch owns the files of its output folder
            execute(args, dir, s);
            if (step.name == QLatin1String("import") && s.status == QLatin1String("ok")) {
                QFile f(dir.filePath(QStringLiteral("import.json")));
                r.session = f.open(QIODevice::ReadOnly)
                                ? static_cast<qint64>(QJsonDocument::fromJson(f.readAll()).object().value(QStringLiteral("session")).toDouble())
                                : 0;
                imported = r.session > 0;
                if (!imported) {
                    s.status = QStringLiteral("failed");
                    s.message = QStringLiteral("import wrote no session id to import.json");
                }
            }
            report(s);
            r.steps.push_back(s);
        }
        return r;
    }

private:
    static bool succeeded(const InputResult &r, const QString &label)
    {
        for (const StepResult &s : r.steps)
            if (s.label == label)
                return s.status == QLatin1String("ok");
        return false;
    }

    void execute(const QStringList &args, const QDir &dir, StepResult &s)
    {
        QElapsedTimer timer;
        timer.start();
        QProcess p;
        s.log = s.label + QStringLiteral(".log");
        p.start(QCoreApplication::applicationFilePath(), args);
        p.waitForFinished(-1);
        const QByteArray err = p.readAllStandardError();
        QSaveFile log(dir.filePath(s.log)); // the command, its output and its messages; never half-written
        if (log.open(QIODevice::WriteOnly)) {
            log.write("$ driftlab-cli " + args.join(QLatin1Char(' ')).toUtf8() + '\n' + p.readAllStandardOutput() + err);
            log.flush();
            log.commit();
        }
        s.seconds = timer.elapsed() / 1000.0;
        s.exitCode = p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1;
        s.status = s.exitCode == 0 ? QStringLiteral("ok") : QStringLiteral("failed");
        if (s.exitCode != 0) {
            const QStringList lines = QString::fromUtf8(err).split(QLatin1Char('\n'), Qt::SkipEmptyParts);
            s.message = p.exitStatus() != QProcess::NormalExit ? QStringLiteral("crashed: %1").arg(p.errorString())
                        : lines.isEmpty()                     ? QStringLiteral("exit code %1").arg(s.exitCode)
                                                              : lines.last();
            s.outputs.clear();
        }
    }

    void report(const StepResult &s)
    {
        const QString line = QStringLiteral("[%1/%2 %3] %4: %5%6")
                                 .arg(m_index + 1)
                                 .arg(m_job.inputs.size())
                                 .arg(m_in.label, s.label, s.status)
                                 .arg(s.status == QLatin1String("skipped") ? QStringLiteral(" (%1)").arg(s.message)
                                      : s.status == QLatin1String("ok")    ? QStringLiteral(" (%1 s)").arg(s.seconds, 0, 'f', 1)
                                                                           : QStringLiteral(" (exit %1): %2").arg(s.exitCode).arg(s.message));
        std::lock_guard<std::mutex> lock(m_progressMutex);
        CliSupport::progress(line);
    }

    const BatchJob &m_job;
    const BatchInput &m_in;
    int m_index;
    std::mutex &m_progressMutex;
};

// Every step's options are checked by its own command's parser before the first step runs, so
// that a misspelt option is found before any import (exit 2 naming the job file and step).
void checkStepOptions(const QString &jobFile, const BatchJob &job)
{
    for (int i = 0; i < job.steps.size(); ++i) {
        const BatchStep &step = job.steps[i];
        std::unique_ptr<CliCommand> command;
        if (step.name == QLatin1String("import"))
            command = std::make_unique<ImportCommand>();
        else if (step.name == QLatin1String("select-points"))
            command = std::make_unique<SelectPointsCommand>();
        else if (step.name == QLatin1String("fit"))
            command = std::make_unique<FitCommand>();
        else if (step.name == QLatin1String("diagnose"))
            command = std::make_unique<DiagnoseCommand>();
        else if (step.name == QLatin1String("export-model"))
            command = std::make_unique<ExportModelCommand>();
        else if (step.name == QLatin1String("plot"))
            command = std::make_unique<PlotCommand>();
        else if (step.name == QLatin1String("report"))
            command = std::make_unique<ReportCommand>();
        else
            continue;
        QStringList options;
        for (int k = 0; k + 1 < step.options.size(); k += 2)
            if (step.options[k] != QLatin1String("%format"))
                options << step.options[k] << step.options[k + 1];
        CliCommand::setOptionsCheckOnly(true);
        try {
            command->run(options);
        } catch (const UsageError &e) {
            CliCommand::setOptionsCheckOnly(false);
            throw UsageError(QStringLiteral("batch: %1: steps[%2]: %3").arg(jobFile).arg(i).arg(QString::fromStdString(e.what())));
        }
        CliCommand::setOptionsCheckOnly(false);
    }
}

QJsonObject summaryJson(const BatchJob &job, const QVector<InputResult> &results, int jobs, double wall_s, int &failed)
{
    QJsonArray inputs;
    failed = 0;
    int ok = 0;
    for (int i = 0; i < results.size(); ++i) {
        const BatchInput &in = job.inputs[i];
        QJsonArray steps;
        for (const StepResult &s : results[i].steps) {
            failed += s.status != QLatin1String("ok");
            ok += s.status == QLatin1String("ok");
            steps.append(QJsonObject{{QStringLiteral("step"), s.step},
                                     {QStringLiteral("name"), s.label},
                                     {QStringLiteral("status"), s.status},
                                     {QStringLiteral("exit_code"), s.exitCode},
                                     {QStringLiteral("seconds"), s.seconds},
                                     {QStringLiteral("outputs"), QJsonArray::fromStringList(s.outputs)},
                                     {QStringLiteral("log"), s.log},
                                     {QStringLiteral("message"), s.message}});
        }
        inputs.append(QJsonObject{{QStringLiteral("label"), in.label},
                                  {QStringLiteral("input"), in.bundle.isEmpty() ? in.database : in.bundle},
                                  {QStringLiteral("folder"), in.label},
                                  {QStringLiteral("database"), results[i].database},
                                  {QStringLiteral("session"), static_cast<double>(results[i].session)},
                                  {QStringLiteral("steps"), steps}});
    }
    return QJsonObject{{QStringLiteral("job"), job.file},
                       {QStringLiteral("output"), job.output},
                       {QStringLiteral("parallel"), jobs},
                       {QStringLiteral("wall_time_s"), wall_s},
                       {QStringLiteral("steps_ok"), ok},
                       {QStringLiteral("steps_not_ok"), failed},
                       {QStringLiteral("recordings"), inputs}};
}

} // namespace

QString BatchCommand::summary() const
{
    return QStringLiteral("Run steps (import, select-points, fit, diagnose, export-model, plot, report) on many recordings from a job\n"
                          "file (docs/batch.md), recordings in parallel over the cores; one progress line per step;\n"
                          "OUTPUT/summary.json lists every step's result. Exit 1 if any step failed (the rest still run).");
}

int BatchCommand::run(const QStringList &args)
{
    QCommandLineParser p;
    const QCommandLineOption jobsOption(QStringLiteral("jobs"), QStringLiteral("Recordings at a time (default: the job's 'jobs', else the cores)."),
                                        QStringLiteral("n"));
    const QCommandLineOption json = CliOptions::json();
    const QCommandLineOption force = CliOptions::force();
    p.addOptions({jobsOption, json, force});
    p.addPositionalArgument(QStringLiteral("JOB.json"), QStringLiteral("The job file."));
    if (!parse(p, args))
        return 0;
    if (p.positionalArguments().size() != 1)
        throw UsageError(QStringLiteral("batch: give exactly one job file"));
    const BatchJob job = BatchJob::read(p.positionalArguments().first());
    checkStepOptions(p.positionalArguments().first(), job);
    int jobs = job.jobs > 0 ? job.jobs : std::max(1, QThread::idealThreadCount());
    if (p.isSet(jobsOption)) {
        bool ok = false;
        jobs = p.value(jobsOption).toInt(&ok);
        if (!ok || jobs < 1)
            throw UsageError(QStringLiteral("batch: --jobs must be a whole number >= 1, got '%1'").arg(p.value(jobsOption)));
    }
    jobs = std::min(jobs, static_cast<int>(job.inputs.size()));
    // The output folder is the batch's: created in an existing folder, or an earlier batch's
    // folder (its summary.json) replaced only with --force.
    const QString summaryPath = QDir(job.output).filePath(QStringLiteral("summary.json"));
    if (QFileInfo(job.output).isDir())
        OutputTarget(summaryPath, QStringLiteral("output")).check(p.isSet(force));
    else
        OutputTarget(job.output, QStringLiteral("output"), OutputTarget::Kind::Folder).check(p.isSet(force));
    OutputTarget::checkJson(p, json, force);
    if (!QDir().mkpath(job.output))
        throw std::runtime_error(QStringLiteral("batch: cannot create the output folder %1").arg(job.output).toStdString());
    CliSupport::progress(QStringLiteral("batch: %1 recording(s) x %2 step(s), %3 at a time, into %4")
                             .arg(job.inputs.size())
                             .arg(job.steps.size())
                             .arg(jobs)
                             .arg(job.output));
    QElapsedTimer timer;
    timer.start();
    QVector<InputResult> results(job.inputs.size());
    std::mutex progressMutex;
    std::atomic<int> next{0};
    std::vector<std::thread> workers;
    for (int w = 0; w < jobs; ++w)
        workers.emplace_back([&] {
            for (int i = next++; i < job.inputs.size(); i = next++)
                results[i] = Pipeline(job, i, progressMutex).run();
        });
    for (std::thread &t : workers)
        t.join();
    int failed = 0;
    const QJsonObject summary = summaryJson(job, results, jobs, timer.elapsed() / 1000.0, failed);
    CliSupport::writeJson(QJsonDocument(summary), QDir(job.output).filePath(QStringLiteral("summary.json")));
    if (p.isSet(json))
        CliSupport::writeJson(QJsonDocument(summary), p.value(json));
    CliSupport::progress(QStringLiteral("batch: %1 step(s) ok, %2 not ok in %3 s; summary in %4")
                             .arg(summary.value(QStringLiteral("steps_ok")).toInt())
                             .arg(failed)
                             .arg(timer.elapsed() / 1000.0, 0, 'f', 1)
                             .arg(QDir(job.output).filePath(QStringLiteral("summary.json"))));
    return failed > 0 ? 1 : 0;
}

} // namespace driftlab
