#pragma once
// Temperature-sensitive point selection, seed 003 Algorithm 1: the temperature rises and
// the displacement are z-scored; K-means (OpenCV cv::kmeans, k-means++ seeding, several
// attempts) clusters the temperature channels for every K in [kMin, kMax]; K* maximises the
// mean silhouette coefficient; in each cluster the channel with the highest Deng grey
// relational grade (rho = 0.5) to the displacement is chosen.
//
// Rules for imperfect data (stated in every result's `rule`):
//  - only grid rows where the target is present (and in the requested rows) are considered;
//  - a channel present on fewer than minValidFraction of those rows is excluded ("gaps");
//  - a channel whose standard deviation over the rows used is below 1e-9 (1 + |mean|) is
//    excluded ("constant": z-scoring would divide by zero);
//  - the rows used are those where the target and every remaining channel are present.
//
// Clustering works on an exact low-dimensional embedding of the z-scored channels (the
// eigenvectors of their Gram matrix scaled by the square roots of its eigenvalues, divided
// by sqrt(rows)): Euclidean distances between channels, and hence the K-means objective and
// the silhouette, are those of the full series, at a cost independent of the series length.

#include "SignalTable.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace driftlab {

struct SelectionOptions {
    std::string target;
    std::vector<std::string> channels; // empty: every temperature channel
    int kMin = 2;
    int kMax = 8;
    int attempts = 10;                 // cv::kmeans attempts per K
    std::uint64_t seed = 1;            // cv::RNG state before each K
    double rho = 0.5;                  // Deng's distinguishing coefficient
    double minValidFraction = 0.8;
    std::vector<char> rows;            // optional: grid rows to use (e.g. the training range)
};

struct ClusteringForK {
    int k = 0;
    double silhouette = 0.0;
    double compactness = 0.0;          // K-means objective (sum of squared distances)
    std::vector<int> labels;           // cluster of each selected channel
};

struct ExcludedChannel {
    std::string id;
    std::string reason;
};

struct SelectionResult {
    std::string target;
    std::vector<std::string> channels;  // clustered channels, in the table's order
    std::vector<ExcludedChannel> excluded;
    std::size_t rows = 0;               // samples used
    double from_s = 0.0, to_s = 0.0;    // time span of the rows used
    std::vector<ClusteringForK> perK;
    int chosenK = 0;
    std::vector<int> labels;            // cluster of each channel at K*, numbered by first member
    std::vector<std::vector<int>> clusters;
    std::vector<double> grade;          // grey grade within the channel's cluster (Algorithm 1)
    std::vector<double> gradeAll;       // grey grade with all channels as the comparison set (Table 5 style)
    std::vector<double> correlation;    // Pearson correlation with the target
    std::vector<double> correlationMatrix; // channels x channels, row-major
    std::vector<std::string> chosen;    // one per cluster, in cluster order
    std::string rule;
};

class SensitivePointSelector {
public:
    // Throws std::invalid_argument naming the target, a channel or the K range when the
    // selection is impossible (fewer than three usable channels or ten usable rows, ...).
    // `progress(fraction)` may return false to cancel (std::runtime_error "cancelled").
    static SelectionResult select(const SignalTable &table, const SelectionOptions &options,
                                  const std::function<bool(double)> &progress = {});

    // Mean silhouette coefficient (Rousseeuw 1987) from a full distance matrix (n x n,
    // row-major); a channel alone in its cluster scores 0.
    static double silhouette(const std::vector<double> &distances, const std::vector<int> &labels);
    // Deng's grey relational grades of each sequence to the reference: coefficient
    // (dmin + rho dmax) / (d + rho dmax) with d = |x0(k) - xi(k)| and dmin, dmax over all the
    // sequences and samples given; grade = mean coefficient.
    static std::vector<double> greyGrades(const std::vector<double> &reference,
                                          const std::vector<std::vector<double>> &sequences, double rho);
};

} // namespace driftlab
