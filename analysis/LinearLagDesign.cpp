#include "LinearLagDesign.h"

#include "DataDrivenPredictor.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

namespace driftlab {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// NaN -> the last finite value (the first finite value before it), as DataDrivenPredictor::run.
std::vector<double> held(const std::vector<double> &v)
{
    std::vector<double> out(v);
    double last = std::numeric_limits<double>::quiet_NaN();
    for (double x : v)
        if (std::isfinite(x)) {
            last = x;
            break;
        }
    for (double &x : out) {
        if (std::isfinite(x))
            last = x;
        else
            x = last;
    }
    return out;
}

} // namespace

LinearLagDesign::LinearLagDesign(const std::vector<LinearLagRun> &runs, const LinearLagOptions &o)
    : m_runs(runs), m_options(o)
{
    const std::size_t R = runs.size();
    const std::size_t nInputs = o.inputs.size();
    hasDrive = !o.drive.empty();

    // Columns of every run and the training rows (target and every input present).
    targets.assign(R, nullptr);
    drives.assign(R, nullptr);
    inputs.resize(R);
    for (std::size_t ri = 0; ri < R; ++ri) {
        const SignalTable &table = *runs[ri].table;
        const std::string where = R > 1 ? "run " + std::to_string(ri) + ": " : std::string();
        if (!runs[ri].rows.empty() && runs[ri].rows.size() != table.t.size())
            throw std::invalid_argument(where + "training rows do not match the grid");
        targets[ri] = &table.column(o.target);
        for (const std::string &id : o.inputs)
            inputs[ri].push_back(&table.column(id));
        if (hasDrive)
            drives[ri] = &table.column(o.drive);
        std::size_t count = 0;
        for (std::size_t k = 0; k < table.t.size(); ++k) {
            if ((!runs[ri].rows.empty() && !runs[ri].rows[k]) || !std::isfinite(targets[ri]->v[k]))
                continue;
            bool ok = !hasDrive || std::isfinite(drives[ri]->v[k]);
            for (const SignalColumn *c : inputs[ri])
                ok = ok && std::isfinite(c->v[k]);
            if (ok) {
                rows.push_back({ri, k});
                ++count;
            }
        }
        if (R > 1 && count == 0)
            throw std::invalid_argument(where + "no training sample has the target and every input");
        rowCounts.push_back(count);
    }
    const std::size_t minRows = std::max<std::size_t>(20, static_cast<std::size_t>(5 * std::max(o.folds, 2)));
    if (rows.size() < minRows)
        throw std::invalid_argument(o.kind + ": " + std::to_string(rows.size()) +
                                    " training samples have the target and every input; at least " +
                                    std::to_string(minRows) + " are needed");
    n = static_cast<Index>(rows.size());
    nT = static_cast<Index>(nInputs);

    // Held inputs on every run's grid (lag states and references run from each run's start).
    std::vector<std::vector<std::vector<double>>> heldInputs(R);
    for (std::size_t ri = 0; ri < R; ++ri)
        for (const SignalColumn *c : inputs[ri])
            heldInputs[ri].push_back(held(c->v));
    prepared.resize(o.references.size());
    for (std::size_t ci = 0; ci < o.references.size(); ++ci) {
        const TemperatureReference &ref = o.references[ci];
        if (ref.kind != "absolute" && ref.kind != "start")
            throw std::invalid_argument(o.kind + ": unknown temperature reference '" + ref.kind + "'");
        Prepared &p = prepared[ci];
        p.offset.resize(nInputs);
        p.scale.resize(nInputs);
        p.z.assign(R, std::vector<std::vector<double>>(nInputs));
        std::vector<std::vector<std::vector<double>>> x(R, std::vector<std::vector<double>>(nInputs));
        for (std::size_t ri = 0; ri < R; ++ri)
            for (std::size_t i = 0; i < nInputs; ++i) {
                const std::vector<double> &h = heldInputs[ri][i];
                const std::vector<double> r = DataDrivenPredictor::referenceSeries(ref, runs[ri].table->t, h);
                x[ri][i].resize(h.size());
                for (std::size_t k = 0; k < h.size(); ++k)
                    x[ri][i][k] = h[k] - r[k];
            }
        for (std::size_t i = 0; i < nInputs; ++i) {
            double mean = 0.0, var = 0.0;
            for (const Row &r : rows)
                mean += x[r.run][i][r.k];
            mean /= static_cast<double>(n);
            for (const Row &r : rows)
                var += (x[r.run][i][r.k] - mean) * (x[r.run][i][r.k] - mean);
            const double sd = std::sqrt(var / static_cast<double>(n));
            if (!(sd > 1e-9 * (1.0 + std::fabs(mean)))) {
                if (ref.kind == "absolute" || o.references.size() == 1)
                    throw std::invalid_argument("input '" + o.inputs[i] + "' is constant over the training samples");
            }
            p.offset[i] = mean;
            p.scale[i] = std::max({sd, o.scaleFloor, 1e-12});
            for (std::size_t ri = 0; ri < R; ++ri) {
                std::vector<double> &zz = p.z[ri][i];
                zz.resize(x[ri][i].size());
                for (std::size_t k = 0; k < zz.size(); ++k)
                    zz[k] = (x[ri][i][k] - mean) / p.scale[i];
            }
        }
    }
    m_driveHeld.resize(R);
    if (hasDrive) {
        driveScale = 0.0;
        for (std::size_t ri = 0; ri < R; ++ri)
            m_driveHeld[ri] = held(drives[ri]->v);
        for (const Row &r : rows)
            driveScale = std::max(driveScale, std::fabs(m_driveHeld[r.run][r.k]));
        if (!(driveScale > 0))
            throw std::invalid_argument("drive '" + o.drive + "' is zero over the training samples");
    }
    y.resize(n);
    for (Index r = 0; r < n; ++r) {
        const Row &row = rows[static_cast<std::size_t>(r)];
        y(r) = targets[row.run]->v[row.k];
    }
}

const MatrixXd &LinearLagDesign::laggedZ(std::size_t ci, double tau)
{
    const auto key = std::make_pair(ci, tau);
    auto it = m_lagged.find(key);
    if (it != m_lagged.end())
        return it->second;
    const std::size_t R = m_runs.size();
    MatrixXd m(n, nT);
    for (Index i = 0; i < nT; ++i) {
        std::vector<std::vector<double>> x(R);
        for (std::size_t ri = 0; ri < R; ++ri)
            x[ri] = DataDrivenPredictor::lagSeries(m_runs[ri].table->t, prepared[ci].z[ri][static_cast<std::size_t>(i)], tau);
        for (Index r = 0; r < n; ++r) {
            const Row &row = rows[static_cast<std::size_t>(r)];
            m(r, i) = x[row.run][row.k];
        }
    }
    return m_lagged.emplace(key, std::move(m)).first->second;
}

const VectorXd &LinearLagDesign::driveFeature(int power, double tau)
{
    const auto key = std::make_pair(power, tau);
    auto it = m_laggedDrive.find(key);
    if (it != m_laggedDrive.end())
        return it->second;
    const std::size_t R = m_runs.size();
    std::vector<std::vector<double>> x(R);
    for (std::size_t ri = 0; ri < R; ++ri) {
        std::vector<double> g(m_driveHeld[ri].size());
        for (std::size_t k = 0; k < g.size(); ++k) {
            const double v = m_driveHeld[ri][k] / driveScale;
            g[k] = power == 2 ? v * v : v;
        }
        x[ri] = DataDrivenPredictor::lagSeries(m_runs[ri].table->t, g, tau);
    }
    VectorXd out(n);
    for (Index r = 0; r < n; ++r) {
        const Row &row = rows[static_cast<std::size_t>(r)];
        out(r) = x[row.run][row.k];
    }
    return m_laggedDrive.emplace(key, std::move(out)).first->second;
}

MatrixXd LinearLagDesign::design(const LinearLagStructure &s)
{
    const Index perLag = s.components == 0 ? nT : s.components;
    const Index p = static_cast<Index>(s.temperatureLags.size()) * perLag + 2 * static_cast<Index>(s.driveLags.size());
    MatrixXd X(n, p);
    Index j = 0;
    for (double tau : s.temperatureLags) {
        const MatrixXd &L = laggedZ(s.reference, tau);
        if (s.components == 0)
            X.middleCols(j, nT) = L;
        else
            X.middleCols(j, perLag).noalias() = L * prepared[s.reference].W.topRows(s.components).transpose();
        j += perLag;
    }
    for (int power : {1, 2})
        for (double tau : s.driveLags)
            X.col(j++) = driveFeature(power, tau);
    return X;
}

// The same design as blocks for BlockGram: lagged temperatures (projected on the components)
// and a selection of the drive features, which are columns of one matrix.
void LinearLagDesign::buildDriveMatrix()
{
    if (!hasDrive)
        return;
    std::set<double> taus;
    for (const std::vector<double> &bank : m_options.driveLags)
        taus.insert(bank.begin(), bank.end());
    m_driveMatrix.resize(n, 2 * static_cast<Index>(taus.size()));
    Index j = 0;
    for (int power : {1, 2})
        for (double tau : taus) {
            m_driveMatrix.col(j) = driveFeature(power, tau);
            m_driveColumn[{power, tau}] = j++;
        }
}

std::vector<BlockGram::Block> LinearLagDesign::designBlocks(const LinearLagStructure &s)
{
    std::vector<BlockGram::Block> blocks;
    for (double tau : s.temperatureLags) {
        BlockGram::Block b;
        b.matrix = &laggedZ(s.reference, tau);
        if (s.components > 0)
            b.projection = prepared[s.reference].W.topRows(s.components).transpose();
        blocks.push_back(std::move(b));
    }
    if (!s.driveLags.empty()) {
        BlockGram::Block b;
        b.matrix = &m_driveMatrix;
        b.projection = MatrixXd::Zero(m_driveMatrix.cols(), 2 * static_cast<Index>(s.driveLags.size()));
        Index j = 0;
        for (int power : {1, 2})
            for (double tau : s.driveLags)
                b.projection(m_driveColumn.at({power, tau}), j++) = 1.0;
        blocks.push_back(std::move(b));
    }
    return blocks;
}

VectorXd LinearLagDesign::priorScale(const LinearLagStructure &s, Index columns) const
{
    VectorXd prior = VectorXd::Zero(columns);
    if (s.components > 0 && !m_options.standardizeComponents)
        prior.head(static_cast<Index>(s.temperatureLags.size()) * s.components).setOnes();
    return prior;
}

std::vector<double> LinearLagDesign::times() const
{
    std::vector<double> out(rows.size());
    for (std::size_t r = 0; r < rows.size(); ++r)
        out[r] = m_runs[rows[r].run].table->t[rows[r].k];
    return out;
}

} // namespace driftlab
