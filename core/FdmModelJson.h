#pragma once
// The one owner of the seed-000 screw model's file format: MODEL.json of `fit --model fdm`
// ("model": "fdm-seed000", read by `simulate --model`, `export-model` and the report) and the
// record stored with every fitted session. Every object of the file (parameters,
// standard_errors, correlation names, plausibility flags) names a parameter by the same key:
// k1, k2, k3, k4, lambda_W_mK, fixed_end_position_mm (components of the diagnosis keep their
// own names).
//
// Schema version 2 (this one) writes "schema_version": 2. Version 1 (no "schema_version",
// DriftLab before 2026-11) named standard errors, correlations and flags "lambda" and "P_f";
// the readers here accept both.

#include "ScrewFitTypes.h"
#include "ScrewModelTypes.h"

#include <QJsonObject>
#include <QPair>
#include <QString>
#include <QStringList>
#include <QVector>

#include <string>

namespace driftlab {

class FdmModelJson {
public:
    static constexpr int kSchemaVersion = 2;
    static QString modelName() { return QStringLiteral("fdm-seed000"); }

    // The key of an identified parameter (ScrewModelIdentifier's name: k1..k4, lambda, P_f).
    static QString key(const std::string &identifierName);
    // A person's label of a parameter key, with its unit: "lambda (W/(m K))".
    static QString parameterLabel(const QString &key);
    // A person's label of a metrics key ("elongation_rms_um", "plausibility.note", ...).
    static QString metricLabel(const QString &key);

    // MODEL.json of a fit (without "database": the caller adds where the sessions came from).
    // The "parameters" object of MODEL.json (the one key set, read back by parameters()).
    static QJsonObject parametersJson(const FdmParameters &p);
    static QJsonObject document(const ScrewFitResult &fit);
    // The record stored with each fitted session, built from the document.
    static FittedModel storedModel(const QJsonObject &document);

    // k1..k4, lambda, P_f of a "parameters" object; missing keys keep `fallback` unless
    // `required`. Throws std::invalid_argument naming source and field.
    static FdmParameters parameters(const QJsonObject &parameters, const QString &source, const FdmParameters &fallback,
                                    bool required);
    // The standard error of `key` in a standard_errors object of either schema; null when
    // the parameter was held (or is missing).
    static QJsonValue standardError(const QJsonObject &standardErrors, const QString &key);
    // The flags of a plausibility object for `key`, as "IMPLAUSIBLE" / "POORLY IDENTIFIED"
    // words and their messages.
    static QStringList flags(const QJsonObject &plausibility, const QString &key, QStringList *messages = nullptr);
    // The metrics of a stored record as label/value rows for a person (arrays left out).
    static QVector<QPair<QString, QString>> metricRows(const QJsonObject &metrics);
};

} // namespace driftlab
