#!/usr/bin/python3
"""Would a gradient-boosted-tree family win DriftLab's leave-runs-out sweep on FL_THERMAL?
(issue 32 item 4: "You may add a nonlinear family from Debian if it wins in the sweep; state
in docs why it is or is not the default"). An experiment outside DriftLab, so that a new C++
dependency (libxgboost-dev) is only taken on if the family wins:

  - the FL_THERMAL cycles as runs, cut as scripts/fl-thermal-cycles.py cuts them (a cycle
    starts where the spindle switches on from rest; 6 cycles);
  - leave one cycle out (6 outer folds); every choice by leave-one-cycle-out CV over the
    training cycles only (nested, as `fit --model auto` does with 3+ training sessions);
  - inputs: the 16 temperatures as rises from each cycle's start through a bank of first-order
    lags (DriftLab's lagridge inputs); targets ch1..ch5 (µm);
  - families: the training mean (equals DriftLab's on these folds); ridge on the lag bank
    (bank and lambda by inner CV; rises only, so it does NOT reproduce DriftLab's lagridge,
    which also offers absolute temperatures: compare the trees with DriftLab's numbers in
    docs/datadriven.md); XGBoost trees on the widest bank (depth by inner CV), also with the
    spindle speed as an input.
Pooled held-out RMSE per channel. Needs Debian's python3-numpy and python3-xgboost (run with
/usr/bin/python3); exits 0 with a note when they are missing. Not run by CI.

    /usr/bin/python3 scripts/nonlinear-family-check.py ../shared/extdata/fl_thermal/fl_thermal_data.csv
"""
import csv
import math
import sys

try:
    import numpy as np
    import xgboost as xgb
except ImportError as e:  # not a DriftLab dependency: the experiment is optional
    print(f"nonlinear-family-check: {e}; install python3-numpy python3-xgboost (Debian) to run it", file=sys.stderr)
    sys.exit(0)

BANKS = [(0,), (0, 900), (0, 1800), (0, 3600), (0, 900, 3600), (0, 1800, 7200)]
LAMBDAS = [1e-4, 1e-3, 1e-2, 3e-2, 0.1, 0.3, 1.0, 3.0]
TREES = [(2, 200), (4, 200)]  # (max_depth, rounds) at eta 0.1
WIDE = (0, 900, 3600, 14400)


def read(path):
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f) if r]
    header = rows[0]
    data = np.array([[float(x) for x in r] for r in rows[1:]])
    rpm = header.index("spindle_rpm")
    starts = [0]
    for k in range(1, len(data)):
        if data[k - 1, rpm] == 0.0 and data[k, rpm] > 0.0 and k > 60:
            starts.append(k)
    starts = sorted(set(starts))
    if len(starts) > 1 and starts[1] < 60:
        starts.pop(1)
    temps = [i for i, h in enumerate(header) if h.endswith("_C")]
    targets = [i for i, h in enumerate(header) if h.endswith("_um")]
    cycles = []
    for n, b in enumerate(starts):
        e = starts[n + 1] if n + 1 < len(starts) else len(data)
        block = data[b:e]
        cycles.append({"t": block[:, 0] - block[0, 0], "T": block[:, temps], "rpm": block[:, rpm], "y": block[:, targets]})
    return cycles, [header[i][:-3] for i in targets]


def lagged(t, x, tau):
    """First-order lag of the columns of x (rises), starting at the first sample."""
    if tau == 0:
        return x.copy()
    out = np.empty_like(x)
    out[0] = x[0]
    for k in range(1, len(t)):
        a = 1.0 - math.exp(-(t[k] - t[k - 1]) / tau)
        out[k] = out[k - 1] + a * (x[k] - out[k - 1])
    return out


def features(c, bank, with_rpm=False):
    rises = c["T"] - c["T"][0]
    cols = [lagged(c["t"], rises, tau) for tau in bank]
    if with_rpm:
        cols.append(c["rpm"][:, None] / 5000.0)
    return np.hstack(cols)


def ridge_fit(X, y, lam):
    mu, sd = X.mean(0), X.std(0)
    sd[sd < 1e-12] = 1.0
    Z = (X - mu) / sd
    ym = y.mean()
    n = len(y)
    beta = np.linalg.solve(Z.T @ Z + lam * n * np.eye(Z.shape[1]), Z.T @ (y - ym))
    return lambda Xn: ((Xn - mu) / sd) @ beta + ym


def tree_fit(X, y, depth, rounds):
    params = {"max_depth": depth, "eta": 0.1, "subsample": 0.8, "colsample_bytree": 0.8, "min_child_weight": 5,
              "tree_method": "hist", "nthread": 1, "seed": 1, "objective": "reg:squarederror"}
    booster = xgb.train(params, xgb.DMatrix(X, label=y), num_boost_round=rounds)
    return lambda Xn: booster.predict(xgb.DMatrix(Xn))


def pooled(errors):
    e = np.concatenate(errors)
    return float(np.sqrt(np.mean(e * e)))


def loro(train, fit, make_x, ch):
    """Leave-one-cycle-out pooled RMSE over `train` (indices into the feature cache)."""
    errs = []
    for k in train:
        rest = [j for j in train if j != k]
        X = np.vstack([make_x(j) for j in rest])
        y = np.concatenate([CYCLES[j]["y"][:, ch] for j in rest])
        errs.append(fit(X, y)(make_x(k)) - CYCLES[k]["y"][:, ch])
    return pooled(errs)


def main():
    global CYCLES
    if len(sys.argv) != 2:
        sys.exit("usage: nonlinear-family-check.py FL_THERMAL.csv")
    CYCLES, names = read(sys.argv[1])
    cache = {}

    def fx(j, bank, with_rpm=False):
        key = (j, bank, with_rpm)
        if key not in cache:
            cache[key] = features(CYCLES[j], bank, with_rpm)
        return cache[key]

    print(f"{len(CYCLES)} cycles, {sum(len(c['t']) for c in CYCLES)} samples", file=sys.stderr)
    print("| channel | mean | ridge on lags (this script) | trees on lags | trees on lags + speed | trees' inner-CV choice |")
    print("|---|---|---|---|---|---|")
    for ch, name in enumerate(names):
        out = {"mean": [], "ridge": [], "trees": [], "trees+rpm": []}
        chosen = []
        for k in range(len(CYCLES)):
            train = [j for j in range(len(CYCLES)) if j != k]
            y = np.concatenate([CYCLES[j]["y"][:, ch] for j in train])
            out["mean"].append(np.full(len(CYCLES[k]["t"]), y.mean()) - CYCLES[k]["y"][:, ch])
            # ridge: bank and lambda by inner leave-one-cycle-out CV
            best = min(((loro(train, lambda X, yy, l=lam: ridge_fit(X, yy, l), lambda j, b=bank: fx(j, b), ch), bank, lam)
                        for bank in BANKS for lam in LAMBDAS), key=lambda r: r[0])
            X = np.vstack([fx(j, best[1]) for j in train])
            out["ridge"].append(ridge_fit(X, y, best[2])(fx(k, best[1])) - CYCLES[k]["y"][:, ch])
            for key, with_rpm in (("trees", False), ("trees+rpm", True)):
                tb = min(((loro(train, lambda X, yy, d=d, r=r: tree_fit(X, yy, d, r), lambda j, w=with_rpm: fx(j, WIDE, w), ch), d, r)
                          for d, r in TREES), key=lambda q: q[0])
                X = np.vstack([fx(j, WIDE, with_rpm) for j in train])
                out[key].append(tree_fit(X, y, tb[1], tb[2])(fx(k, WIDE, with_rpm)) - CYCLES[k]["y"][:, ch])
                if key == "trees":
                    chosen.append(f"d{tb[1]}/{tb[2]}")
            print(f"  {name} fold {k + 1}: ridge bank {best[1]} lambda {best[2]:g}", file=sys.stderr)
        print(f"| {name} | {pooled(out['mean']):.3f} | {pooled(out['ridge']):.3f} | {pooled(out['trees']):.3f} | "
              f"{pooled(out['trees+rpm']):.3f} | {' '.join(chosen)} |", flush=True)


if __name__ == "__main__":
    main()
