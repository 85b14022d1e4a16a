#!/usr/bin/env python3
"""thirdsim.py - a third, independent ball-screw simulator for blind diagnosis tests (issue 36).

Written for issue 36 from the physics reference and the recording-bundle spec only, on purpose
unlike DriftLab's rig (acquisition/SimulatedRig) and unlike scripts/othersim.py:

* discretisation: a vertex-centred finite-volume / lumped-mass linear-element grid that is
  NON-uniform (geometric refinement towards the fixed end, 34 nodes), integrated IMPLICITLY
  with a theta scheme (theta = 0.6, 6 s heat step, tridiagonal solve); the expansion integral
  is the exact integral of the piecewise-linear temperature (othersim: explicit, uniform
  cell-centred, piecewise-constant);
* machine: a 1.25 m x 32 mm screw, 110 mm nut, travel 0..850 mm, fixed end at -70 mm on the
  drawing (truth 1.5-5 mm off); convection h = h0 + h1 (v / 1 m/min)^0.8;
* housings: the fixed-end bearing housing is a body of two nodes (flange + block) that takes 25 %
  of the bearing heat and exchanges heat with the screw both ways; the nut housing and the motor
  are first-order lags; a slow bed casting follows the hall and the hydraulic unit;
* sensors: PT100s at 1/3 Hz with 0.04 K noise, 0.01 K resolution and 0.5 % dropouts; an
  eddy-current probe at 1 Hz (0.15 um noise, a -3 um zero offset); position at 2 Hz and feed at
  1 Hz; an interferometer with its laser head at -40 mm (0.2 um noise, a residual air-compensation
  error of 0.1 um/m/K) visiting 9 targets with 4 s dwell, runs every 20-30 min, alternately
  outwards and inwards; the hall drifts more than othersim's (0.3-0.8 K swings, up to 0.4 K/h);
* programmes: `ladder` (feed steps 2000..8000 mm/min, then a cool-down), `cycles` (10-20 min
  machining bursts with short pauses) or `random`, picked from the seed.

Effects (the truth), any combination, comma-separated with --effects:
  within the grammar of issue 36 item 2 (named by the library code the diagnosis should give):
    motor_heat_fixed_end   G (T_motor - T_air) into the fixed-end bearing section (coupling)
    free_end_bearing_heat  k_F v^1.0 at the free-end bearing section
    nonlinear_feed_heat    extra nut heat a (v / 1 m/min)^2
    heat_path_lag          the fixed-end bearing heat arrives through a 20-minute lag
    holding_heat           P_hold into the fixed end while the axis stands still
    structure_offset       c (T_bed - T_bed(0)) added to every target
    structure_linear       (c1 X + c0) (T_bed - T_bed(0))
    screw_coolant          g (T_c - T) per metre of screw (a cored screw)
  outside the grammar (the right answer is `unexplained`):
    midspan_radiant        a lamp over the middle third of the screw, on a clock schedule
    bed_bending            error c X^2 (T_bed - T_bed(0)): the bed bows, quadratic in position
    preload_spring         the free-end support is a spring: the screw's expansion is partly
                           held back, error reduced by kappa (X - P_f) / L x elongation
  faults of the measurement chain (the right answer names the sensor and its law):
    interferometer_air     the interferometer reading follows the air temperature at 1 um/m/K
                           over the beam length (air compensation off)
    probe_mount_drift      the probe's holder moves with the bed: +3 um/K x (T_bed - T_bed(0))
    ambient_pt100_step     the ambient PT100 reads +0.6 K from a random moment on (loose contact)

The truth is written to --truth FILE (JSON), never into the bundle. Standard library only.

    thirdsim.py --effects none --seed 1 --hours 4 --out train.bundle --truth truth.json
    thirdsim.py --selftest
"""

import argparse
import json
import math
import os
import random
import sys

GRAMMAR = ("motor_heat_fixed_end", "free_end_bearing_heat", "nonlinear_feed_heat", "heat_path_lag",
           "holding_heat", "structure_offset", "structure_linear", "screw_coolant")
OUTSIDE = ("midspan_radiant", "bed_bending", "preload_spring")
SENSOR = ("interferometer_air", "probe_mount_drift", "ambient_pt100_step")
ALL = GRAMMAR + OUTSIDE + SENSOR


def machine(machine_seed):
    m = {
        "L": 1.25, "D": 0.032, "nut": 0.110, "bearing": 0.035, "free_bearing": 0.030,
        "rho": 7850.0, "c": 470.0, "alpha": 11.2e-6, "lam": 42.0,
        "pf_drawing": -70.0, "travel": (0.0, 850.0),
        "kB": 0.85e-3, "kN": 1.25e-3,           # W per mm/min
        "h0": 11.0, "h1": 9.0,                   # h = h0 + h1 (v / 1 m/min)^0.8
        "motor_G": 0.9, "kF": 0.7e-3, "nl_a": 0.10, "lag_tau": 1200.0, "hold_W": 5.0,
        "s_off": 6.0, "s_c1": 9.0, "s_c0": -2.0, "cool_g": 9.0,
        "lamp_W": 3.0, "bend_um_m2K": 7.0, "spring_kappa": 0.35,
        "iair_um_mK": 1.0, "probe_um_K": 3.0, "pt_step_K": 0.6,
    }
    r = random.Random(machine_seed * 6271 + 29)
    for k in ("kB", "kN", "h0", "h1", "lam", "motor_G", "kF", "nl_a", "hold_W", "cool_g", "lamp_W"):
        m[k] *= math.exp(r.gauss(0.0, 0.10))
    m["lag_tau"] *= r.uniform(0.8, 1.3)
    m["pf_true"] = m["pf_drawing"] + r.choice((-1.0, 1.0)) * r.uniform(1.5, 5.0)
    for k in ("s_off", "s_c1", "bend_um_m2K"):
        m[k] *= r.choice((-1.0, 1.0)) * r.uniform(0.8, 1.2)
    return m


# ----------------------------------------------------------------------------------------------
# Screw: non-uniform vertex grid, lumped capacities, theta scheme

class Screw:
    def __init__(self, L, D, rho, c, lam, t0, nodes=34, ratio=1.08):
        w = [ratio ** i for i in range(nodes - 1)]
        scale = L / sum(w)
        self.s = [0.0]
        for wi in w:
            self.s.append(self.s[-1] + wi * scale)
        self.s[-1] = L
        self.n = nodes
        self.L = L
        self.A = math.pi * D * D / 4.0
        self.P = math.pi * D
        self.rc = rho * c
        self.lam = lam
        # control volume of node i: [lo_i, hi_i]
        self.lo = [0.0] + [0.5 * (self.s[i - 1] + self.s[i]) for i in range(1, nodes)]
        self.hi = [0.5 * (self.s[i] + self.s[i + 1]) for i in range(nodes - 1)] + [L]
        self.vol = [self.hi[i] - self.lo[i] for i in range(nodes)]
        self.C = [self.rc * self.A * v for v in self.vol]
        self.G = [lam * self.A / (self.s[i + 1] - self.s[i]) for i in range(nodes - 1)]
        self.T = [t0] * nodes

    def spread(self, a, b):
        """[(node, fraction)] of the interval [a, b] over the control volumes."""
        a, b = max(a, 0.0), min(b, self.L)
        out = []
        if b <= a:
            return out
        for i in range(self.n):
            o = min(b, self.hi[i]) - max(a, self.lo[i])
            if o > 0:
                out.append((i, o / (b - a)))
        return out

    def cover(self, a, b):
        """Covered length of each control volume by [a, b]."""
        cv = [0.0] * self.n
        for i, f in self.spread(a, b):
            cv[i] = f * (min(b, self.L) - max(a, 0.0))
        return cv

    def step(self, dt, q, exposed_len, h, t_air, g=0.0, t_cool=0.0, theta=0.6):
        """theta scheme: (C/dt + theta K) T1 = (C/dt - (1-theta) K) T0 + q + b."""
        n = self.n
        T = self.T
        # K = conduction + convection (diag), b = convection * t_air
        hd = [h * self.P * exposed_len[i] + g * self.vol[i] for i in range(n)]
        hd[-1] += h * self.A
        bsrc = [h * self.P * exposed_len[i] * t_air + g * self.vol[i] * t_cool for i in range(n)]
        bsrc[-1] += h * self.A * t_air
        a = [0.0] * n
        bdiag = [0.0] * n
        cc = [0.0] * n
        rhs = [0.0] * n
        for i in range(n):
            kd = hd[i]
            kT = hd[i] * T[i]
            if i > 0:
                kd += self.G[i - 1]
                kT += self.G[i - 1] * (T[i] - T[i - 1])
                a[i] = -theta * self.G[i - 1]
            if i < n - 1:
                kd += self.G[i]
                kT += self.G[i] * (T[i] - T[i + 1])
                cc[i] = -theta * self.G[i]
            # K T0 = sum of the conductive differences + hd T0
            kT0 = kT
            bdiag[i] = self.C[i] / dt + theta * kd
            rhs[i] = self.C[i] / dt * T[i] - (1.0 - theta) * kT0 + q[i] + bsrc[i]
        # Thomas
        cp = [0.0] * n
        dp = [0.0] * n
        cp[0] = cc[0] / bdiag[0]
        dp[0] = rhs[0] / bdiag[0]
        for i in range(1, n):
            den = bdiag[i] - a[i] * cp[i - 1]
            cp[i] = cc[i] / den if i < n - 1 else 0.0
            dp[i] = (rhs[i] - a[i] * dp[i - 1]) / den
        x = [0.0] * n
        x[-1] = dp[-1]
        for i in range(n - 2, -1, -1):
            x[i] = dp[i] - cp[i] * x[i + 1]
        self.T = x

    def at(self, s):
        s = min(max(s, 0.0), self.L)
        for i in range(self.n - 1):
            if s <= self.s[i + 1]:
                f = (s - self.s[i]) / (self.s[i + 1] - self.s[i])
                return self.T[i] + f * (self.T[i + 1] - self.T[i])
        return self.T[-1]

    def integral(self, s, t_ref):
        """Exact integral of the piecewise-linear rise from 0 to s (K m)."""
        s = min(max(s, 0.0), self.L)
        tot = 0.0
        for i in range(self.n - 1):
            a, b = self.s[i], self.s[i + 1]
            if s <= a:
                break
            hi = min(b, s)
            ta = self.T[i] - t_ref
            tb = self.at(hi) - t_ref
            tot += 0.5 * (ta + tb) * (hi - a)
        return tot

    def energy(self, t_ref):
        return sum(self.C[i] * (self.T[i] - t_ref) for i in range(self.n))


class Lag:
    def __init__(self, y, tau):
        self.y, self.tau = y, tau

    def update(self, target, dt):
        self.y += (target - self.y) * (1.0 - math.exp(-dt / self.tau))
        return self.y


# ----------------------------------------------------------------------------------------------
# Programme

def programme(seed, total_s, kind):
    r = random.Random(seed * 92821 + 7)
    if kind == "auto":
        kind = ("ladder", "cycles", "random")[seed % 3]
    ph = [(0.0, 240.0, 0.0)]
    t = 240.0
    if kind == "ladder":
        feeds = [2000.0, 4000.0, 6000.0, 8000.0]
        if seed % 2:
            feeds.reverse()
        for f in feeds:
            d = 60.0 * r.uniform(30.0, 45.0)
            ph.append((t, t + d, f))
            t += d
        ph.append((t, total_s + 3600.0, 0.0))
    elif kind == "cycles":
        while t < total_s + 3600.0:
            d = 60.0 * r.uniform(10.0, 20.0)
            f = 500.0 * round(r.uniform(2500.0, 8500.0) / 500.0)
            ph.append((t, t + d, f))
            t += d
            p = 60.0 * (r.uniform(3.0, 8.0) if r.random() < 0.8 else r.uniform(25.0, 40.0))
            ph.append((t, t + p, 0.0))
            t += p
    else:
        moving = True
        while t < total_s + 3600.0:
            d = 60.0 * (r.uniform(25.0, 70.0) if moving else r.uniform(15.0, 45.0))
            f = 100.0 * round(r.uniform(2000.0, 9000.0) / 100.0) if moving else 0.0
            ph.append((t, t + d, f))
            t += d
            moving = not moving
    return ph, kind


def hall(seed):
    r = random.Random(seed * 313 + 1)
    t0 = round(r.uniform(18.5, 23.0), 2)
    trend = r.uniform(-0.4, 0.4) / 3600.0
    amp = r.uniform(0.3, 0.8)
    per = r.uniform(4.0, 9.0) * 3600.0
    phase = r.uniform(0.0, 2.0 * math.pi)

    def f(t):
        return t0 + trend * t + amp * (math.sin(2.0 * math.pi * t / per + phase) - math.sin(phase))
    return f, t0


# ----------------------------------------------------------------------------------------------

def simulate(effects, seed, hours, m, kind="auto", interval_min=None, targets=9):
    eff = set(effects)
    rnd = random.Random(seed * 7777 + 3)
    total = hours * 3600.0
    air, t0 = hall(seed)
    sc = Screw(m["L"], m["D"], m["rho"], m["c"], m["lam"], t0)
    phases, kind = programme(seed, total, kind)
    trav = m["travel"]
    pf = m["pf_true"]
    if interval_min is None:
        interval_min = (20.0, 25.0, 30.0)[seed % 3]
    tg = [trav[0] + 25.0 + (trav[1] - trav[0] - 50.0) * k / (targets - 1) for k in range(targets)]
    run_times = []
    t = 60.0
    while t < total - 40.0:
        run_times.append(t)
        t += 60.0 * interval_min
    sub = 0.5
    nsub = 12
    dt = sub * nsub
    bearing = sc.spread(0.0, m["bearing"])
    cov_bearing = sc.cover(0.0, m["bearing"])
    free = sc.spread(m["L"] - m["free_bearing"], m["L"])
    lamp = sc.spread(0.4 * m["L"], 0.7 * m["L"])
    r_on = random.Random(seed * 11 + 5)
    lamp_on = (r_on.uniform(0.3, 1.2) * 3600.0, r_on.uniform(2.0, 3.0) * 3600.0)
    step_at = r_on.uniform(0.3, 0.7) * total
    flange = t0
    block = t0
    nut_h = Lag(t0, 800.0)
    motor = Lag(t0, 1800.0)
    bed = Lag(t0 + 0.2, 9000.0)
    bed0 = bed.y
    lagged_qb = Lag(0.0, m["lag_tau"])
    fhous = Lag(t0, 1300.0)

    def chiller(tt):
        return t0 - 1.0 + 0.3 * math.sin(2.0 * math.pi * tt / 2400.0)

    pos = trav[0]
    direction = 1.0
    pi = 0
    run_i = -1
    in_run = False
    order = []
    tk = 0
    dwell = 0.0
    pending = []
    meas = []
    kin = []
    events = []
    states = [(0.0, sc.integral(m["L"], t0) * m["alpha"] * 1e6, (t0, flange, t0, t0, t0, bed.y, chiller(0.0)))]
    last_label = None
    for step in range(int(math.ceil(total / dt))):
        q = [0.0] * sc.n
        cov = list(cov_bearing)
        vsum = 0.0
        vpow = 0.0
        still = 0.0
        for k in range(nsub):
            ts = step * dt + k * sub
            if not in_run and run_i + 1 < len(run_times) and ts >= run_times[run_i + 1]:
                run_i += 1
                in_run = True
                order = list(tg) if run_i % 2 == 0 else list(reversed(tg))
                tk = 0
                dwell = 4.0
                events.append((ts, "laser run %d" % run_i))
            v = 0.0
            if in_run:
                goal = order[tk]
                gap = goal - pos
                if abs(gap) > 1e-9:
                    mv = min(abs(gap), 2500.0 / 60.0 * sub)
                    pos += math.copysign(mv, gap)
                    v = 2500.0 * mv / (2500.0 / 60.0 * sub)
                else:
                    dwell -= sub
                    if dwell <= 1e-9:
                        pending.append((ts + sub, run_i, goal))
                        tk += 1
                        dwell = 4.0
                        if tk == len(order):
                            in_run = False
                fcmd = 2500.0 if v > 0 else 0.0
            else:
                while pi + 1 < len(phases) and phases[pi][1] <= ts:
                    pi += 1
                fcmd = phases[pi][2]
                label = ("F%d" % int(fcmd)) if fcmd > 0 else "hold"
                if label != last_label:
                    events.append((ts, label))
                    last_label = label
                rem = fcmd / 60.0 * sub
                while rem > 1e-12:
                    lim = trav[1] if direction > 0 else trav[0]
                    d = min(rem, abs(lim - pos))
                    pos += direction * d
                    rem -= d
                    if rem > 1e-12:
                        direction = -direction
                v = fcmd
            if ts <= total + 1e-9 and abs(ts * 2.0 - round(ts * 2.0)) < 1e-9:
                kin.append((ts, pos, fcmd))
            vsum += v
            vpow += (v / 1000.0) ** 2
            if v == 0.0:
                still += sub
            s = abs(pos - pf) / 1000.0
            qn = (m["kN"] * v + (m["nl_a"] * (v / 1000.0) ** 2 if "nonlinear_feed_heat" in eff else 0.0)) / nsub
            half = m["nut"] / 2.0
            for i, f in sc.spread(s - half, s + half):
                q[i] += qn * f
            for i, c in enumerate(sc.cover(s - half, s + half)):
                cov[i] += c / nsub
        v = vsum / nsub
        ta = air(step * dt + 0.5 * dt)
        qb = m["kB"] * v
        # fixed-bearing housing: flange in contact with the screw, block behind it
        tb = sum(sc.T[i] * f for i, f in bearing)
        q_contact = 0.6 * (flange - tb)
        qb_screw = 0.75 * qb
        if "heat_path_lag" in eff:
            qb_screw = 0.75 * lagged_qb.update(qb, dt)
        extra_fixed = q_contact + qb_screw
        if "motor_heat_fixed_end" in eff:
            extra_fixed += m["motor_G"] * (motor.y - ta)
        if "holding_heat" in eff:
            extra_fixed += m["hold_W"] * still / dt
        for i, f in bearing:
            q[i] += extra_fixed * f
        qf = 0.0
        if "free_end_bearing_heat" in eff:
            qf = m["kF"] * v
            for i, f in free:
                q[i] += qf * f
        if "midspan_radiant" in eff and lamp_on[0] <= step * dt < lamp_on[0] + lamp_on[1]:
            for i, f in lamp:
                q[i] += m["lamp_W"] * f
        exposed = [max(0.0, sc.vol[i] - cov[i]) for i in range(sc.n)]
        h = m["h0"] + m["h1"] * (v / 1000.0) ** 0.8
        g = m["cool_g"] if "screw_coolant" in eff else 0.0
        sc.step(dt, q, exposed, h, ta, g, chiller(step * dt + 0.5 * dt))
        tnow = (step + 1) * dt
        # housing nodes (explicit, small steps are stable: capacities 2500/6000 J/K)
        flange += dt / 2500.0 * (0.25 * qb - q_contact + 1.5 * (block - flange) - 0.8 * (flange - ta))
        block += dt / 6000.0 * (1.5 * (flange - block) - 3.0 * (block - ta))
        nh = nut_h.update(ta + 0.3 * m["kN"] * v + 0.2 * (sc.at(abs(pos - pf) / 1000.0) - ta), dt)
        mo = motor.update(ta + 1.5e-3 * v + 0.8 * still / dt, dt)
        bd = bed.update(ta + 0.2 + 1.8 + 0.12 * v / 1000.0, dt)
        fh = fhous.update(ta + 0.8 * qf + 0.2 * (sc.T[-1] - ta), dt)
        elong = sc.integral(m["L"], t0) * m["alpha"] * 1e6
        if "preload_spring" in eff:
            elong *= (1.0 - m["spring_kappa"])
        states.append((tnow, elong, (ta, flange * 0.4 + block * 0.6, fh, nh, mo, bd, chiller(tnow))))
        for (tm, run, x) in pending:
            sx = abs(x - pf) / 1000.0
            e = m["alpha"] * sc.integral(sx, t0) * 1e6
            if "preload_spring" in eff:
                e -= m["spring_kappa"] * (sx / m["L"]) * m["alpha"] * sc.integral(m["L"], t0) * 1e6
            dT = bd - bed0
            if "structure_offset" in eff:
                e += m["s_off"] * dT
            if "structure_linear" in eff:
                e += (m["s_c1"] * x / 1000.0 + m["s_c0"]) * dT
            if "bed_bending" in eff:
                e += m["bend_um_m2K"] * (x / 1000.0) ** 2 * dT
            meas.append((tm, run, x, e, ta))
        pending = []
    return {"kin": kin, "states": states, "meas": meas, "events": events, "kind": kind, "t0": t0,
            "bed0": bed0, "step_at": step_at, "lamp_on": lamp_on, "rnd": rnd, "total": total, "dt": dt,
            "interval_min": interval_min, "screw": sc}


def interp(states, idx, t, sub=None):
    dt = states[1][0] - states[0][0]
    i = min(max(int(t / dt), 0), len(states) - 2)
    f = min(max((t - states[i][0]) / dt, 0.0), 1.0)
    a = states[i][idx] if sub is None else states[i][idx][sub]
    b = states[i + 1][idx] if sub is None else states[i + 1][idx][sub]
    return a + f * (b - a)


CHANNELS = [
    # id, kind, sensor, unit, role, location, aux index
    ("Tair", "temperature", "PT100", "degC", "ambient", "hall air beside the column", 0),
    ("Tfb", "temperature", "PT100", "degC", "fixed_bearing", "fixed bearing block", 1),
    ("Tsb", "temperature", "PT100", "degC", "free_bearing", "support bearing block", 2),
    ("Tnut", "temperature", "PT100", "degC", "nut", "nut housing", 3),
    ("Tmot", "temperature", "PT100", "degC", "motor", "servo motor flange", 4),
    ("Tbed", "temperature", "PT100", "degC", "structure", "bed casting, mid travel", 5),
    ("Tcool", "temperature", "PT100", "degC", "coolant", "screw coolant inlet", 6),
]


def write_bundle(out, effects, seed, m, sim, name):
    os.makedirs(out, exist_ok=True)
    eff = set(effects)
    rnd = sim["rnd"]
    total = sim["total"]
    st = sim["states"]
    rows = {}

    def put(t, cid, text):
        rows.setdefault(round(t, 1), {})[cid] = text
    for (t, x, f) in sim["kin"]:
        put(t, "Xact", "%.3f" % x)
        if abs(t - round(t)) < 1e-9:
            put(t, "Fcmd", "%d" % int(round(f)))
    t = 1.3
    while t <= total:
        for (cid, _, _, _, _, _, k) in CHANNELS:
            if rnd.random() < 0.005:
                continue
            v = interp(st, 2, t, k) + rnd.gauss(0.0, 0.04)
            if cid == "Tair" and "ambient_pt100_step" in eff and t >= sim["step_at"]:
                v += m["pt_step_K"]
            put(t, cid, "%.2f" % v)
        t += 3.0
    t = 0.0
    while t <= total:
        v = interp(st, 1, t) - 3.0 + rnd.gauss(0.0, 0.15)
        if "probe_mount_drift" in eff:
            v += m["probe_um_K"] * (interp(st, 2, t, 5) - sim["bed0"])
        put(t, "Zprobe", "%.2f" % v)
        t += 1.0
    ids = ["Xact", "Fcmd", "Zprobe"] + [c[0] for c in CHANNELS]
    order = sorted(ids, key=lambda s: (len(s) * 7919 + seed) % 13)
    with open(os.path.join(out, "channels.csv"), "w", encoding="utf-8", newline="\n") as fh:
        fh.write("time_s," + ",".join(order) + "\n")
        for tt in sorted(rows):
            c = rows[tt]
            fh.write("%.1f," % tt + ",".join(c.get(i, "") for i in order) + "\n")
    trav = m["travel"]

    def pitch(x):
        return 4.0 * (x - trav[0]) / (trav[1] - trav[0]) + 0.8 * math.sin(2.0 * math.pi * x / 191.0)
    laser = trav[0] - 40.0
    air0 = None
    with open(os.path.join(out, "interferometer.csv"), "w", encoding="utf-8", newline="\n") as fh:
        fh.write("time_s,run,position_mm,error_um\n")
        for (tm, run, x, e, ta) in sim["meas"]:
            if air0 is None:
                air0 = ta
            beam = (x - laser) / 1000.0
            k_air = m["iair_um_mK"] if "interferometer_air" in eff else 0.1
            air_err = k_air * beam * (ta - air0)
            fh.write("%.1f,%d,%.3f,%.3f\n" % (tm, run, x, pitch(x) + e + air_err + rnd.gauss(0.0, 0.2)))
    with open(os.path.join(out, "events.csv"), "w", encoding="utf-8", newline="\n") as fh:
        fh.write("time_s,label\n")
        for (te, label) in sim["events"]:
            if te <= total:
                fh.write("%.1f,%s\n" % (te, label))
    channels = []
    for (cid, kind, sensor, unit, role, loc, _) in CHANNELS:
        ch = {"id": cid, "kind": kind, "sensor": sensor, "unit": unit, "location": loc, "role": role}
        if role == "fixed_bearing":
            ch["screw_position_m"] = 0.0
        if role == "free_bearing":
            ch["screw_position_m"] = m["L"]
        channels.append(ch)
    channels.append({"id": "Zprobe", "kind": "displacement", "sensor": "eddy-current", "unit": "um",
                     "location": "free screw end, axial", "role": "screw_elongation"})
    channels.append({"id": "Xact", "kind": "position", "sensor": "cnc", "unit": "mm", "role": "axis_position"})
    channels.append({"id": "Fcmd", "kind": "feed", "sensor": "cnc", "unit": "mm/min", "role": "feed_rate"})
    r = random.Random(seed)
    manifest = {
        "format": "thermal-error-bundle", "version": 1,
        "session": {"name": name, "started": "2026-10-%02dT%02d:%02d:00Z" % (1 + seed % 27, 6 + seed % 9, r.randrange(60)),
                    "operator": "thirdsim.py", "notes": "third simulator (scripts/thirdsim.py), programme %s" % sim["kind"]},
        "machine": {"name": "vertical mill Z slide (thirdsim)", "axis": "X", "loop": "semi-closed",
                    "screw": {"length_m": m["L"], "diameter_m": m["D"], "nut_length_m": m["nut"],
                              "fixed_bearing_length_m": m["bearing"], "density_kg_m3": m["rho"],
                              "specific_heat_J_kgK": m["c"], "expansion_per_K": m["alpha"],
                              "conductivity_W_mK": None, "mounting": "fixed-free"},
                    "fixed_end_position_mm": m["pf_drawing"], "travel_mm": list(m["travel"])},
        "channels": channels,
        "interferometer": {"file": "interferometer.csv", "unit": "um", "reference_run": 0},
        "events": "events.csv",
    }
    with open(os.path.join(out, "manifest.json"), "w", encoding="utf-8", newline="\n") as fh:
        json.dump(manifest, fh, indent=2)
        fh.write("\n")


# ----------------------------------------------------------------------------------------------

def selftest():
    ok = True

    def check(name, v, e, tol):
        nonlocal ok
        good = abs(v - e) <= tol
        ok = ok and good
        print("%-60s %12.6g expected %12.6g (tol %g) %s" % (name, v, e, tol, "ok" if good else "FAIL"))

    m = machine(0)
    # 1. steady fin: heat Q into [0, a] (covered), convection h elsewhere and on the free face
    for nodes in (34, 80):
        sc = Screw(m["L"], m["D"], m["rho"], m["c"], m["lam"], 20.0, nodes=nodes)
        h, Q, a = 15.0, 4.0, m["bearing"]
        lam, A, P, L = m["lam"], sc.A, sc.P, m["L"]
        mm = math.sqrt(h * P / (lam * A))
        beta = h / (lam * mm)
        C2 = Q / (lam * A * mm * (math.sinh(mm * (L - a)) + beta * math.cosh(mm * (L - a))))
        ta_ = C2 * (math.cosh(mm * (L - a)) + beta * math.sinh(mm * (L - a)))
        C1 = ta_ + Q / a * a * a / (2.0 * lam * A)

        def an(x):
            return C1 - Q / a * x * x / (2.0 * lam * A) if x <= a else C2 * (math.cosh(mm * (L - x)) + beta * math.sinh(mm * (L - x)))
        q = [0.0] * sc.n
        for i, f in sc.spread(0.0, a):
            q[i] += Q * f
        cov = sc.cover(0.0, a)
        exp_ = [sc.vol[i] - cov[i] for i in range(sc.n)]
        for _ in range(3000):
            sc.step(60.0, q, exp_, h, 20.0)
        err = max(abs(sc.T[i] - 20.0 - an(sc.s[i])) for i in range(sc.n))
        check("steady fin, %d nodes: max |T - analytic| / peak" % nodes, err / an(0.0), 0.0, 0.05 if nodes == 34 else 0.015)
    # 2. energy conservation, adiabatic
    sc = Screw(m["L"], m["D"], m["rho"], m["c"], m["lam"], 20.0)
    inj = 0.0
    for k in range(500):
        q = [0.0] * sc.n
        s = 0.3 + 0.5 * abs(math.sin(0.03 * k))
        for i, f in sc.spread(s - 0.05, s + 0.05):
            q[i] += 7.0 * f
        sc.step(6.0, q, [0.0] * sc.n, 0.0, 20.0)
        inj += 7.0 * 6.0
    check("adiabatic: stored / injected energy", sc.energy(20.0) / inj, 1.0, 1e-9)
    # 3. uniform rise: expansion alpha dT (X - P_f)
    sc.T = [22.0] * sc.n
    for x in (0.0, 425.0, 850.0):
        s = (x - m["pf_true"]) / 1000.0
        check("uniform +2 K: error at X=%g (um)" % x, m["alpha"] * sc.integral(s, 20.0) * 1e6,
              m["alpha"] * 2.0 * s * 1e6, 1e-9)
    # 4. linear profile: the trapezoid integral is exact
    sc.T = [20.0 + 3.0 * s for s in sc.s]
    check("linear profile integral to 0.77 m (K m)", sc.integral(0.77, 20.0), 1.5 * 0.77 ** 2, 1e-12)
    # 5. lumped cooling
    sc = Screw(m["L"], m["D"], m["rho"], m["c"], m["lam"], 25.0)
    h = 20.0
    tau = m["rho"] * m["c"] * sc.A * m["L"] / (h * (sc.P * m["L"] + sc.A))
    for _ in range(300):
        sc.step(6.0, [0.0] * sc.n, list(sc.vol), h, 20.0, theta=0.5)
    check("uniform cooling 30 min: mean rise (K)", sc.energy(20.0) / sum(sc.C), 5.0 * math.exp(-1800.0 / tau), 0.01)
    print("selftest", "passed" if ok else "FAILED")
    return 0 if ok else 1


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--effects", default="none", help="comma-separated effects, or none")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--machine-seed", type=int, default=1)
    p.add_argument("--hours", type=float, default=4.0)
    p.add_argument("--programme", choices=("auto", "ladder", "cycles", "random"), default="auto")
    p.add_argument("--interval-min", type=float, default=None)
    p.add_argument("--out")
    p.add_argument("--truth", help="write the concealed truth (JSON) here, outside the bundle")
    p.add_argument("--selftest", action="store_true")
    a = p.parse_args(argv)
    if a.selftest:
        return selftest()
    if not a.out:
        p.error("--out is required")
    effects = [] if a.effects == "none" else a.effects.split(",")
    for e in effects:
        if e not in ALL:
            p.error("unknown effect %s" % e)
    m = machine(a.machine_seed)
    sim = simulate(effects, a.seed, a.hours, m, a.programme, a.interval_min)
    write_bundle(a.out, effects, a.seed, m, sim, "thirdsim seed %d" % a.seed)
    if a.truth:
        kinds = {e: ("grammar" if e in GRAMMAR else "outside" if e in OUTSIDE else "sensor") for e in effects}
        with open(a.truth, "w", encoding="utf-8") as fh:
            json.dump({"effects": effects, "kinds": kinds, "machine_seed": a.machine_seed, "seed": a.seed,
                       "programme": sim["kind"], "pf_true_mm": m["pf_true"], "conductivity_W_mK": m["lam"],
                       "last_position_s": sim["kin"][-1][0],
                       "last_interferometer_s": sim["meas"][-1][0] if sim["meas"] else None}, fh, indent=1)
    print("thirdsim: %s (%s, seed %d, %s, %d points)" % (a.out, a.effects, a.seed, sim["kind"], len(sim["meas"])),
          file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
