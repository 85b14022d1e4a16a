#include "RigConfigLoader.h"

#include "JsonFields.h"
#include "OffsetRegisterMap.h"
#include "RigJsonBinder.h"

#include "RealDevices.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>

#include <stdexcept>

// Q_INIT_RESOURCE must be used outside a namespace.
static void initRigResources()
{
    Q_INIT_RESOURCE(rigs);
}

namespace driftlab {

namespace {
using Binder = RigJsonBinder;

void bindNode(Binder &b, const char *key, RigNode &n)
{
    b.object(key, [&] {
        b.positive("capacity_J_K", n.capacity_J_K);
        b.nonNegative("to_screw_W_K", n.toScrew_W_K);
        b.nonNegative("to_ambient_W_K", n.toAmbient_W_K);
        b.nonNegative("to_bed_W_K", n.toBed_W_K);
    });
}

void bindTravel(Binder &b, double &lo, double &hi)
{
    QVector<double> t{lo, hi};
    b.numbers("travel_mm", t, 2, 2);
    if (b.reading() && t[0] >= t[1])
        b.fail(QStringLiteral("travel_mm"), QStringLiteral("expected [low, high] with low < high"));
    lo = t[0];
    hi = t[1];
}

void bindProgramme(Binder &b, RigConfig &c)
{
    b.object("programme", [&] {
        if (!b.reading()) {
            QJsonArray phases;
            for (const FeedPhase &p : c.program.phases())
                phases.append(QJsonObject{{QStringLiteral("name"), p.name},
                                          {QStringLiteral("duration_s"), p.duration_s},
                                          {QStringLiteral("feed_mm_min"), p.feed_mm_min},
                                          {QStringLiteral("travel_mm"), QJsonArray{p.travelLow_mm, p.travelHigh_mm}}});
            b.current().insert(QStringLiteral("phases"), phases);
            return;
        }
        const bool hasPreset = b.has("preset");
        const bool hasPhases = b.has("phases");
        if (hasPreset == hasPhases)
            b.fail(QString(), QStringLiteral("give either \"preset\" or \"phases\""));
        double lo = c.travelLow_mm, hi = c.travelHigh_mm;
        if (hasPreset) {
            QString name;
            b.str("preset", name);
            if (name != QLatin1String("seed000-table2"))
                b.fail(QStringLiteral("preset"), QStringLiteral("unknown programme preset \"%1\" (known: seed000-table2)").arg(name));
            double feed = 6000.0;
            b.num("feed_mm_min", feed, 1.0, 60000.0);
            bindTravel(b, lo, hi);
            c.program = FeedProgram::seed000Table2(feed, lo, hi);
            return;
        }
        QVector<FeedPhase> phases;
        b.eachObject("phases", QStringLiteral("phases"), true, [&](const QString &key, const QJsonObject &item) {
            FeedPhase p;
            p.travelLow_mm = c.travelLow_mm;
            p.travelHigh_mm = c.travelHigh_mm;
            p.name = QStringLiteral("phase %1").arg(phases.size() + 1);
            b.enter(key, item);
            b.str("name", p.name);
            p.duration_s = -1.0;
            b.num("duration_s", p.duration_s, 0.0, 1e7);
            if (p.duration_s < 0.0)
                b.fail(QStringLiteral("duration_s"), QStringLiteral("missing"));
            b.num("feed_mm_min", p.feed_mm_min, 0.0, 60000.0);
            bindTravel(b, p.travelLow_mm, p.travelHigh_mm);
            b.leave();
            phases.push_back(p);
        });
        c.program = FeedProgram(phases);
    });
}

void bindSensors(Binder &b, RigConfig &c)
{
    b.object("sensors", [&] {
        if (!b.reading()) {
            QJsonArray a;
            for (const Pt100Config &p : c.pt100) {
                QJsonObject o{{QStringLiteral("id"), p.id},
                              {QStringLiteral("location"), p.location},
                              {QStringLiteral("rate_Hz"), p.rate_Hz},
                              {QStringLiteral("noise_K"), p.noise_K},
                              {QStringLiteral("dropout_probability"), p.dropoutProbability},
                              {QStringLiteral("dropout_max_samples"), p.dropoutMaxSamples}};
                if (p.location == QLatin1String("screw"))
                    o.insert(QStringLiteral("screw_position_m"), p.screwPosition_m);
                a.append(o);
            }
            b.current().insert(QStringLiteral("pt100"), a);
        } else if (b.has("pt100")) {
            c.pt100.clear();
            QStringList ids;
            b.eachObject("pt100", QStringLiteral("channels"), false, [&](const QString &key, const QJsonObject &item) {
                Pt100Config p;
                b.enter(key, item);
                b.str("id", p.id);
                b.str("location", p.location);
                if (p.id.isEmpty() || p.location.isEmpty())
                    b.fail(QString(), QStringLiteral("\"id\" and \"location\" are required"));
                if (ids.contains(p.id))
                    b.fail(QStringLiteral("id"), QStringLiteral("duplicate channel id \"%1\"").arg(p.id));
                ids << p.id;
                b.num("screw_position_m", p.screwPosition_m, 0.0, c.screwParams.length_m);
                b.num("rate_Hz", p.rate_Hz, 1e-4, 1000.0);
                b.nonNegative("noise_K", p.noise_K);
                b.num("dropout_probability", p.dropoutProbability, 0.0, 1.0);
                b.integer("dropout_max_samples", p.dropoutMaxSamples, 1, 1000000);
                b.leave();
                c.pt100.push_back(p);
            });
        }
        b.object("probe", [&] {
            b.boolean("enabled", c.probe.enabled);
            b.str("id", c.probe.id);
            b.num("rate_Hz", c.probe.rate_Hz, 1e-4, 1000.0);
            b.nonNegative("noise_um", c.probe.noise_um);
        });
        b.object("cnc", [&] {
            b.boolean("enabled", c.cnc.enabled);
            b.num("rate_Hz", c.cnc.rate_Hz, 1e-4, 1000.0);
        });
        b.object("interferometer", [&] {
            InterferometerConfig &li = c.interferometer;
            b.boolean("enabled", li.enabled);
            b.numbers("targets_mm", li.targets_mm, 0, 1000);
            b.nonNegative("first_run_s", li.firstRun_s);
            b.positive("interval_s", li.interval_s);
            b.nonNegative("dwell_s", li.dwell_s);
            b.nonNegative("noise_um", li.noise_um);
            b.nonNegative("pitch_error_amplitude_um", li.pitchErrorAmplitude_um);
            b.integer("cycles", li.cycles, 1, 100);
            b.boolean("bidirectional", li.bidirectional);
            b.num("reversal_um", li.reversal_um, -1000.0, 1000.0);
        });
        b.object("infrared", [&] {
            InfraredConfig &ir = c.infrared;
            b.boolean("enabled", ir.enabled);
            b.positive("interval_s", ir.interval_s);
            b.integer("width_px", ir.width_px, 8, 4096);
            b.integer("height_px", ir.height_px, 4, 4096);
            QVector<double> line{ir.lineStartX_px, ir.lineStartY_px, ir.lineEndX_px, ir.lineEndY_px};
            b.numbers("screw_line_px", line, 4, 4);
            ir.lineStartX_px = line[0];
            ir.lineStartY_px = line[1];
            ir.lineEndX_px = line[2];
            ir.lineEndY_px = line[3];
            b.integer("screw_width_px", ir.screwWidth_px, 1, 4096);
            b.integer("nut_width_px", ir.nutWidth_px, 1, 4096);
            b.nonNegative("noise_K", ir.noise_K);
        });
    });
}

void bindDevices(Binder &b, RigConfig &c)
{
    if (!b.reading()) {
        if (c.devices.isEmpty())
            return;
        QJsonArray a;
        for (const DeviceConfig &d : c.devices) {
            QJsonObject o = d.settings;
            o.insert(QStringLiteral("id"), d.id);
            o.insert(QStringLiteral("type"), d.type);
            a.append(o);
        }
        b.current().insert(QStringLiteral("devices"), a);
        return;
    }
    if (!b.has("devices"))
        return;
    QStringList ids;
    int camera = -1;
    b.eachObject("devices", QStringLiteral("devices"), true, [&](const QString &key, const QJsonObject &item) {
        QJsonObject o = item;
        DeviceConfig d;
        const QJsonValue id = o.take(QStringLiteral("id"));
        const QJsonValue type = o.take(QStringLiteral("type"));
        if (!id.isString() || id.toString().isEmpty())
            b.fail(key + QStringLiteral(".id"), QStringLiteral("expected a non-empty string, got %1").arg(Binder::shown(id)));
        if (!type.isString() || !RealDevices::knownType(type.toString()))
            b.fail(key + QStringLiteral(".type"), QStringLiteral("expected one of %1, got %2")
                                                      .arg(RealDevices::allTypes().join(QStringLiteral(", ")), Binder::shown(type)));
        d.id = id.toString();
        d.type = type.toString();
        d.settings = o;
        if (ids.contains(d.id))
            b.fail(key + QStringLiteral(".id"), QStringLiteral("duplicate device id \"%1\"").arg(d.id));
        ids << d.id;
        if (RealDevices::isCamera(d.type)) {
            if (camera >= 0)
                b.fail(key + QStringLiteral(".type"),
                       QStringLiteral("only one infrared camera per rig (a session has one infrared calibration); devices[%1] is one").arg(camera));
            camera = ids.size() - 1;
        }
        try {
            RealDevices::validate(d.type, d.settings, b.path(key));
        } catch (const std::invalid_argument &e) {
            b.fail(QString(), QString::fromUtf8(e.what()), true);
        }
        c.devices.push_back(d);
    });
}

void bindCompensationServer(Binder &b, RigConfig &c)
{
    CompensationServerConfig &s = c.compensationServer;
    if (!b.reading() && !s.enabled)
        return; // rig files without a server stay as they were
    b.object("compensation_server", [&] {
        b.boolean("enabled", s.enabled);
        b.str("host", s.host);
        b.integer("port", s.port, 1, 65535);
        if (!b.reading()) {
            b.current().insert(QStringLiteral("map"), s.map);
            return;
        }
        if (!b.has("map"))
            return;
        const QJsonValue v = b.get("map");
        if (!v.isObject())
            b.fail(QStringLiteral("map"), QStringLiteral("expected a register map object, e.g. {\"preset\": \"m80\"}, got %1").arg(Binder::shown(v)));
        s.map = v.toObject();
        try {
            JsonFields f(s.map, b.path(QStringLiteral("map")));
            OffsetRegisterMap::fromJson(f);
            f.finish();
        } catch (const std::invalid_argument &e) {
            b.fail(QString(), QString::fromUtf8(e.what()), true);
        }
    });
}

void bind(Binder &b, RigConfig &c)
{
    if (b.reading()) {
        b.markUsed("format");
        b.markUsed("version");
        b.markUsed("description");
    } else {
        b.current().insert(QStringLiteral("format"), QStringLiteral("driftlab-rig"));
        b.current().insert(QStringLiteral("version"), 1);
    }
    b.str("name", c.name);
    double seed = c.seed;
    b.num("seed", seed, 0.0, 4294967295.0);
    c.seed = static_cast<unsigned>(seed);
    b.object("machine", [&] {
        b.str("name", c.machineName);
        b.str("axis", c.axis);
        b.num("fixed_end_position_mm", c.fixedEndPosition_mm);
        bindTravel(b, c.travelLow_mm, c.travelHigh_mm);
    });
    b.object("screw", [&] {
        RigScrew &s = c.screwParams;
        b.positive("length_m", s.length_m);
        b.positive("diameter_m", s.diameter_m);
        b.positive("nut_length_m", s.nutLength_m);
        b.positive("fixed_bearing_length_m", s.fixedBearingLength_m);
        b.positive("free_bearing_length_m", s.freeBearingLength_m);
        b.positive("density_kg_m3", s.density_kg_m3);
        b.positive("specific_heat_J_kgK", s.specificHeat_J_kgK);
        b.positive("conductivity_W_mK", s.conductivity_W_mK);
        b.num("expansion_per_K", s.expansion_per_K, 0.0, 1e-3);
        b.integer("cells", s.cells, 8, 5000);
        b.num("dt_s", s.dt_s, 1e-3, 60.0);
    });
    b.object("thermal", [&] {
        RigThermal &t = c.thermal;
        b.object("ambient", [&] {
            b.num("mean_C", t.ambientMean_C, -50.0, 150.0);
            b.nonNegative("drift_amplitude_K", t.ambientDriftAmplitude_K);
            b.positive("drift_period_s", t.ambientDriftPeriod_s);
            b.nonNegative("random_walk_K", t.ambientRandomWalk_K);
            b.positive("random_walk_tau_s", t.ambientRandomWalkTau_s);
        });
        b.object("convection", [&] {
            b.nonNegative("h0_W_m2K", t.convectionH0_W_m2K);
            b.nonNegative("h1_W_m2K_per_mm_min", t.convectionH1_W_m2K_per_mm_min);
        });
        b.nonNegative("nut_heat_W_per_mm_min", t.nutHeat_W_per_mm_min);
        b.nonNegative("fixed_bearing_heat_W_per_mm_min", t.fixedBearingHeat_W_per_mm_min);
        b.nonNegative("motor_heat_W", t.motorHeat_W);
        b.nonNegative("motor_heat_W_per_mm_min", t.motorHeat_W_per_mm_min);
        b.nonNegative("bed_heat_W", t.bedHeat_W);
        bindNode(b, "fixed_bearing_housing", t.fixedBearingHousing);
        bindNode(b, "free_bearing_housing", t.freeBearingHousing);
        bindNode(b, "nut_housing", t.nutHousing);
        bindNode(b, "motor", t.motor);
        bindNode(b, "bed", t.bed);
        b.object("hydraulic_unit", [&] {
            b.nonNegative("rise_K", t.unitRise_K);
            b.positive("period_s", t.unitPeriod_s);
            b.num("duty", t.unitDuty, 0.0, 1.0);
            b.positive("time_constant_s", t.unitTimeConstant_s);
            b.num("phase_s", t.unitPhase_s);
        });
    });
    b.object("effects", [&] {
        RigEffects &e = c.effects;
        b.object("motor_coupling", [&] {
            b.boolean("enabled", e.motorCoupling);
            b.nonNegative("conductance_W_K", e.motorCoupling_W_K);
        });
        b.object("free_bearing_heat", [&] {
            b.boolean("enabled", e.freeBearingHeat);
            b.nonNegative("coefficient_W_per_mm_min", e.freeBearingHeat_W_per_mm_min);
        });
        b.object("superlinear_heat", [&] {
            b.boolean("enabled", e.superlinearHeat);
            b.num("nut_exponent", e.nutExponent, 0.5, 4.0);
            b.num("bearing_exponent", e.bearingExponent, 0.5, 4.0);
            b.positive("reference_feed_mm_min", e.referenceFeed_mm_min);
        });
        b.object("heat_path_lag", [&] {
            b.boolean("enabled", e.heatPathLag);
            b.num("fraction", e.lagFraction, 0.0, 1.0);
            b.positive("bearing_contact_W_K", e.lagBearingContact_W_K);
            b.positive("bearing_housing_capacity_J_K", e.lagBearingCapacity_J_K);
            b.positive("nut_contact_W_K", e.lagNutContact_W_K);
            b.positive("nut_housing_capacity_J_K", e.lagNutCapacity_J_K);
        });
        b.object("holding_heat", [&] {
            b.boolean("enabled", e.holdingHeat);
            b.nonNegative("power_W", e.holdingPower_W);
        });
        b.object("structure_offset", [&] {
            b.boolean("enabled", e.structureOffset);
            b.num("coefficient_um_K", e.structureOffset_um_K);
        });
        b.object("structure_linear", [&] {
            b.boolean("enabled", e.structureLinear);
            b.num("coefficient_um_m_K", e.structureLinear_um_m_K);
            b.num("reference_position_mm", e.structureReference_mm);
        });
        b.object("coolant", [&] {
            b.boolean("enabled", e.coolant);
            b.nonNegative("conductance_W_mK", e.coolant_W_mK);
            b.num("mean_C", e.coolantMean_C, -50.0, 150.0);
            b.nonNegative("amplitude_K", e.coolantAmplitude_K);
            b.positive("period_s", e.coolantPeriod_s);
        });
        b.object("ambient_gradient", [&] {
            b.boolean("enabled", e.ambientGradient);
            b.num("fraction", e.gradientFraction, 0.0, 1.0);
        });
        b.object("neighbour_radiation", [&] {
            b.boolean("enabled", e.neighbourRadiation);
            b.nonNegative("conductance_W_mK", e.radiationConductance_W_mK);
            b.nonNegative("start_m", e.radiationStart_m);
            b.nonNegative("end_m", e.radiationEnd_m);
        });
    });
    bindSensors(b, c);
    bindProgramme(b, c);
    b.object("randomise", [&] {
        b.boolean("enabled", c.randomise.enabled);
        b.nonNegative("relative_spread", c.randomise.relativeSpread);
        b.nonNegative("fixed_end_jitter_mm", c.randomise.fixedEndJitter_mm);
    });
    bindCompensationServer(b, c);
    bindDevices(b, c);
}
} // namespace

RigConfig RigConfigLoader::fromJson(const QJsonObject &root, const QString &source)
{
    if (root.contains(QStringLiteral("format")) && root.value(QStringLiteral("format")).toString() != QLatin1String("driftlab-rig"))
        throw std::invalid_argument(QStringLiteral("%1: format: expected \"driftlab-rig\"").arg(source).toStdString());
    if (root.contains(QStringLiteral("version")) && root.value(QStringLiteral("version")).toInt() != 1)
        throw std::invalid_argument(QStringLiteral("%1: version: only version 1 is supported").arg(source).toStdString());
    RigConfig c;
    Binder b(true, source);
    b.enter(QString(), root);
    // The travel is needed before the programme default; bind everything in order.
    bind(b, c);
    b.leave();
    if (!root.contains(QStringLiteral("programme")))
        c.program = FeedProgram::seed000Table2(6000.0, c.travelLow_mm, c.travelHigh_mm);
    return c;
}

QJsonObject RigConfigLoader::toJson(const RigConfig &config)
{
    RigConfig c = config;
    Binder b(false, QStringLiteral("rig"));
    b.enter(QString(), QJsonObject());
    bind(b, c);
    QJsonObject root = b.current();
    b.leave();
    return root;
}

RigConfig RigConfigLoader::fromText(const QByteArray &text, const QString &source)
{
    QJsonParseError err{};
    const QJsonDocument doc = QJsonDocument::fromJson(text, &err);
    if (err.error != QJsonParseError::NoError) {
        const QByteArray before = text.left(err.offset);
        throw std::invalid_argument(QStringLiteral("%1: line %2: invalid JSON: %3")
                                        .arg(source)
                                        .arg(before.count('\n') + 1)
                                        .arg(err.errorString())
                                        .toStdString());
    }
    if (!doc.isObject())
        throw std::invalid_argument(QStringLiteral("%1: expected a JSON object").arg(source).toStdString());
    return fromJson(doc.object(), source);
}

RigConfig RigConfigLoader::loadFile(const QString &path)
{
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly))
        throw std::runtime_error(QStringLiteral("%1: cannot open rig file: %2").arg(path, f.errorString()).toStdString());
    const QString source = path.startsWith(QLatin1Char(':')) ? QFileInfo(path).fileName() : path;
    return fromText(f.readAll(), source);
}

QStringList RigConfigLoader::presetNames()
{
    initRigResources();
    QStringList names;
    for (const QString &f : QDir(QStringLiteral(":/rigs")).entryList({QStringLiteral("*.json")}, QDir::Files, QDir::Name))
        names << QFileInfo(f).completeBaseName();
    return names;
}

RigConfig RigConfigLoader::preset(const QString &name)
{
    initRigResources();
    const QString path = QStringLiteral(":/rigs/%1.json").arg(name);
    if (!QFile::exists(path))
        throw std::invalid_argument(
            QStringLiteral("unknown rig preset '%1' (known: %2)").arg(name, presetNames().join(QStringLiteral(", "))).toStdString());
    return loadFile(path);
}

RigConfig RigConfigLoader::load(const QString &nameOrPath)
{
    if (QFileInfo::exists(nameOrPath) || nameOrPath.contains(QLatin1Char('/')) || nameOrPath.endsWith(QLatin1String(".json")))
        return loadFile(nameOrPath);
    return preset(nameOrPath);
}

} // namespace driftlab
