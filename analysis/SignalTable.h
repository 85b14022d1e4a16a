#pragma once
// Channels of one recording on a common time grid, the input of sensitive-point selection
// and of the data-driven model fits. A missing value is NaN.
//
// Gap rule (resample): a grid time takes the linear interpolation of the two samples around
// it when they are at most maxGap_s apart; inside a longer gap, and before the first or
// after the last sample, the value is NaN. DataDrivenSession uses maxGap_s = 10 x the
// channel's median sample interval (at least two grid steps).

#include "TimeSeries.h"

#include <string>
#include <vector>

namespace driftlab {

struct SignalColumn {
    std::string id;
    std::string unit;
    std::string kind; // temperature | displacement | position | feed | other
    std::string role; // e.g. spindle, feed_rate, ambient
    std::vector<double> v;
};

struct SignalTable {
    std::vector<double> t; // seconds since the session start, increasing
    std::vector<SignalColumn> columns;

    int find(const std::string &id) const; // -1 when absent
    // Throws std::invalid_argument naming the id when absent.
    const SignalColumn &column(const std::string &id) const;
    // The grid rows with t in [from_s, to_s).
    std::vector<char> rowsIn(double from_s, double to_s) const;
    double medianStep() const;

    // Runs one after another on one grid (sensitive points and the exp model on several runs):
    // each run's times are shifted to start pause_s after the previous run's end, with one
    // pause row between runs where the columns named in zeroInPause are 0 and all others NaN
    // (a first-order state driven by them decays to rest). Columns are the first run's; a
    // column another run lacks is NaN there. Columns named in `rises` become rises from each
    // run's first finite value. rows[r] (empty: all) marks run r's rows to keep marked in
    // *rowsOut (pause rows unmarked).
    static SignalTable concatenate(const std::vector<const SignalTable *> &runs,
                                   const std::vector<std::vector<char>> &rows, double pause_s,
                                   const std::vector<std::string> &zeroInPause, const std::vector<std::string> &rises,
                                   std::vector<char> *rowsOut);

    static std::vector<double> resample(const TimeSeries &s, const std::vector<double> &grid, double maxGap_s);
    static double medianInterval(const std::vector<double> &t);
};

} // namespace driftlab
