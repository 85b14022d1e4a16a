#include "SimulateCommand.h"

#include "BearingHeatSource.h"
#include "CliSupport.h"
#include "CliOptions.h"
#include "OutputTarget.h"
#include "SessionArgument.h"
#include "ExportableModelJson.h"
#include "NutHeatSource.h"
#include "ScrewResponseSimulator.h"
#include "SessionAnalysis.h"
#include "SessionStore.h"

#include <QCommandLineParser>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTextStream>

#include <cmath>

namespace driftlab {

QString SimulateCommand::summary() const
{
    return QStringLiteral(
        "Run a fitted seed-000 screw model (MODEL.json from 'fit --json') over a session's recorded axis\n"
        "position, feed and ambient, and compare the predicted screw-end elongation and interferometer\n"
        "thermal errors with the measured ones (RMS). --json writes the predicted series.");
}

int SimulateCommand::run(const QStringList &args)
{
    QCommandLineParser p;
    const QCommandLineOption db = CliOptions::db();
    const QCommandLineOption modelOpt(QStringLiteral("model"), QStringLiteral("MODEL.json written by 'fit --json'."),
                                      QStringLiteral("file"));
    const QCommandLineOption json = CliOptions::json();
    const QCommandLineOption force = CliOptions::force();
    const QCommandLineOption interval(QStringLiteral("interval"),
                                      QStringLiteral("Elongation output interval, s (default 60)."),
                                      QStringLiteral("seconds"), QStringLiteral("60"));
    p.addOptions({db, modelOpt, json, force, interval});
    p.addPositionalArgument(QStringLiteral("SESSION"), QStringLiteral("Session id."));
    if (!parse(p, args))
        return 0;
    if (!p.isSet(modelOpt))
        throw UsageError(QStringLiteral("simulate: --model MODEL.json is required"));
    if (p.positionalArguments().size() != 1)
        throw UsageError(QStringLiteral("simulate: name exactly one SESSION id"));
    bool ok = false;
    const double every = p.value(interval).toDouble(&ok);
    if (!ok || !(every > 0))
        throw UsageError(QStringLiteral("simulate: --interval must be > 0 s, got '%1'").arg(p.value(interval)));
    SessionArgument::checkForm(p.positionalArguments().front(), QStringLiteral("SESSION"), name());
    OutputTarget::checkJson(p, json, force);

    const QString modelPath = p.value(modelOpt);
    QFile file(modelPath);
    if (!file.open(QIODevice::ReadOnly))
        throw UsageError(QStringLiteral("simulate: cannot read %1: %2").arg(modelPath, file.errorString()));
    const QByteArray bytes = file.readAll();
    ExportableModel model; // the one reader of model files (export-model reads them too)
    try {
        model = ExportableModelJson::parse(bytes, modelPath);
    } catch (const std::invalid_argument &e) {
        throw UsageError(QStringLiteral("simulate: %1").arg(QString::fromUtf8(e.what())));
    }
    if (!model.physics)
        throw UsageError(QStringLiteral("simulate: %1: a %2 model: simulate runs the seed-000 screw model "
                                        "(\"model\": \"fdm-seed000\"); 'validate' predicts a session with a data-driven one")
                             .arg(modelPath, QString::fromStdString(model.kind())));
    const QJsonObject m = QJsonDocument::fromJson(bytes).object();
    const QJsonObject par = m.value(QStringLiteral("parameters")).toObject();
    const FdmParameters &fp = model.parameters;
    const ScrewGeometry &g = model.geometry;
    ResponseSimulatorOptions so;
    so.grid.dx_m = model.grid.dx_m;
    // The implicit step the model was fitted with (model.grid holds the controller's explicit one).
    const QJsonValue dt = m.value(QStringLiteral("grid")).toObject().value(QStringLiteral("dt_s"));
    if (!dt.isUndefined()) {
        if (!dt.isDouble() || !(dt.toDouble() > 0))
            throw UsageError(QStringLiteral("simulate: %1: grid.dt_s: must be a number > 0").arg(modelPath));
        so.grid.dt_s = dt.toDouble();
    }
    so.elongationInterval_s = every;

    const QString path = CliSupport::databasePath(p.value(db), QString(), true);
    SessionStore store(path);
    const qint64 id = SessionArgument::one(store, p.positionalArguments().front(), QStringLiteral("SESSION"), name());

    QString note;
    ScrewRecording rec = SessionAnalysis(store, id).recording(&note);
    CliSupport::progress(QStringLiteral("session %1: %2").arg(id).arg(note));
    const bool measuredProbe = !rec.elongation_um.empty();
    if (!measuredProbe) {
        // Prediction only: an output grid over the drive.
        const double t0 = rec.drive.position_mm.t.front(), t1 = rec.drive.position_mm.t.back();
        for (double t = t0; t <= t1 + 1e-9; t += every) {
            rec.elongation_um.t.push_back(t);
            rec.elongation_um.v.push_back(0.0);
        }
    }
    ScrewResponseSimulator sim(g, {rec}, so,
                               {std::make_shared<BearingHeatSource>(), std::make_shared<NutHeatSource>()});
    Eigen::MatrixXd phi;
    sim.simulate(fp.k1, fp.k2, fp.conductivity_W_mK, fp.fixedEndPosition_mm, phi);
    const Eigen::VectorXd pred = phi.col(0) + fp.k3 * phi.col(1) + fp.k4 * phi.col(2);

    QJsonArray elong, interf;
    double se = 0, si = 0, peak = 0, maxTe = 0;
    int ne = 0, ni = 0;
    for (int r = 0; r < sim.rowCount(); ++r) {
        const ResponseObservation &o = sim.observations()[static_cast<size_t>(r)];
        const double e = pred[r] - o.measured_um;
        if (o.elongation) {
            peak = std::max(peak, std::fabs(pred[r]));
            QJsonObject row{{QStringLiteral("t_s"), o.t_s}, {QStringLiteral("predicted_um"), pred[r]}};
            if (measuredProbe) {
                row.insert(QStringLiteral("measured_um"), o.measured_um);
                se += e * e;
                ++ne;
            }
            elong.append(row);
        } else {
            maxTe = std::max(maxTe, std::fabs(pred[r]));
            si += e * e;
            ++ni;
            interf.append(QJsonObject{{QStringLiteral("t_s"), o.t_s},
                                      {QStringLiteral("position_mm"), o.position_mm},
                                      {QStringLiteral("predicted_um"), pred[r]},
                                      {QStringLiteral("measured_um"), o.measured_um}});
        }
    }
    const double rmsE = ne ? std::sqrt(se / ne) : 0.0, rmsI = ni ? std::sqrt(si / ni) : 0.0;
    if (p.isSet(json)) {
        QJsonObject out{{QStringLiteral("session"), static_cast<double>(id)},
                        {QStringLiteral("model"), modelPath},
                        {QStringLiteral("parameters"), par},
                        {QStringLiteral("elongation"), elong},
                        {QStringLiteral("interferometer"), interf},
                        {QStringLiteral("predicted_peak_elongation_um"), peak},
                        {QStringLiteral("predicted_max_abs_error_um"), maxTe}};
        if (ne)
            out.insert(QStringLiteral("elongation_rms_um"), rmsE);
        if (ni)
            out.insert(QStringLiteral("interferometer_rms_um"), rmsI);
        CliSupport::writeJson(QJsonDocument(out), p.value(json));
    }
    if (!p.isSet(json) || p.value(json) != QLatin1String("-")) {
        QTextStream o(stdout);
        o << "session " << id << ": predicted peak elongation " << QString::number(peak, 'f', 2) << QStringLiteral(" \u00b5m");
        if (ne)
            o << ", RMS against the probe " << QString::number(rmsE, 'f', 3) << QStringLiteral(" \u00b5m over ") << ne << " samples";
        if (ni)
            o << "; positioning error max " << QString::number(maxTe, 'f', 2) << QStringLiteral(" \u00b5m, RMS against the interferometer ")
              << QString::number(rmsI, 'f', 3) << QStringLiteral(" \u00b5m over ") << ni << " points";
        o << '\n';
    }
    return 0;
}

} // namespace driftlab
