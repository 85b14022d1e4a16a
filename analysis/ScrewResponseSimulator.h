#pragma once
// Fast unit-response simulator behind the identification (variable projection).
//
// For fixed h-law (k1, k2), conductivity lambda and fixed-end coordinate P_f the screw
// temperature field is linear in the heat inputs and the ambient. simulate() runs the
// implicit (Crank-Nicolson) scheme of CrankNicolsonScrewModel once for all inputs at once
// (one tridiagonal factorisation per step, one solve per input) and returns the design
// matrix: row = observation, column 0 = the response to the recorded ambient (coefficient 1,
// not fitted), then one column per heat-source component at unit amplitude, then one per
// error-term component. Prediction = column 0 + sum amplitude_c x column c. A component's
// contact conductance (HeatSourceComponent::addConductance, set by its nonlinear parameters)
// enters the operator like convection, so the field stays linear in the amplitudes.
//
// Large steps: the nut position and feed are sampled at `driveSample_s` inside each step and
// the nut heat, the nut's shielding from convection and the feed-dependent h are averaged
// over the step (with one sample per step this is exactly CrankNicolsonScrewModel).

#include "ErrorTermComponent.h"
#include "HeatSourceComponent.h"
#include "IdentificationTypes.h"
#include "ScrewCellLayout.h"
#include "TridiagonalSolver.h"

#include <Eigen/Dense>

#include <memory>
#include <vector>

namespace driftlab {

struct ResponseSimulatorOptions {
    FdmSettings grid{0.01, 20.0};       // implicit grid of the fit: dx (m), dt (s)
    double driveSample_s = 0.25;        // drive sampling inside a step
    double interferometerSigma_um = 1.0; // residual weight 1/sigma (see ScrewModelIdentifier)
    double elongationSigma_um = 1.0;
    double elongationInterval_s = 60.0; // probe samples used: at most one per interval
    double temperatureSigma_K = 0.1;    // screw temperature rows (value = T - T_a at the start, K)
    // true: the nut covers cells by the exact overlap of [X_N - L_N/2, X_N + L_N/2] (smooth in
    // P_f, total heat exactly Q_N: what the fit needs for derivatives in P_f); false: the
    // whole-cell rule of eq. (10) as in FdmScrewModel / CrankNicolsonScrewModel.
    bool fractionalNut = true;
    // Recordings are simulated on up to this many threads (0 = hardware concurrency).
    int threads = 0;
};

struct ResponseObservation {
    int recording = 0;
    bool elongation = false;
    double t_s = 0.0;
    double position_mm = 0.0; // interferometer target (P_x)
    double measured_um = 0.0;
    double sigma_um = 1.0;
    double referenceTime_s = 0.0; // NaN: none (model error at the start is zero)
    bool temperature = false;     // screw temperature rise at distance_m (elongation is false)
    double distance_m = 0.0;
};

class ScrewResponseSimulator {
public:
    // Throws std::invalid_argument for empty drives, observations outside a drive, bad options.
    ScrewResponseSimulator(const ScrewGeometry &geometry, const std::vector<ScrewRecording> &recordings,
                           const ResponseSimulatorOptions &options,
                           std::vector<std::shared_ptr<HeatSourceComponent>> sources,
                           std::vector<std::shared_ptr<ErrorTermComponent>> errorTerms = {});

    const std::vector<ResponseObservation> &observations() const { return m_obs; }
    int rowCount() const { return static_cast<int>(m_obs.size()); }
    int columnCount() const { return 1 + sourceCount() + errorTermCount(); }
    int sourceCount() const { return static_cast<int>(m_sources.size()); }
    int errorTermCount() const { return static_cast<int>(m_terms.size()); }
    const std::vector<std::shared_ptr<HeatSourceComponent>> &sources() const { return m_sources; }
    const std::vector<std::shared_ptr<ErrorTermComponent>> &errorTerms() const { return m_terms; }
    const ScrewGeometry &geometry() const { return m_geometry; }
    const ResponseSimulatorOptions &options() const { return m_options; }

    // Fills phi (rowCount x columnCount, um). Components' nonlinear parameters must be set.
    void simulate(double k1, double k2, double lambda_W_mK, double fixedEnd_mm, Eigen::MatrixXd &phi);

    // Cell updates (cells x steps x inputs) of the last simulate(), for benchmarks.
    double lastCellUpdates() const { return m_lastCellUpdates; }

private:
    struct Request {
        int boundary;
        int row;
        double weight;
    };
    struct Prepared {
        double t0 = 0.0;
        int steps = 0;
        int substeps = 1;
        std::vector<double> finePos_mm, fineFeed;   // steps x substeps
        std::vector<double> ambientDev;             // steps + 1 boundaries: T_a - T_a0
        std::vector<Request> requests;              // sorted by boundary
        double cachedFixedEnd = 0.0;
        bool cacheValid = false;
        std::vector<double> occ, vocc, meanFeed;    // steps x cells, steps x cells, steps
    };

    void prepare(const ScrewRecording &rec, int index);
    void updateOccupancy(Prepared &p, double fixedEnd_mm) const;
    // Returns the cell updates done.
    double runRecording(Prepared &p, const std::vector<std::shared_ptr<HeatSourceComponent>> &sources,
                        TridiagonalSolver &solver, double k1, double k2, double lambda, double fixedEnd_mm,
                        Eigen::MatrixXd &phi) const;

    ScrewGeometry m_geometry;
    ResponseSimulatorOptions m_options;
    ScrewCellLayout m_layout;
    std::vector<std::shared_ptr<HeatSourceComponent>> m_sources;
    std::vector<std::shared_ptr<ErrorTermComponent>> m_terms;
    std::vector<ResponseObservation> m_obs;
    std::vector<Prepared> m_prepared;
    Eigen::MatrixXd m_termColumns; // rows x terms, parameter-independent
    double m_lastCellUpdates = 0.0;
};

} // namespace driftlab
