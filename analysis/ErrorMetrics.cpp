#include "ErrorMetrics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace driftlab {

ErrorMetrics ErrorMetrics::compute(const std::vector<double> &measured, const std::vector<double> &predicted,
                                   const std::vector<char> *mask)
{
    if (measured.size() != predicted.size() || (mask && mask->size() != measured.size()))
        throw std::invalid_argument("ErrorMetrics: series of different lengths");
    ErrorMetrics m;
    double sumY = 0.0, sumE = 0.0, sumE2 = 0.0, sumAbs = 0.0;
    for (std::size_t k = 0; k < measured.size(); ++k) {
        if ((mask && !(*mask)[k]) || !std::isfinite(measured[k]) || !std::isfinite(predicted[k]))
            continue;
        const double e = measured[k] - predicted[k];
        ++m.n;
        sumY += measured[k];
        sumE += e;
        sumE2 += e * e;
        sumAbs += std::fabs(e);
        m.maxAbs = std::max(m.maxAbs, std::fabs(e));
    }
    if (m.n == 0)
        return m;
    const double n = static_cast<double>(m.n);
    const double meanY = sumY / n;
    double ss = 0.0;
    for (std::size_t k = 0; k < measured.size(); ++k) {
        if ((mask && !(*mask)[k]) || !std::isfinite(measured[k]) || !std::isfinite(predicted[k]))
            continue;
        ss += (measured[k] - meanY) * (measured[k] - meanY);
    }
    m.mse = sumE2 / n;
    m.rmse = std::sqrt(m.mse);
    m.mae = sumAbs / n;
    m.meanError = sumE / n;
    m.fittingDegree_pct = ss > 0 ? 100.0 * (1.0 - sumE2 / ss) : 0.0;
    return m;
}

} // namespace driftlab
