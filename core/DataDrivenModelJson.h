#pragma once
// "driftlab-model" JSON, versions 1 and 2 (docs/datadriven.md): the model a controller evaluates
// (format, version, model, target, inputs, linear | exponential | synthetic, evaluation) plus
// whatever documentation blocks the fit adds (training, hyperparameters, uncertainties,
// metrics, selection), which reading keeps but does not need.
//
// parse() takes bytes and returns the model or throws std::invalid_argument naming the
// source and the field ("model.json: linear.terms[2].lags_s: expected an array of numbers
// >= 0"), so it can be fuzzed.

#include "DataDrivenModel.h"

#include <QByteArray>
#include <QJsonArray>
#include <QJsonObject>
#include <QString>

#include <vector>

namespace driftlab {

class DataDrivenModelJson {
public:
    // Version 2 adds the temperature reference (`reference`, terms' `rise`); a model without
    // rises is written as version 1, readable by older DriftLab. Both versions are read.
    static constexpr int kVersion = 2;
    static constexpr int kOldestVersion = 1;
    static QJsonObject toJson(const DataDrivenModel &model);
    static DataDrivenModel fromJson(const QJsonObject &object, const QString &source);
    static DataDrivenModel parse(const QByteArray &bytes, const QString &source, QJsonObject *document = nullptr);
    // The top-level JSON object of bytes (std::invalid_argument naming the source and byte).
    static QJsonObject object(const QByteArray &bytes, const QString &source);
    // Reads and parses a file (std::invalid_argument names the file for every failure).
    static DataDrivenModel read(const QString &path, QJsonObject *document = nullptr);
    // Writes atomically (QSaveFile); throws std::runtime_error naming the file.
    static void write(const QJsonObject &document, const QString &path);
    // Numbers as a JSON array, NaN as null.
    static QJsonArray numbers(const std::vector<double> &values);
};

} // namespace driftlab
