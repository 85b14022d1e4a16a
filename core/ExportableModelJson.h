#pragma once
// Reads a fitted model for export: a seed-000 screw model ('fit --model fdm --json',
// "model": "fdm-seed000", its parameters read by FdmModelJson, the format's owner) or a data-driven model ("format": "driftlab-model", read by
// DataDrivenModelJson, which refuses another version). Every failure throws
// std::invalid_argument naming the file and the field.

#include "ExportableModel.h"

#include <QByteArray>
#include <QString>

namespace driftlab {

class ExportableModelJson {
public:
    static ExportableModel parse(const QByteArray &bytes, const QString &source);
    static ExportableModel read(const QString &path);
};

} // namespace driftlab
