#include "DiagnosisSwitchLabels.h"

#include <QStringList>

#include <utility>

namespace driftlab {

QString DiagnosisSwitchLabels::priors() { return QStringLiteral("Priors"); }

QString DiagnosisSwitchLabels::measurementChain() { return QStringLiteral("Measurement chain"); }

QString DiagnosisSwitchLabels::triples() { return QStringLiteral("Triples"); }

QString DiagnosisSwitchLabels::housingContact() { return QStringLiteral("Housing contact"); }

QString DiagnosisSwitchLabels::screwTemperatures() { return QStringLiteral("Screw temperatures fitted"); }

QString DiagnosisSwitchLabels::summary(const DiagnosisSwitches &s)
{
    const std::pair<QString, bool> all[] = {{priors(), s.priors},
                                            {measurementChain(), s.checkMeasurementChain},
                                            {triples(), s.tryTriples},
                                            {housingContact(), s.housingContact},
                                            {screwTemperatures(), s.fitScrewTemperatures}};
    QStringList parts;
    for (const auto &p : all)
        parts << p.first + (p.second ? QStringLiteral(" on") : QStringLiteral(" off"));
    return parts.join(QStringLiteral(", "));
}

} // namespace driftlab
