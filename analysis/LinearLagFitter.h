#pragma once
// Fits the linear-lag data-driven models on one or several runs (SignalTables, each a
// session or a cycle of one that starts its own lag states and temperature reference):
//  - mlr: ordinary least squares on the given temperature channels (seed 003 eq. 5, with an
//    intercept);
//  - ridge: ridge regression on the given channels, the penalty from cross-validation;
//  - lagridge: ridge regression on every given channel through a bank of first-order lags
//    (time constants of tens of minutes), bank and penalty from cross-validation;
//  - dynamic: DriftLab's own model. The temperatures, centred and scaled by their standard
//    deviation but at least scaleFloor (0.5 K), are reduced to their first m principal
//    components (over the training samples), which pass through a bank of
//    first-order lags (time constants 0 = no lag and a few of 15 min .. 4 h); the drive (spindle
//    speed or feed, scaled to its training maximum) enters as v and v^2 (heat generation
//    a v + b v^2 spans the load term ~ v and the viscous term ~ v^(5/3) of bearing friction)
//    through a second lag bank (or the drive alone, m = 0, no temperatures: seed 001's virtual
//    sensor as a lag bank). m, both banks and the ridge penalty are chosen by time-blocked
//    cross-validation on the training samples only. Since lags and the projection are linear,
//    the result is stored as per-channel lag coefficients (DataDrivenModel terms).
//
// Cross-validation: with one run, time-blocked folds (TimeBlockedFolds); with two or more,
// whole runs are left out (leave-one-run-out up to maxRunFolds runs, else maxRunFolds groups of
// consecutive runs). The temperature reference (TemperatureReference: absolute or rises from
// each run's start) is one more hyperparameter chosen by the same folds among `references`.
//
// Ridge works on features standardised over the fitting samples with the penalty
// lambda * n * |beta|^2. Standard errors: the ridge sandwich sigma^2 A^-1 X'X A^-1 with
// sigma^2 from the residuals (n - effective degrees of freedom), inflated by
// sqrt((1 + r) / (1 - r)) for the lag-1 autocorrelation r of the training residuals.

#include "DataDrivenModel.h"
#include "ErrorMetrics.h"
#include "SignalTable.h"
#include "TimeBlockedFolds.h"

#include <functional>
#include <string>
#include <vector>

namespace driftlab {

// One run of training data: a table and the rows of it to fit (empty: all).
struct LinearLagRun {
    const SignalTable *table = nullptr;
    std::vector<char> rows;
};

struct LinearLagOptions {
    std::string kind = "dynamic";      // mlr | ridge | lagridge | dynamic
    std::string target;
    std::vector<std::string> inputs;   // temperature channels
    std::string drive;                 // dynamic only: spindle speed or feed channel (empty: none)
    std::vector<char> trainRows;       // grid rows to fit (empty: all); single-table fit() only
    std::vector<double> lambdas{1e-4, 1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.3, 1.0, 3.0};
    std::vector<std::vector<double>> temperatureLags{{0, 3600}, {0, 1800, 7200}, {0, 900, 3600, 14400}};
    std::vector<std::vector<double>> driveLags{{}, {1800, 7200}, {900, 3600, 14400}, {600, 1800, 5400, 16200}};
    std::vector<int> components{2, 3, 4, 5, 6, 8};
    // lagridge: candidate lag banks of every temperature channel.
    std::vector<std::vector<double>> ridgeLags{{0}, {0, 900}, {0, 1800}, {0, 3600}, {0, 900, 3600}, {0, 1800, 7200}};
    // Candidate temperature references; more than one: chosen by cross-validation.
    std::vector<TemperatureReference> references{TemperatureReference{}};
    int maxRunFolds = 10;
    int folds = 4;
    double gap_s = -1.0;               // < 0: TimeBlockedFolds::defaultGap
    // Inputs are scaled by max(standard deviation, floor) (K for temperatures): a channel that
    // barely moves is not blown up to the weight of one that carries the thermal load.
    double scaleFloor = 0.5;
    bool standardizeComponents = true; // dynamic: penalise the components per standard deviation
};

struct CvCandidate {
    int components = 0;                // 0: the channels themselves (mlr, ridge, lagridge)
    TemperatureReference reference;
    std::vector<double> temperatureLags_s{0.0};
    std::vector<double> driveLags_s;
    double lambda = 0.0;
    double cvRmse = 0.0;
    std::vector<double> foldRmse;
    std::size_t features = 0;
};

struct LinearLagFit {
    DataDrivenModel model;
    CvCandidate chosen;
    std::vector<CvCandidate> structures; // every structure searched, with its best penalty
    // Nested (selection-honest) CV: fold f scored with the candidate (structure, reference,
    // penalty) of lowest error on the other folds. chosen.cvRmse is optimistic by the search;
    // this is not, so families with searches of different size compare fairly.
    double nestedCvRmse = 0.0;
    std::vector<double> nestedFoldRmse;
    ErrorMetrics training;
    std::size_t trainingRows = 0;
    int folds = 0;
    double gap_s = 0.0;
    std::string foldRule;              // "time-blocked" or "leave-runs-out"
    std::size_t runs = 0;
    // The training mean (intercept only) scored on the same folds: a plain reference.
    CvCandidate mean;
    double trainingMean = 0.0;
    double residualLag1 = 0.0;
    double seInflation = 1.0;
    double effectiveDof = 0.0;
    std::vector<double> componentVariance; // dynamic: cumulative explained variance of the components
};

class LinearLagFitter {
public:
    // Throws std::invalid_argument naming the option or channel at fault; std::runtime_error
    // "cancelled" when progress(fraction) returns false.
    static LinearLagFit fit(const SignalTable &table, const LinearLagOptions &options,
                            const std::function<bool(double)> &progress = {});
    // Several runs; options.trainRows is ignored (each run carries its rows). Errors about a
    // run name it as "run N" (0-based).
    static LinearLagFit fit(const std::vector<LinearLagRun> &runs, const LinearLagOptions &options,
                            const std::function<bool(double)> &progress = {});
    // The folds over the stacked training rows of runs with rowCounts rows each (times: the
    // rows' times, used with one run only). Sets rule to the fold rule's name.
    // Nested CV over candidates' squared errors per fold (candidateFoldSse[c][f]): fold f is
    // scored with the candidate of lowest squared error summed over the other folds (ties: the
    // first); returns the pooled RMSE and sets foldRmse.
    static double nestedCv(const std::vector<std::vector<double>> &candidateFoldSse, const std::vector<double> &foldLength,
                           std::vector<double> &foldRmse);
    static std::vector<TimeBlockedFold> folds(const std::vector<std::size_t> &rowCounts, const std::vector<double> &times,
                                              int timeFolds, double gap_s, int maxRunFolds, std::string &rule);
};

} // namespace driftlab
