// driftlab-cli: the headless face of DriftLab.

#include "AnalyseCommand.h"
#include "BatchCommand.h"
#include "DiagnoseCommand.h"
#include "ExportCommand.h"
#include "ExportModelCommand.h"
#include "CompensateCommand.h"
#include "FitCommand.h"
#include "ImportCommand.h"
#include "ImportCsvCommand.h"
#include "Iso230Command.h"
#include "ImportRtlCommand.h"
#include "InfoCommand.h"
#include "ListCommand.h"
#include "PullCommand.h"
#include "PushCommand.h"
#include "NewBundleCommand.h"
#include "PlotCommand.h"
#include "RecordCommand.h"
#include "ReportCommand.h"
#include "SelectPointsCommand.h"
#include "SimulateCommand.h"
#include "ValidateCommand.h"

#include <QApplication>
#include <QCoreApplication>
#include <QTextCodec>
#include <QTextStream>

#include <exception>
#include <memory>
#include <vector>

using namespace driftlab;

namespace {

std::vector<std::unique_ptr<CliCommand>> commands()
{
    std::vector<std::unique_ptr<CliCommand>> list;
    list.push_back(std::make_unique<RecordCommand>());
    list.push_back(std::make_unique<InfoCommand>());
    list.push_back(std::make_unique<AnalyseCommand>());
    list.push_back(std::make_unique<ImportCommand>());
    list.push_back(std::make_unique<ImportCsvCommand>());
    list.push_back(std::make_unique<Iso230Command>());
    list.push_back(std::make_unique<ImportRtlCommand>());
    list.push_back(std::make_unique<ExportCommand>());
    list.push_back(std::make_unique<ListCommand>());
    list.push_back(std::make_unique<PlotCommand>());
    list.push_back(std::make_unique<FitCommand>());
    list.push_back(std::make_unique<SimulateCommand>());
    list.push_back(std::make_unique<DiagnoseCommand>());
    list.push_back(std::make_unique<NewBundleCommand>());
    list.push_back(std::make_unique<SelectPointsCommand>());
    list.push_back(std::make_unique<ValidateCommand>());
    list.push_back(std::make_unique<ReportCommand>());
    list.push_back(std::make_unique<BatchCommand>());
    list.push_back(std::make_unique<ExportModelCommand>());
    list.push_back(std::make_unique<CompensateCommand>());
    list.push_back(std::make_unique<PushCommand>());
    list.push_back(std::make_unique<PullCommand>());
    return list;
}

void usage(QTextStream &out, const std::vector<std::unique_ptr<CliCommand>> &list)
{
    out << "Usage: driftlab-cli COMMAND [options]\n"
           "       driftlab-cli COMMAND --help\n\nCommands:\n";
    for (const auto &c : list)
        out << "  " << c->name().leftJustified(14) << c->summary().section(QLatin1Char('\n'), 0, 0) << '\n';
    out << "\nExit codes: 0 done, 1 failed, 2 bad usage or bad input.\n";
}

} // namespace

int main(int argc, char **argv)
{
    // Rendering plots (plot, report) needs a QApplication; it never needs a display.
    const bool gui = argc > 1 && (qstrcmp(argv[1], "plot") == 0 || qstrcmp(argv[1], "report") == 0);
    if (gui && qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM"))
        qputenv("QT_QPA_PLATFORM", "offscreen");
    std::unique_ptr<QCoreApplication> application =
        gui ? std::make_unique<QApplication>(argc, argv) : std::make_unique<QCoreApplication>(argc, argv);
    // Every message is UTF-8 (°C, µm, file names), whatever the locale says: under LANG=C
    // Qt 5 would otherwise write '?' or Latin-1 bytes, and decode UTF-8 arguments wrongly.
    QTextCodec::setCodecForLocale(QTextCodec::codecForName("UTF-8"));
    QCoreApplication::setApplicationName(QStringLiteral("DriftLab"));
    QCoreApplication::setApplicationVersion(QStringLiteral(DRIFTLAB_VERSION));
    QTextStream err(stderr);
    QTextStream out(stdout);
    const auto list = commands();
    QStringList args = QCoreApplication::arguments();
    args.removeFirst();
    if (args.isEmpty()) {
        usage(err, list);
        return 2;
    }
    const QString name = args.takeFirst();
    if (name == QLatin1String("--help") || name == QLatin1String("-h") || name == QLatin1String("help")) {
        usage(out, list);
        return 0;
    }
    if (name == QLatin1String("--version")) {
        out << "driftlab-cli " << DRIFTLAB_VERSION << '\n';
        return 0;
    }
    for (const auto &c : list) {
        if (c->name() != name && !(name == QLatin1String("analyze") && c->name() == QLatin1String("analyse")))
            continue;
        try {
            return c->run(args);
        } catch (const UsageError &e) {
            // what() holds UTF-8; QTextStream would read a const char * as Latin-1 ("Â°C").
            err << "driftlab-cli: " << QString::fromUtf8(e.what()) << '\n';
            return 2;
        } catch (const std::exception &e) {
            err << "driftlab-cli " << name << ": " << QString::fromUtf8(e.what()) << '\n';
            return 1;
        }
    }
    err << "driftlab-cli: unknown command '" << name << "'\n\n";
    usage(err, list);
    return 2;
}
