#pragma once
// Reads and writes rig files (JSON, "format": "driftlab-rig", "version": 1). Every key
// is optional and defaults to the baseline preset; unknown keys, wrong types and values
// out of range are errors whose message names the file and the field
// (e.g. "my.json: effects.coolant.mean_C: expected a number in [-50, 150], got "x"").
// The schema is documented in docs/acquisition.md.

#include "RigConfig.h"

#include <QJsonObject>
#include <QString>
#include <QStringList>

namespace driftlab {

class RigConfigLoader {
public:
    // Throws std::invalid_argument (bad content) or std::runtime_error (unreadable file).
    static RigConfig loadFile(const QString &path);
    static RigConfig fromJson(const QJsonObject &root, const QString &source = QStringLiteral("rig"));
    // The whole file's text to a config (no I/O; invalid JSON names the line).
    static RigConfig fromText(const QByteArray &text, const QString &source = QStringLiteral("rig"));
    static QJsonObject toJson(const RigConfig &config);

    // Presets compiled into the library (resources/rigs/*.json): names and loading.
    static QStringList presetNames();
    static RigConfig preset(const QString &name); // throws std::invalid_argument for an unknown name
    // A preset name or a file path.
    static RigConfig load(const QString &nameOrPath);
};

} // namespace driftlab
