#pragma once
// One notation for units on screen: the bundle's ASCII units (degC, um, mm/min, W/(m^2 K))
// shown as °C, µm, mm/min, W/(m² K). CSV headers and the CLI keep ASCII.

#include <QString>

namespace driftlab {

class UnitLabels {
public:
    static QString display(const QString &unit);
};

} // namespace driftlab
