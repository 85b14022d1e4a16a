#pragma once
// The training data of a LinearLagFitter fit, shared by every candidate structure: the rows of
// every run that have the target and every input, the inputs normalised under each candidate
// temperature reference, the drive scaled to its training maximum, and the lagged features
// (cached per reference or drive power and time constant), assembled into a candidate's design
// matrix or into BlockGram blocks.

#include "BlockGram.h"
#include "LinearLagFitter.h"

#include <Eigen/Dense>

#include <map>
#include <utility>
#include <vector>

namespace driftlab {

// One candidate structure: principal components (0: the channels themselves), the lag banks
// of the temperatures and of the drive, and the temperature reference (index into the
// candidate references).
struct LinearLagStructure {
    int components = 0;
    std::vector<double> temperatureLags{0.0};
    std::vector<double> driveLags;
    std::size_t reference = 0;
};

class LinearLagDesign {
public:
    struct Row {
        std::size_t run = 0, k = 0;
    };
    // Inputs under one temperature reference: normalised values on every run's grid.
    struct Prepared {
        std::vector<double> offset, scale;
        std::vector<std::vector<std::vector<double>>> z; // run, input, grid row
        Eigen::MatrixXd W;                               // dynamic: components x inputs
        std::vector<double> componentVariance;
    };

    // Throws std::invalid_argument naming the run, channel or option at fault.
    LinearLagDesign(const std::vector<LinearLagRun> &runs, const LinearLagOptions &options);

    // Lagged normalised temperatures at the training rows (rows x inputs).
    const Eigen::MatrixXd &laggedZ(std::size_t reference, double tau);
    // The scaled drive to the power 1 or 2, lagged, at the training rows.
    const Eigen::VectorXd &driveFeature(int power, double tau);
    Eigen::MatrixXd design(const LinearLagStructure &s);
    // Every drive feature of the candidate banks as the columns of one matrix (for designBlocks).
    void buildDriveMatrix();
    std::vector<BlockGram::Block> designBlocks(const LinearLagStructure &s);
    // Scales of the features in the ridge penalty: 0 = the feature's own standard deviation.
    Eigen::VectorXd priorScale(const LinearLagStructure &s, Eigen::Index columns) const;
    // The times of the training rows.
    std::vector<double> times() const;

    std::vector<const SignalColumn *> targets, drives;
    std::vector<std::vector<const SignalColumn *>> inputs;
    std::vector<Row> rows;
    std::vector<std::size_t> rowCounts;
    std::vector<Prepared> prepared; // per candidate reference
    double driveScale = 1.0;
    Eigen::VectorXd y;
    Eigen::Index n = 0, nT = 0;
    bool hasDrive = false;

private:
    const std::vector<LinearLagRun> &m_runs;
    const LinearLagOptions &m_options;
    std::vector<std::vector<double>> m_driveHeld;
    std::map<std::pair<std::size_t, double>, Eigen::MatrixXd> m_lagged;
    std::map<std::pair<int, double>, Eigen::VectorXd> m_laggedDrive;
    Eigen::MatrixXd m_driveMatrix;
    std::map<std::pair<int, double>, Eigen::Index> m_driveColumn;
};

} // namespace driftlab
