#include "CCodeExporter.h"

#include "CompensationLaw.h"
#include "DataDrivenPredictor.h"
#include "FdmScrewModel.h"

#include <cctype>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace driftlab {

namespace {

std::string num(double v)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    std::string s = buf;
    if (s.find_first_of(".eEn") == std::string::npos)
        s += ".0";
    return s;
}

std::string array(const std::vector<double> &v)
{
    std::string s = "{";
    for (std::size_t i = 0; i < v.size(); ++i)
        s += (i ? ", " : "") + num(v[i]);
    return s + "}";
}

std::string intArray(const std::vector<int> &v)
{
    std::string s = "{";
    for (std::size_t i = 0; i < v.size(); ++i)
        s += (i ? ", " : "") + std::to_string(v[i]);
    return s + "}";
}

std::string upper(std::string s)
{
    for (char &c : s)
        c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return s;
}

bool identifier(const std::string &s)
{
    if (s.empty() || std::isdigit(static_cast<unsigned char>(s[0])))
        return false;
    for (char c : s)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_'))
            return false;
    return true;
}

} // namespace

std::string CCodeExporter::description() const
{
    return "Portable C99 (one .h, one .c; init, step, error_at; fixed arrays, no allocation)";
}

std::string CCodeExporter::reference() const
{
    return "ISO/IEC 9899:1999 (C99); seed 000 (FDM model embedded in an HNC-848 controller); docs/models.md, "
           "docs/datadriven.md (evaluation rules)";
}

ExportResult CCodeExporter::exportModel(const ExportableModel &model, const ExportOptions &o) const
{
    const std::string &p = o.baseName;
    if (!identifier(p))
        throw ExportRefused("c: the base name '" + p + "' is not a C identifier (letters, digits, _)");
    const std::string guard = upper(p) + "_H";
    std::ostringstream h;
    h << "/* " << p << ".h: DriftLab thermal-error model " << model.kind() << " from " << model.source << ".\n"
      << " * Generated C99; parameters baked in, fixed arrays, no allocation. See docs/export.md. */\n"
      << "#ifndef " << guard << "\n#define " << guard << "\n\n";
    std::string source;
    if (model.physics) {
        const FdmScrewModel check(model.geometry, model.parameters, model.grid); // validates
        h << "#define " << upper(p) << "_CELLS " << check.cellCount() << "\n"
          << "#define " << upper(p) << "_INPUTS 1 /* temperatures[0] = ambient, degC */\n\n"
          << "typedef struct {\n    double T[" << check.cellCount() << "];\n    double next[" << check.cellCount()
          << "];\n    double ambient, ambient0, t0;\n    long steps;\n    double checked_feed, coeff_feed;\n"
          << "    double conv, face, bearing_src, nut_src;\n    int started;\n} " << p << "_state;\n\n";
        source = physicsSource(model, p);
    } else {
        const DataDrivenModel &m = model.dataDriven;
        DataDrivenPredictor check(m); // validates
        std::size_t states = 0;
        for (const Evaluated &e : evaluatedModels(m))
            for (const ModelTerm &t : e.model->terms)
                states += t.lags_s.size();
        h << "#define " << upper(p) << "_INPUTS " << m.inputs.size() << " /* temperatures[i], MODEL.json inputs:";
        for (const ModelChannel &c : m.inputs)
            h << ' ' << c.id;
        const std::size_t nin = std::max<std::size_t>(m.inputs.size(), 1);
        h << " */\n\ntypedef struct {\n    double x[" << std::max<std::size_t>(states, 1) << "];\n    double held["
          << nin << "];\n    double ref[" << nin << "], ref_sum[" << nin
          << "]; /* temperature reference captured at start-up */\n    double ref_count, elapsed;\n"
          << "    double seen[" << nin << "]; /* time of each input's last finite value */\n"
          << "    double stale_s; /* an input silent for longer is failed; init sets " << num(std::max(30.0, 5.0 * m.samplePeriod_s))
          << " s, the live loop's default */\n"
          << "    double y, safe, last_time;\n    int active, started;\n} " << p << "_state;\n\n";
        h << "/* The model in use after the last step: -1 the full model, i >= 0 the reduced model without\n"
          << " * input i (one input failed: silent longer than stale_s or outside its training range by more\n"
          << " * than the margin), -2 holding the last output of a model whose inputs were sound. Reduced models:";
        const std::vector<Evaluated> models = evaluatedModels(m);
        for (std::size_t k = 1; k < models.size(); ++k)
            h << " without " << models[k].model->without << " (input " << models[k].without << ")" << (k + 1 < models.size() ? "," : "");
        if (models.size() == 1)
            h << " none";
        h << ". */\nint " << p << "_active(const " << p << "_state *s);\n";
        source = dataDrivenSource(model, p);
    }
    h << "void " << p << "_init(" << p << "_state *s);\n"
      << "/* Advances the model to time_s (s). Returns 0, -1 when time goes backwards, -2 when the explicit\n"
      << " * step is unstable at this feed. */\n"
      << "int " << p << "_step(" << p << "_state *s, double time_s, double position_mm, double feed_mm_min,\n"
      << "        const double *temperatures);\n"
      << "/* Thermal error E (um, actual minus nominal) at an axis position (mm); compensate with -E. */\n"
      << "double " << p << "_error_at(const " << p << "_state *s, double position_mm);\n\n#endif\n";
    ExportResult r;
    r.files.push_back({p + ".c", source});
    r.files.push_back({p + ".h", h.str()});
    r.notes.push_back(model.physics ? "explicit seed-000 scheme, dx " + CompensationLaw::number(model.grid.dx_m, 6) +
                                          " m, dt " + CompensationLaw::number(model.grid.dt_s, 6) +
                                          " s: identical to FdmScrewModel; step() returns -2 at a feed where dt is unstable"
                                    : "identical to DataDrivenPredictor (same recursion, constants to 17 digits)");
    if (!model.physics)
        r.notes.push_back(std::to_string(evaluatedModels(model.dataDriven).size() - 1) +
                          " reduced model(s) and the live loop's switching: a failed input (silent longer than stale_s, "
                          "or outside its training range by more than the margin) switches to the model without it, two "
                          "hold the last sound output; " + p + "_active() says which");
    return r;
}

std::string CCodeExporter::physicsSource(const ExportableModel &model, const std::string &p)
{
    const ScrewGeometry &g = model.geometry;
    const FdmParameters &k = model.parameters;
    const FdmSettings &st = model.grid;
    const FdmScrewModel ref(g, k, st);
    const int n = ref.cellCount();
    int first = 0, last = 0, bearing = 0;
    ref.heatedCells(0.0, first, last, bearing);
    const double rhoC = g.density_kg_m3 * g.specificHeat_J_kgK;
    const double area = 3.14159265358979323846 * g.diameter_m * g.diameter_m / 4.0;
    std::ostringstream c;
    c << "/* " << p << ".c: seed-000 explicit finite-difference ball-screw model (eq. 10-16), generated by DriftLab. */\n"
      << "#include \"" << p << ".h\"\n#include <math.h>\n\n"
      << "#define N " << n << "\n"
      << "static const double DX = " << num(st.dx_m) << ", DT = " << num(st.dt_s) << ";\n"
      << "static const double K1 = " << num(k.k1) << ", K2 = " << num(k.k2) << ", K3 = " << num(k.k3)
      << ", K4 = " << num(k.k4) << ";\n"
      << "static const double LAMBDA = " << num(k.conductivity_W_mK) << ", PF = " << num(k.fixedEndPosition_mm) << ";\n"
      << "static const double D = " << num(g.diameter_m) << ", NUT_LENGTH = " << num(g.nutLength_m)
      << ", BEARING_LENGTH = " << num(g.fixedBearingLength_m) << ", ALPHA = " << num(g.expansion_per_K) << ";\n"
      << "static const double RHO_C = " << num(rhoC) << ";\n"
      << "static const double R = " << num(k.conductivity_W_mK * st.dt_s / (rhoC * st.dx_m * st.dx_m)) << ";\n"
      << "static const double SRC_SCALE = " << num(st.dt_s / (rhoC * area)) << ";\n"
      << "static const int BEARING_CELLS = " << bearing << ";\n\n"
      << R"C(static double max_stable_dt(double v)
{
    double h = K1 * v + K2;
    double interior, free_end;
    if (h < 0.0)
        h = 0.0;
    interior = 2.0 * LAMBDA / (DX * DX) + 4.0 * h / D;
    free_end = LAMBDA / (DX * DX) + 4.0 * h / D * (1.0 + D / (4.0 * DX));
    return RHO_C / (interior > free_end ? interior : free_end);
}

static int cell_floor(double x)
{
    double c = x < -2.0 ? -2.0 : (x > N + 2.0 ? N + 2.0 : x);
    int k = (int)c;
    return k > c ? k - 1 : k;
}

static void coefficients(PREFIX_state *s, double v)
{
    const double h = K1 * v + K2;
    const double qb = K3 * v, qn = K4 * v;
    s->conv = 4.0 * h * DT / (RHO_C * D);
    s->face = s->conv * D / (4.0 * DX);
    s->bearing_src = BEARING_LENGTH > 0 ? SRC_SCALE * qb / BEARING_LENGTH : 0.0;
    s->nut_src = NUT_LENGTH > 0 ? SRC_SCALE * qn / NUT_LENGTH : 0.0;
    s->coeff_feed = v;
}

void PREFIX_init(PREFIX_state *s)
{
    int i;
    for (i = 0; i < N; ++i)
        s->T[i] = s->next[i] = 20.0;
    s->ambient = s->ambient0 = 20.0;
    s->t0 = 0.0;
    s->steps = 0;
    s->checked_feed = s->coeff_feed = -1.0;
    s->conv = s->face = s->bearing_src = s->nut_src = 0.0;
    s->started = 0;
}

/* One explicit step of eq. (10) with the ambient of the previous step (as FdmScrewModel). */
static int advance(PREFIX_state *s, double position_mm, double feed_mm_min, double ambient_C)
{
    const double v = fabs(feed_mm_min);
    const double nut_centre = fabs(position_mm - PF) / 1000.0;
    const double half_nut = NUT_LENGTH / 2.0;
    const double ta = s->ambient;
    int first_nut, last_nut, i;
    if (v != s->checked_feed) {
        if (DT > max_stable_dt(v))
            return -2;
        s->checked_feed = v;
    }
    if (v != s->coeff_feed)
        coefficients(s, v);
    first_nut = cell_floor((nut_centre - half_nut) / DX + 1e-9) + 1;
    if (first_nut < 1)
        first_nut = 1;
    first_nut -= 1;
    last_nut = cell_floor((nut_centre + half_nut) / DX + 1e-9);
    if (last_nut > N)
        last_nut = N;
    last_nut -= 1;
    if (last_nut < first_nut)
        first_nut = last_nut = N + 1;
    for (i = 0; i < N; ++i) {
        const int under_bearing = i < BEARING_CELLS;
        const int under_nut = i >= first_nut && i < last_nut + 1;
        const double c = (under_bearing || under_nut) ? 0.0 : s->conv;
        const double src = (under_bearing ? s->bearing_src : 0.0) + (under_nut ? s->nut_src : 0.0);
        const double *T = s->T;
        if (i == 0) {
            s->next[0] = T[0] + R * (T[1] - T[0]) + src - c * (T[0] - ta);
        } else if (i == N - 1) {
            const double c_end = c + s->face;
            s->next[i] = T[i] + R * (T[i - 1] - T[i]) + src - c_end * (T[i] - ta);
        } else {
            const double a = 1.0 - 2.0 * R - c, b = c * ta + src;
            s->next[i] = a * T[i] + R * (T[i - 1] + T[i + 1]) + b;
        }
    }
    for (i = 0; i < N; ++i)
        s->T[i] = s->next[i];
    s->ambient = ambient_C;
    s->steps += 1;
    return 0;
}

int PREFIX_step(PREFIX_state *s, double time_s, double position_mm, double feed_mm_min, const double *temperatures)
{
    const double ambient = temperatures[0];
    int i, rc;
    if (!s->started) {
        for (i = 0; i < N; ++i)
            s->T[i] = ambient;
        s->ambient = s->ambient0 = ambient;
        s->t0 = time_s;
        s->steps = 0;
        s->started = 1;
        return 0;
    }
    if (time_s < s->t0 + DT * (double)s->steps - 1e-9)
        return -1;
    while (s->t0 + DT * (double)(s->steps + 1) <= time_s + 1e-9) {
        rc = advance(s, position_mm, feed_mm_min, ambient);
        if (rc != 0)
            return rc;
    }
    return 0;
}

double PREFIX_error_at(const PREFIX_state *s, double position_mm)
{
    const double d_mm = position_mm - PF;
    double x = fabs(d_mm) / 1000.0, sum = 0.0, e, te;
    int m, i;
    if (x > DX * N)
        x = DX * N;
    m = (int)floor(x / DX);
    if (m > N)
        m = N;
    for (i = 0; i < m; ++i)
        sum += s->T[i] - s->ambient0;
    e = sum * DX;
    if (m < N)
        e += (x - m * DX) * (s->T[m] - s->ambient0);
    te = ALPHA * e * 1e6;
    return d_mm >= 0 ? te : -te;
}
)C";
    std::string out = c.str();
    for (std::size_t pos; (pos = out.find("PREFIX")) != std::string::npos;)
        out.replace(pos, 6, p);
    return out;
}

std::vector<CCodeExporter::Evaluated> CCodeExporter::evaluatedModels(const DataDrivenModel &m)
{
    std::vector<Evaluated> models{{&m, -1}};
    if (!m.linearLag())
        return models;
    for (const DataDrivenModel &r : m.reduced) {
        const int without = m.inputIndex(r.without);
        bool mapped = without >= 0 && r.linearLag();
        for (const ModelChannel &c : r.inputs)
            mapped = mapped && m.inputIndex(c.id) >= 0;
        if (!mapped)
            continue; // reads a channel the full model does not (SessionOffsetSource skips it too)
        DataDrivenPredictor check(r); // validates
        if (r.usesRises() && m.usesRises() && !(r.reference == m.reference))
            throw ExportRefused("c: the reduced model without " + r.without + " reads temperature rises from another reference (" +
                                r.reference.label() + ") than the model (" + m.reference.label() + ")");
        if (r.usesRises() && !m.usesRises())
            throw ExportRefused("c: the reduced model without " + r.without +
                                " reads temperature rises, the model absolute temperatures");
        models.push_back({&r, without});
    }
    return models;
}

std::string CCodeExporter::dataDrivenSource(const ExportableModel &model, const std::string &p)
{
    const DataDrivenModel &m = model.dataDriven;
    const std::vector<Evaluated> models = evaluatedModels(m);
    // The states of every model in a row: the full model's first, then each reduced model's,
    // with the reduced models' inputs mapped onto the full model's.
    std::vector<int> stateInput, statePower, stateRise, stateModel, reducedWithout, inputRise, inputRange;
    std::vector<double> stateOffset, stateScale, stateLag, stateCoef, intercepts, inputMin, inputMax, inputMargin;
    for (std::size_t k = 0; k < models.size(); ++k) {
        const DataDrivenModel &r = *models[k].model;
        intercepts.push_back(r.intercept);
        if (k > 0)
            reducedWithout.push_back(models[k].without);
        for (const ModelTerm &t : r.terms)
            for (std::size_t l = 0; l < t.lags_s.size(); ++l) {
                stateInput.push_back(k == 0 ? t.input : m.inputIndex(r.inputs[static_cast<std::size_t>(t.input)].id));
                statePower.push_back(t.power);
                stateRise.push_back(t.rise ? 1 : 0);
                stateModel.push_back(static_cast<int>(k));
                stateOffset.push_back(t.offset);
                stateScale.push_back(t.scale);
                stateLag.push_back(t.lags_s[l]);
                stateCoef.push_back(t.coefficients[l]);
            }
    }
    bool rises = false;
    for (const Evaluated &e : models)
        rises = rises || e.model->usesRises();
    for (std::size_t i = 0; i < m.inputs.size(); ++i) {
        const ModelChannel &c = m.inputs[i];
        const bool known = std::isfinite(c.trainingMin) && std::isfinite(c.trainingMax);
        inputRise.push_back(m.inputIsRise(static_cast<int>(i)) ? 1 : 0);
        inputRange.push_back(known ? 1 : 0);
        inputMin.push_back(known ? c.trainingMin : 0.0);
        inputMax.push_back(known ? c.trainingMax : 0.0);
        inputMargin.push_back(known ? DataDrivenModel::extrapolationMargin(c.trainingMin, c.trainingMax) : 0.0);
    }
    const int kind = m.linearLag() ? 0 : (m.kind == "exp" ? 1 : 2);
    if (stateInput.empty()) { // C forbids empty arrays
        stateInput = statePower = stateRise = stateModel = {0};
        stateOffset = stateScale = stateLag = stateCoef = {0.0};
    }
    if (reducedWithout.empty())
        reducedWithout = {-1};
    if (inputRise.empty()) {
        inputRise = inputRange = {0};
        inputMin = inputMax = inputMargin = {0.0};
    }
    const ExponentialLaw &e = m.exponential;
    const SyntheticLaw &s = m.synthetic;
    std::vector<int> temps = s.temperatures;
    if (temps.empty())
        temps = {0};
    std::ostringstream c;
    c << "/* " << p << ".c: DriftLab data-driven thermal-error model '" << m.kind
      << "' (docs/datadriven.md evaluation), generated. */\n"
      << "#include \"" << p << ".h\"\n#include <math.h>\n\n"
      << "#define KIND " << kind << " /* 0 linear-lag, 1 exp, 2 synthetic */\n"
      << "#define NIN " << m.inputs.size() << "\n#define NSTATE " << (m.linearLag() ? stateLag.size() : 0) << "\n"
      << "#define NTEMP " << s.temperatures.size() << "\n"
      << "#define NREDUCED " << models.size() - 1 << " /* reduced models, each without one input */\n"
      << "static const int STATE_INPUT[] = " << intArray(stateInput) << ";\n"
      << "static const int STATE_POWER[] = " << intArray(statePower) << ";\n"
      << "static const int STATE_RISE[] = " << intArray(stateRise) << "; /* 1: input minus its reference */\n"
      << "static const int STATE_MODEL[] = " << intArray(stateModel) << "; /* 0 the model, r the reduced model r */\n"
      << "static const int REDUCED_WITHOUT[] = " << intArray(reducedWithout) << "; /* the input each does without */\n"
      << "#define REF_START " << (rises && m.reference.kind == "start" ? 1 : 0) << "\n"
      << "static const double REF_WINDOW = " << num(m.reference.window_s) << ";\n"
      << "static const double STATE_OFFSET[] = " << array(stateOffset) << ";\n"
      << "static const double STATE_SCALE[] = " << array(stateScale) << ";\n"
      << "static const double STATE_LAG[] = " << array(stateLag) << ";\n"
      << "static const double STATE_COEF[] = " << array(stateCoef) << ";\n"
      << "static const double INTERCEPT[] = " << array(intercepts) << ";\n"
      << "/* Inputs: training range as the model reads it (a rise where it takes rises) and its margin. */\n"
      << "static const int INPUT_RISE[] = " << intArray(inputRise) << ", INPUT_RANGE[] = " << intArray(inputRange) << ";\n"
      << "static const double INPUT_MIN[] = " << array(inputMin) << ";\n"
      << "static const double INPUT_MAX[] = " << array(inputMax) << ";\n"
      << "static const double INPUT_MARGIN[] = " << array(inputMargin) << ";\n"
      << "static const double STALE_S = " << num(std::max(30.0, 5.0 * m.samplePeriod_s)) << ";\n"
      << "static const int EXP_DRIVE = " << e.drive << ";\n"
      << "static const double EXP_ON = " << num(e.onThreshold) << ", EXP_REF = " << num(e.referenceDrive)
      << ", EXP_SS = " << num(e.steadyState) << ", EXP_P = " << num(e.exponent) << ";\n"
      << "static const double EXP_TAU_WARM = " << num(e.tauWarm_s) << ", EXP_TAU_COOL = " << num(e.tauCool_s)
      << ", EXP_BASELINE = " << num(e.baseline) << ";\n"
      << "static const int SYN_TEMP[] = " << intArray(temps) << ";\n"
      << "static const double SYN_A = " << num(s.a) << ", SYN_B = " << num(s.b_perK) << ", SYN_C = " << num(s.c)
      << ", SYN_T0 = " << num(s.t0_C) << ", SYN_P0 = " << num(s.p0_mm) << ", SYN_PREF = " << num(s.pRef_mm) << ";\n\n"
      << R"C(static double feature(const PREFIX_state *s, int k)
{
    const int in = STATE_INPUT[k];
    const double u = s->held[in] - (STATE_RISE[k] ? s->ref[in] : 0.0);
    const double z = (u - STATE_OFFSET[k]) / STATE_SCALE[k];
    return STATE_POWER[k] == 2 ? z * z : z;
}

static double lag_step(double x, double u, double dt, double tau)
{
    if (tau <= 0)
        return u;
    return x + (1.0 - exp(-dt / tau)) * (u - x);
}

static double synthetic_g(const PREFIX_state *s)
{
    double sum = 0.0;
    int i;
    for (i = 0; i < NTEMP; ++i)
        sum += s->held[SYN_TEMP[i]];
    return SYN_C + SYN_A * (exp(SYN_B * (sum / (double)NTEMP - SYN_T0)) - 1.0);
}

/* Input i is failed at time t when its last finite value is older than the stale limit or, as
 * the model reads it, outside its training range by more than the margin (SessionOffsetSource). */
static int failed(const PREFIX_state *s, int i, double t)
{
    double v;
    if (t - s->seen[i] > s->stale_s)
        return 1;
    if (!INPUT_RANGE[i])
        return 0;
    v = s->held[i] - (INPUT_RISE[i] ? s->ref[i] : 0.0);
    return v < INPUT_MIN[i] - INPUT_MARGIN[i] || v > INPUT_MAX[i] + INPUT_MARGIN[i];
}

/* One input failed: the reduced model without it, if any; two or more, or none: hold the last
 * output of a model whose inputs were sound. */
static double choose(PREFIX_state *s, const double *y, double t)
{
    int i, count = 0, which = -1, next = -1;
    for (i = 0; i < NIN; ++i)
        if (failed(s, i, t)) {
            if (count++ == 0)
                which = i;
        }
    if (count == 1) {
        next = -2;
        for (i = 0; i < NREDUCED; ++i)
            if (REDUCED_WITHOUT[i] == which)
                next = i;
    } else if (count > 1) {
        next = -2;
    }
    s->active = next < 0 ? next : REDUCED_WITHOUT[next];
    if (next == -2)
        return s->safe;
    s->safe = y[next + 1];
    return s->safe;
}

void PREFIX_init(PREFIX_state *s)
{
    int i;
    for (i = 0; i < (int)(sizeof s->x / sizeof s->x[0]); ++i)
        s->x[i] = 0.0;
    for (i = 0; i < (int)(sizeof s->held / sizeof s->held[0]); ++i) {
        s->held[i] = s->ref[i] = s->ref_sum[i] = 0.0;
        s->seen[i] = -1e300;
    }
    s->ref_count = s->elapsed = 0.0;
    s->y = s->safe = 0.0;
    s->last_time = 0.0;
    s->stale_s = STALE_S;
    s->active = -1;
    s->started = 0;
}

int PREFIX_active(const PREFIX_state *s)
{
    return s->active;
}

int PREFIX_step(PREFIX_state *s, double time_s, double position_mm, double feed_mm_min, const double *temperatures)
{
    double dt, y[NREDUCED + 1];
    int i;
    (void)position_mm;
    (void)feed_mm_min;
    if (s->started && time_s < s->last_time)
        return -1;
    for (i = 0; i < NIN; ++i)
        if (isfinite(temperatures[i])) {
            s->held[i] = temperatures[i];
            s->seen[i] = time_s;
        }
    if (!s->started) {
        for (i = 0; i < NIN; ++i)
            s->ref[i] = s->ref_sum[i] = REF_START ? s->held[i] : 0.0;
        s->ref_count = 1.0;
        s->elapsed = 0.0;
        for (i = 0; i < NSTATE; ++i)
            s->x[i] = feature(s, i);
        s->last_time = time_s;
        s->started = 1;
    }
    dt = time_s - s->last_time;
    s->last_time = time_s;
    if (KIND == 0) {
        s->elapsed += dt;
        if (REF_START && REF_WINDOW > 0 && dt > 0 && s->elapsed <= REF_WINDOW) {
            s->ref_count += 1.0;
            for (i = 0; i < NIN; ++i) {
                s->ref_sum[i] += s->held[i];
                s->ref[i] = s->ref_sum[i] / s->ref_count;
            }
        }
        for (i = 0; i <= NREDUCED; ++i)
            y[i] = INTERCEPT[i];
        for (i = 0; i < NSTATE; ++i) {
            s->x[i] = lag_step(s->x[i], feature(s, i), dt, STATE_LAG[i]);
            y[STATE_MODEL[i]] += STATE_COEF[i] * s->x[i];
        }
    } else if (KIND == 1) {
        const double v = fabs(s->held[EXP_DRIVE]);
        const int on = v > EXP_ON;
        const double goal = on ? EXP_SS * pow(v / EXP_REF, EXP_P) : 0.0;
        s->x[0] = lag_step(s->x[0], goal, dt, on ? EXP_TAU_WARM : EXP_TAU_COOL);
        y[0] = EXP_BASELINE + s->x[0];
    } else {
        y[0] = synthetic_g(s) * (SYN_PREF - SYN_P0) / (SYN_PREF - SYN_P0);
    }
    s->y = choose(s, y, time_s);
    return 0;
}

double PREFIX_error_at(const PREFIX_state *s, double position_mm)
{
    if (KIND == 2 && s->active == -1)
        return synthetic_g(s) * (position_mm - SYN_P0) / (SYN_PREF - SYN_P0);
    (void)position_mm;
    return s->y;
}
)C";
    std::string out = c.str();
    for (std::size_t pos; (pos = out.find("PREFIX")) != std::string::npos;)
        out.replace(pos, 6, p);
    return out;
}

} // namespace driftlab
