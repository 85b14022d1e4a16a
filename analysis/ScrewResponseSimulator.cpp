#include "ScrewResponseSimulator.h"

#include <algorithm>
#include <limits>
#include <cmath>
#include <sstream>
#include <exception>
#include <functional>
#include <stdexcept>
#include <thread>

namespace driftlab {

namespace {
constexpr double kPi = 3.14159265358979323846;

std::invalid_argument inputError(const std::string &recording, const std::string &what)
{
    return std::invalid_argument("recording '" + recording + "': " + what);
}

// R = (I + dt/2 L) T + dt F for the interleaved columns (x[i * cols + c]); C > 0 fixes the
// column count at compile time, C == 0 takes cols.
template <int C>
void explicitHalf(const double *T, const double *F, const double *conv, double half, double hr, int n, int cols, double *R)
{
    const int k = C > 0 ? C : cols;
    {
        const double w0 = 1.0 - half * conv[0] - hr;
        for (int c = 0; c < k; ++c)
            R[c] = w0 * T[c] + hr * T[k + c] + F[c];
    }
    for (int i = 1; i < n - 1; ++i) {
        const double wi = 1.0 - half * conv[i] - 2.0 * hr;
        const double *Ti = T + static_cast<size_t>(i) * k;
        const double *Fi = F + static_cast<size_t>(i) * k;
        double *Ri = R + static_cast<size_t>(i) * k;
        for (int c = 0; c < k; ++c)
            Ri[c] = wi * Ti[c] + hr * (Ti[c - k] + Ti[c + k]) + Fi[c];
    }
    {
        const size_t last = static_cast<size_t>(n - 1) * k;
        const double wl = 1.0 - half * conv[n - 1] - hr;
        for (int c = 0; c < k; ++c)
            R[last + c] = wl * T[last + c] + hr * T[last - k + c] + F[last + c];
    }
}
} // namespace

ScrewResponseSimulator::ScrewResponseSimulator(const ScrewGeometry &geometry,
                                               const std::vector<ScrewRecording> &recordings,
                                               const ResponseSimulatorOptions &options,
                                               std::vector<std::shared_ptr<HeatSourceComponent>> sources,
                                               std::vector<std::shared_ptr<ErrorTermComponent>> errorTerms)
    : m_geometry(geometry), m_options(options), m_layout(geometry, options.grid), m_sources(std::move(sources)),
      m_terms(std::move(errorTerms))
{
    if (!(options.grid.dt_s > 0) || !(options.driveSample_s > 0))
        throw std::invalid_argument("response simulator: grid dt_s and driveSample_s must be > 0");
    if (!(options.interferometerSigma_um > 0) || !(options.elongationSigma_um > 0) || !(options.temperatureSigma_K > 0))
        throw std::invalid_argument("response simulator: observation sigmas must be > 0");
    if (recordings.empty())
        throw std::invalid_argument("response simulator: no recordings");
    for (const auto &s : m_sources)
        if (!s)
            throw std::invalid_argument("response simulator: null heat source");
    for (const auto &t : m_terms)
        if (!t)
            throw std::invalid_argument("response simulator: null error term");
    m_prepared.resize(recordings.size());
    for (size_t i = 0; i < recordings.size(); ++i)
        prepare(recordings[i], static_cast<int>(i));
    for (Prepared &p : m_prepared)
        std::stable_sort(p.requests.begin(), p.requests.end(),
                         [](const Request &a, const Request &b) { return a.boundary < b.boundary; });

    // Error-term columns do not depend on the screw parameters: evaluate once.
    m_termColumns.setZero(rowCount(), errorTermCount());
    for (int r = 0; r < rowCount(); ++r) {
        const ResponseObservation &o = m_obs[static_cast<size_t>(r)];
        const ScrewRecording &rec = recordings[static_cast<size_t>(o.recording)];
        const Prepared &p = m_prepared[static_cast<size_t>(o.recording)];
        ErrorObservation eo;
        eo.elongation = o.elongation;
        eo.temperature = o.temperature;
        eo.t_s = o.t_s;
        eo.elapsed_s = o.t_s - p.t0;
        eo.position_mm = o.position_mm;
        if (!rec.drive.ambient_C.empty()) {
            const double a0 = rec.drive.ambient_C.at(p.t0);
            eo.ambientDeviation_K = rec.drive.ambient_C.at(o.t_s) - a0;
            if (std::isfinite(o.referenceTime_s) && !o.elongation && !o.temperature)
                eo.referenceAmbientDeviation_K = rec.drive.ambient_C.at(o.referenceTime_s) - a0;
        }
        for (int c = 0; c < errorTermCount(); ++c)
            m_termColumns(r, c) = m_terms[static_cast<size_t>(c)]->unitValue(eo);
    }
}

void ScrewResponseSimulator::prepare(const ScrewRecording &rec, int index)
{
    Prepared &p = m_prepared[static_cast<size_t>(index)];
    const ScrewDrive &d = rec.drive;
    if (d.position_mm.empty() || d.feed_mm_min.empty())
        throw inputError(rec.name, "the drive needs axis position and feed series");
    p.t0 = d.position_mm.t.front();
    const double dt = m_options.grid.dt_s;

    // Observations (rows) and the time span they need.
    double tEnd = p.t0;
    const double tDriveEnd = std::max(d.position_mm.t.back(), d.feed_mm_min.t.back());
    auto checkTime = [&](double t, const char *what) {
        if (!std::isfinite(t) || t < p.t0 - 1e-9 || t > tDriveEnd + dt)
            throw inputError(rec.name, std::string(what) + " at t = " + std::to_string(t) +
                                           " s lies outside the drive [" + std::to_string(p.t0) + ", " +
                                           std::to_string(tDriveEnd) + "] s");
        tEnd = std::max(tEnd, t);
    };
    const int firstRow = rowCount();
    for (const PositioningErrorPoint &ip : rec.interferometer) {
        checkTime(ip.t_s, "interferometer point");
        if (!std::isfinite(ip.position_mm) || !std::isfinite(ip.error_um))
            throw inputError(rec.name, "non-finite interferometer point at t = " + std::to_string(ip.t_s));
        const double ref = std::isfinite(ip.referenceTime_s) ? ip.referenceTime_s : rec.referenceTime_s;
        if (std::isfinite(ref))
            checkTime(ref, "reference run");
        m_obs.push_back({index, false, ip.t_s, ip.position_mm, ip.error_um, m_options.interferometerSigma_um, ref});
    }
    double lastKept = -std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < rec.elongation_um.size(); ++k) {
        const double t = rec.elongation_um.t[k];
        if (t > tDriveEnd + dt || t < p.t0)
            continue; // probe samples outside the drive carry no information for the model
        if (t < lastKept + m_options.elongationInterval_s - 1e-9)
            continue;
        if (!std::isfinite(rec.elongation_um.v[k]))
            continue;
        lastKept = t;
        tEnd = std::max(tEnd, t);
        m_obs.push_back({index, true, t, 0.0, rec.elongation_um.v[k], m_options.elongationSigma_um,
                         std::numeric_limits<double>::quiet_NaN()});
    }
    const double ambient0 = d.ambient_C.empty() ? 20.0 : d.ambient_C.at(p.t0);
    for (const ScrewTemperaturePoint &tp : rec.screwTemperatures) {
        checkTime(tp.t_s, "screw temperature");
        if (!(tp.distance_m >= 0.0 && tp.distance_m <= m_geometry.length_m) || !std::isfinite(tp.temperature_C))
            throw inputError(rec.name, "screw temperature at t = " + std::to_string(tp.t_s) + " s: distance " +
                                           std::to_string(tp.distance_m) + " m outside the screw or value not finite");
        ResponseObservation o{index, false, tp.t_s, 0.0, tp.temperature_C - ambient0, m_options.temperatureSigma_K,
                              std::numeric_limits<double>::quiet_NaN()};
        o.temperature = true;
        o.distance_m = tp.distance_m;
        m_obs.push_back(o);
    }
    if (rowCount() == firstRow)
        throw inputError(rec.name, "no interferometer points, elongation samples or screw temperatures inside the drive");

    p.steps = std::max(1, static_cast<int>(std::ceil((tEnd - p.t0) / dt - 1e-9)));
    p.substeps = std::max(1, static_cast<int>(std::lround(dt / m_options.driveSample_s)));
    const double fine = dt / p.substeps;
    const size_t nFine = static_cast<size_t>(p.steps) * static_cast<size_t>(p.substeps);
    p.finePos_mm.resize(nFine);
    p.fineFeed.resize(nFine);
    TimeSeries::Cursor pos(d.position_mm), feed(d.feed_mm_min);
    for (size_t k = 0; k < nFine; ++k) {
        const double t = p.t0 + static_cast<double>(k) * fine;
        p.finePos_mm[k] = pos.at(t);
        p.fineFeed[k] = std::fabs(feed.at(t));
    }
    p.ambientDev.assign(static_cast<size_t>(p.steps) + 1, 0.0);
    if (!d.ambient_C.empty()) {
        TimeSeries::Cursor amb(d.ambient_C);
        const double a0 = amb.at(p.t0);
        for (int j = 0; j <= p.steps; ++j)
            p.ambientDev[static_cast<size_t>(j)] = amb.at(p.t0 + j * dt) - a0;
    }

    // Each observation is read at the two step boundaries around its time (linear
    // interpolation); interferometer rows also subtract the model at the reference run.
    auto addRequests = [&](double t, int row, double sign) {
        const double u = (t - p.t0) / dt;
        int j = std::clamp(static_cast<int>(std::floor(u)), 0, p.steps);
        double w = std::clamp(u - j, 0.0, 1.0);
        if (j == p.steps) {
            w = 0.0;
        }
        if (1.0 - w > 0.0 && j > 0)
            p.requests.push_back({j, row, sign * (1.0 - w)});
        if (w > 0.0)
            p.requests.push_back({j + 1, row, sign * w});
    };
    for (int r = firstRow; r < rowCount(); ++r) {
        const ResponseObservation &o = m_obs[static_cast<size_t>(r)];
        addRequests(o.t_s, r, 1.0);
        if (!o.elongation && !o.temperature && std::isfinite(o.referenceTime_s))
            addRequests(o.referenceTime_s, r, -1.0);
    }
}

void ScrewResponseSimulator::updateOccupancy(Prepared &p, double fixedEnd_mm) const
{
    if (p.cacheValid && p.cachedFixedEnd == fixedEnd_mm)
        return;
    const int n = m_layout.cellCount();
    const int S = p.substeps;
    p.occ.assign(static_cast<size_t>(p.steps) * n, 0.0);
    p.vocc.assign(static_cast<size_t>(p.steps) * n, 0.0);
    p.meanFeed.assign(static_cast<size_t>(p.steps), 0.0);
    std::vector<double> dOcc(static_cast<size_t>(n) + 1), dV(static_cast<size_t>(n) + 1);
    const double inv = 1.0 / S;
    const double halfNut = m_geometry.nutLength_m / 2.0;
    const double dxm = m_layout.dx_m();
    for (int j = 0; j < p.steps; ++j) {
        std::fill(dOcc.begin(), dOcc.end(), 0.0);
        std::fill(dV.begin(), dV.end(), 0.0);
        double vSum = 0.0;
        const size_t base = static_cast<size_t>(j) * static_cast<size_t>(S);
        for (int k = 0; k < S; ++k) {
            const double v = p.fineFeed[base + static_cast<size_t>(k)];
            vSum += v;
            const double centre_m = std::fabs(p.finePos_mm[base + static_cast<size_t>(k)] - fixedEnd_mm) / 1000.0;
            if (m_options.fractionalNut) {
                // Exact overlap in cell units; partial end cells through the difference array
                // as two opposite point corrections.
                const double a = std::clamp((centre_m - halfNut) / dxm, 0.0, static_cast<double>(n));
                const double b = std::clamp((centre_m + halfNut) / dxm, 0.0, static_cast<double>(n));
                if (b > a) {
                    const int ia = std::min(n - 1, static_cast<int>(a));
                    const int ib = std::min(n - 1, static_cast<int>(b));
                    auto add = [&](int i0, int i1, double w) { // cells [i0, i1) get w
                        dOcc[static_cast<size_t>(i0)] += w;
                        dOcc[static_cast<size_t>(i1)] -= w;
                        dV[static_cast<size_t>(i0)] += w * v;
                        dV[static_cast<size_t>(i1)] -= w * v;
                    };
                    if (ia == ib) {
                        add(ia, ia + 1, b - a);
                    } else {
                        add(ia, ia + 1, ia + 1 - a);
                        if (ib > ia + 1)
                            add(ia + 1, ib, 1.0);
                        add(ib, ib + 1, b - ib);
                    }
                }
            } else {
                int first = 0, last = -1;
                m_layout.nutCells(centre_m, first, last);
                if (first <= last) {
                    dOcc[static_cast<size_t>(first)] += 1.0;
                    dOcc[static_cast<size_t>(last) + 1] -= 1.0;
                    dV[static_cast<size_t>(first)] += v;
                    dV[static_cast<size_t>(last) + 1] -= v;
                }
            }
        }
        p.meanFeed[static_cast<size_t>(j)] = vSum * inv;
        double o = 0.0, ov = 0.0;
        double *occ = p.occ.data() + static_cast<size_t>(j) * n;
        double *vocc = p.vocc.data() + static_cast<size_t>(j) * n;
        for (int i = 0; i < n; ++i) {
            o += dOcc[static_cast<size_t>(i)];
            ov += dV[static_cast<size_t>(i)];
            occ[i] = o * inv;
            vocc[i] = ov * inv;
        }
    }
    p.cachedFixedEnd = fixedEnd_mm;
    p.cacheValid = true;
}

void ScrewResponseSimulator::simulate(double k1, double k2, double lambda, double fixedEnd_mm, Eigen::MatrixXd &phi)
{
    if (!(lambda > 0) || !std::isfinite(k1) || !std::isfinite(k2) || !std::isfinite(fixedEnd_mm))
        throw std::invalid_argument("response simulator: lambda must be > 0 and k1, k2, P_f finite");
    phi.setZero(rowCount(), columnCount());
    m_lastCellUpdates = 0.0;
    const int recs = static_cast<int>(m_prepared.size());
    int threads = m_options.threads > 0 ? m_options.threads : static_cast<int>(std::thread::hardware_concurrency());
    threads = std::clamp(threads, 1, recs);
    if (threads == 1) {
        TridiagonalSolver solver;
        for (Prepared &p : m_prepared)
            m_lastCellUpdates += runRecording(p, m_sources, solver, k1, k2, lambda, fixedEnd_mm, phi);
    } else {
        // Recording r runs on thread r % threads; rows of phi are disjoint per recording.
        std::vector<double> updates(static_cast<size_t>(threads), 0.0);
        std::vector<std::exception_ptr> errors(static_cast<size_t>(threads));
        auto work = [&](int t, const std::vector<std::shared_ptr<HeatSourceComponent>> &sources) {
            try {
                TridiagonalSolver solver;
                for (int r = t; r < recs; r += threads)
                    updates[static_cast<size_t>(t)] +=
                        runRecording(m_prepared[static_cast<size_t>(r)], sources, solver, k1, k2, lambda, fixedEnd_mm, phi);
            } catch (...) {
                errors[static_cast<size_t>(t)] = std::current_exception();
            }
        };
        std::vector<std::vector<std::shared_ptr<HeatSourceComponent>>> copies(static_cast<size_t>(threads));
        for (int t = 1; t < threads; ++t)
            for (const auto &s : m_sources)
                copies[static_cast<size_t>(t)].push_back(s->clone());
        std::vector<std::thread> pool;
        for (int t = 1; t < threads; ++t)
            pool.emplace_back(work, t, std::cref(copies[static_cast<size_t>(t)]));
        work(0, m_sources);
        for (std::thread &th : pool)
            th.join();
        for (const std::exception_ptr &e : errors)
            if (e)
                std::rethrow_exception(e);
        for (double u : updates)
            m_lastCellUpdates += u;
    }
    if (errorTermCount() > 0)
        phi.rightCols(errorTermCount()) = m_termColumns;
}

double ScrewResponseSimulator::runRecording(Prepared &p, const std::vector<std::shared_ptr<HeatSourceComponent>> &sources,
                                            TridiagonalSolver &solver, double k1, double k2, double lambda,
                                            double fixedEnd_mm, Eigen::MatrixXd &phi) const
{
    updateOccupancy(p, fixedEnd_mm);
    for (const auto &s : sources)
        s->beginRecording();
    double cellUpdates = 0.0;
    const int n = m_layout.cellCount();
    const int nb = m_layout.bearingCells();
    const int cols = 1 + sourceCount(); // columns that go through the temperature field
    const double dx = m_options.grid.dx_m;
    const double dt = m_options.grid.dt_s;
    const double D = m_geometry.diameter_m;
    const double rhoC = m_geometry.density_kg_m3 * m_geometry.specificHeat_J_kgK;
    const double area = kPi * D * D / 4.0;
    const double r = lambda / (rhoC * dx * dx);
    const double lat = 4.0 / (rhoC * D);     // x h -> 1/s
    const double face = 1.0 / (rhoC * dx);   // x h -> 1/s
    const double wattsToRate = 1.0 / (rhoC * area * dx);
    const double half = 0.5 * dt;
    const double outScale = m_geometry.expansion_per_K * 1e6; // K m -> um

    // State, right-hand side and forcing, interleaved by input: x[i * cols + c].
    const size_t nc = static_cast<size_t>(n) * static_cast<size_t>(cols);
    std::vector<double> T(nc, 0.0), R(nc), F(nc);
    std::vector<double> lower(static_cast<size_t>(n), -half * r), upper(static_cast<size_t>(n), -half * r),
        watts(static_cast<size_t>(n)), cum(static_cast<size_t>(n) + 1);
    HeatStepInput in;
    in.dt_s = dt;
    in.layout = &m_layout;
    in.geometry = &m_geometry;
    in.fineCount = p.substeps;
    size_t next = 0;
    const double hr = half * r;
    // Contact conductances of the components (W/K per cell), refilled every step.
    std::vector<double> contact(static_cast<size_t>(n), 0.0);
    auto stepInput = [&](int j) {
        const double vbar = p.meanFeed[static_cast<size_t>(j)];
        in.meanFeed_mm_min = vbar;
        in.nutOccupancy = p.occ.data() + static_cast<size_t>(j) * n;
        in.nutFeed = p.vocc.data() + static_cast<size_t>(j) * n;
        in.fineFeed_mm_min = p.fineFeed.data() + static_cast<size_t>(j) * p.substeps;
        in.ambientDeviation_K =
            0.5 * (p.ambientDev[static_cast<size_t>(j)] + p.ambientDev[static_cast<size_t>(j) + 1]);
    };
    // The steps' matrices do not depend on the temperatures (contacts are set by the nonlinear
    // parameters alone: addConductance is const), so a block of steps is factored together,
    // side by side, before the block is stepped through.
    constexpr int kBlock = TridiagonalSolver::kMaxSystems;
    std::vector<double> convBlock(static_cast<size_t>(kBlock) * n), diagBlock(static_cast<size_t>(kBlock) * n);
    for (int j0 = 0; j0 < p.steps; j0 += kBlock) {
        const int count = std::min(kBlock, p.steps - j0);
        for (int b = 0; b < count; ++b) {
            const int j = j0 + b;
            stepInput(j);
            const double vbar = in.meanFeed_mm_min;
            const double *occ = in.nutOccupancy;
            const double *vocc = in.nutFeed;
            double *conv = convBlock.data() + static_cast<size_t>(b) * n;
            double *diag = diagBlock.data() + static_cast<size_t>(b) * n;
            for (int i = 0; i < n; ++i) {
                // mean over the step of h(t) x (not under nut or bearing)
                const double shielded = i < nb ? 0.0 : k1 * (vbar - vocc[i]) + k2 * (1.0 - occ[i]);
                conv[static_cast<size_t>(i)] = lat * std::max(0.0, shielded);
            }
            conv[static_cast<size_t>(n) - 1] += face * std::max(0.0, k1 * vbar + k2);
            // Contacts (W/K) act like convection: a sink to ambient on the diagonal, the ambient's
            // share through column 0.
            std::fill(contact.begin(), contact.end(), 0.0);
            for (const auto &s : sources)
                s->addConductance(in, contact.data());
            for (int i = 0; i < n; ++i)
                conv[static_cast<size_t>(i)] += wattsToRate * contact[static_cast<size_t>(i)];
            for (int i = 0; i < n; ++i)
                diag[static_cast<size_t>(i)] = 1.0 + half * (2.0 * r + conv[static_cast<size_t>(i)]);
            diag[0] -= hr;
            diag[static_cast<size_t>(n) - 1] -= hr;
        }
        solver.factorSeveral(lower.data(), diagBlock.data(), upper.data(), n, count);
        for (int b = 0; b < count; ++b) {
            const int j = j0 + b;
            stepInput(j);
            solver.select(b);
            const double *conv = convBlock.data() + static_cast<size_t>(b) * n;

            // Forcing (K/s): ambient through convection in column 0, unit heat in the others.
            const double TaMid = in.ambientDeviation_K;
            for (int i = 0; i < n; ++i)
                F[static_cast<size_t>(i) * cols] = dt * conv[static_cast<size_t>(i)] * TaMid;
            for (int c = 1; c < cols; ++c) {
                std::fill(watts.begin(), watts.end(), 0.0);
                sources[static_cast<size_t>(c) - 1]->addUnitHeat(in, watts.data());
                for (int i = 0; i < n; ++i)
                    F[static_cast<size_t>(i) * cols + static_cast<size_t>(c)] = dt * wattsToRate * watts[static_cast<size_t>(i)];
            }

            // Explicit half: R = (I + dt/2 L) T + dt F; adiabatic fixed end, end face in conv.
            switch (cols) { // the column count fixed at compile time where it is small (same operations)
            case 2: explicitHalf<2>(T.data(), F.data(), conv, half, hr, n, cols, R.data()); break;
            case 3: explicitHalf<3>(T.data(), F.data(), conv, half, hr, n, cols, R.data()); break;
            case 4: explicitHalf<4>(T.data(), F.data(), conv, half, hr, n, cols, R.data()); break;
            case 5: explicitHalf<5>(T.data(), F.data(), conv, half, hr, n, cols, R.data()); break;
            case 6: explicitHalf<6>(T.data(), F.data(), conv, half, hr, n, cols, R.data()); break;
            default: explicitHalf<0>(T.data(), F.data(), conv, half, hr, n, cols, R.data()); break;
            }
            solver.solveInterleaved(R.data(), cols);
            T.swap(R);
            cellUpdates += static_cast<double>(n) * cols;

            // Observations read at boundary j + 1.
            const int boundary = j + 1;
            if (next < p.requests.size() && p.requests[next].boundary == boundary) {
                for (int c = 0; c < cols; ++c) {
                    cum[0] = 0.0;
                    for (int i = 0; i < n; ++i)
                        cum[static_cast<size_t>(i) + 1] = cum[static_cast<size_t>(i)] + T[static_cast<size_t>(i) * cols + c] * dx;
                    for (size_t q = next; q < p.requests.size() && p.requests[q].boundary == boundary; ++q) {
                        const Request &rq = p.requests[q];
                        const ResponseObservation &o = m_obs[static_cast<size_t>(rq.row)];
                        double value = 0.0;
                        if (o.temperature) {
                            // Temperature rise of the cell containing the point (K, no expansion scale).
                            const int cell = std::clamp(static_cast<int>(std::floor(o.distance_m / dx)), 0, n - 1);
                            phi(rq.row, c) += rq.weight * T[static_cast<size_t>(cell) * cols + c];
                            continue;
                        }
                        if (o.elongation) {
                            value = cum[static_cast<size_t>(n)];
                        } else {
                            // eq. (13)-(16): expansion from the fixed end to |P_x - P_f|, signed.
                            const double d_mm = o.position_mm - fixedEnd_mm;
                            const double x = std::clamp(std::fabs(d_mm) / 1000.0, 0.0, dx * n);
                            const int m = std::min(n, static_cast<int>(std::floor(x / dx)));
                            value = cum[static_cast<size_t>(m)] +
                                    (m < n ? (x - m * dx) * T[static_cast<size_t>(m) * cols + c] : 0.0);
                            if (d_mm < 0)
                                value = -value;
                        }
                        phi(rq.row, c) += rq.weight * outScale * value;
                    }
                }
                while (next < p.requests.size() && p.requests[next].boundary == boundary)
                    ++next;
            }
        }
    }
    return cellUpdates;
}

} // namespace driftlab
