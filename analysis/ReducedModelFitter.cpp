#include "ReducedModelFitter.h"

#include <algorithm>
#include <stdexcept>

namespace driftlab {

LinearLagOptions ReducedModelFitter::without(const LinearLagOptions &options, const CvCandidate &chosen, const std::string &input)
{
    LinearLagOptions o = options;
    o.references = {chosen.reference};
    if (o.kind != "mlr")
        o.lambdas = {chosen.lambda};
    if (input == o.drive) {
        o.drive.clear();
        o.driveLags = {{}};
    } else {
        o.inputs.erase(std::remove(o.inputs.begin(), o.inputs.end(), input), o.inputs.end());
        if (!chosen.driveLags_s.empty())
            o.driveLags = {chosen.driveLags_s};
        else
            o.driveLags = {{}};
    }
    if (o.kind == "lagridge")
        o.ridgeLags = {chosen.temperatureLags_s};
    if (o.kind == "dynamic") {
        o.temperatureLags = {chosen.temperatureLags_s.empty() ? std::vector<double>{0.0} : chosen.temperatureLags_s};
        o.components = {std::max(1, std::min<int>(chosen.components, static_cast<int>(o.inputs.size())))};
    }
    return o;
}

std::vector<DataDrivenModel> ReducedModelFitter::fit(const std::vector<LinearLagRun> &runs, const LinearLagOptions &options,
                                                     const CvCandidate &chosen)
{
    if (options.kind != "mlr" && options.kind != "ridge" && options.kind != "lagridge" && options.kind != "dynamic")
        throw std::invalid_argument("reduced models: no reduced models for kind " + options.kind);
    std::vector<std::string> dropped = options.inputs;
    // The drive is an input of the fitted model only when the chosen structure reads it (a
    // dynamic model may choose temperature lags alone); a reduced model "without" a channel
    // the model does not read would be refused by the reader.
    if (options.kind == "dynamic" && !options.drive.empty() && !chosen.driveLags_s.empty())
        dropped.push_back(options.drive);
    std::vector<DataDrivenModel> out;
    for (const std::string &input : dropped) {
        const LinearLagOptions o = without(options, chosen, input);
        if (o.inputs.empty()) // nothing left to read: the loop holds instead
            continue;
        LinearLagFit f = LinearLagFitter::fit(runs, o);
        f.model.without = input;
        out.push_back(std::move(f.model));
    }
    return out;
}

} // namespace driftlab
