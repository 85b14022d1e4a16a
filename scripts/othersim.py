#!/usr/bin/env python3
"""othersim.py - an independent ball-screw feed-axis simulator that writes recording bundles.

Written from the seed-000 paper (1-D finite differences of a fixed-free ball screw, heat
Q_B = k_B v at the fixed-end bearing, Q_N = k_N v spread over the moving nut, convection
h = h0 + h1 v, thermal error = alpha * integral of the temperature rise from the fixed end to
the nut) and the recording-bundle spec (/work/shared/spec/recording-bundle.md), without
DriftLab's own rig or analysis code. Its purpose is to check that DriftLab's diagnosis does not
depend on quirks of DriftLab's simulated rig: another machine (1.0 m x 40 mm screw, 150 mm nut,
travel 0..700 mm, fixed end on the negative side), other channel ids and column order, other
sample rates, dropouts, an extra channel with an unknown role, a probe with a zero offset.

Standard library only (no numpy).

    othersim.py --effect none --seed 1 --hours 4 --out train.bundle
    othersim.py --effect none --seed 2 --hours 3 --out validate.bundle
    othersim.py --selftest          # physics checks (analytic steady state, energy, expansion)

Machine: fixed end on the negative side (drawing P_f = -120 mm, truth -124.5 mm) or, with
--fixed-end positive, mirrored beyond the travel's positive end (+820 / +824.5 mm: the error is
then -alpha * integral, eq. 15 of the paper). --machine-seed N spreads the laws by 12 %.
Duty (--duty random): seeded feed phases 3000-9000 mm/min of 30-80 min and standstills of 20-50
min after a cold reference run; the axis reciprocates over its travel at the feed. --duty table2:
the paper's 84 min warm-up, 42 min cooling, 42 min warm-up. Interferometer runs every
--interval-min at --targets targets (3 s dwell, 0.25 um noise, a fixed pitch error), run 0 cold.
Channels: PT100s TC01..TC08 (roles ambient, fixed_bearing, free_bearing, nut, motor, structure,
coolant and an unknown role hydraulic_oil) at 0.5 Hz on their own clock, 0.03 K noise, 1 %
dropouts; eddy-current probe EC1 (screw_elongation, 0.5 Hz, 0.2 um noise, +2 um zero offset,
"nan" dropouts); AXPOS (axis_position) and FEED (feed_rate) at 1 Hz; scrambled column order.

--wide widens the differences from DriftLab's rig (issue 18): a coarser grid (40 cells), a
fixed-bearing housing that is a body of its own (4000 J/K, 2.5 W/K to the air) taking 30 % of
the bearing heat and exchanging heat with the screw's bearing section through 0.25 W/K both
ways (the fixed_bearing PT100 reads it), PT100s at 0.2 Hz with 0.05 K noise, a calibration
offset of up to +-0.15 K and a slow random-walk wander (0.02 K per sqrt(h)), the probe at
1 Hz with 0.3 um/h holder drift, interferometer noise 0.3 um white plus an air-refraction
drift proportional to the distance from the laser head (a random walk, 0.4 ppm per sqrt(h)
at the end of the travel, reset at the reference run), runs with 5 s dwell that visit the
targets outwards and back on alternate runs, and position / feed at 0.5 Hz.

Effects (physics the seed-000 model leaves out), fixed per machine:
  structure_offset       position-independent error c_s (T_structure - T_structure(0)), 8 um/K
  free_end_bearing_heat  k_F v into the free-end bearing section (k_F = 0.8 k_B)
  holding_heat           P_hold = 4 W into the fixed-end section while the axis stands still
  screw_coolant          g (T_c - T) per metre of screw, g = 8 W/(m K), chiller temperature T_c

Measurement-chain faults (--sensor-fault, issue 36; the machine is not changed, a sensor reads
wrong; --fault-size scales the law, default 1):
  air_compensation  the interferometer's air compensation is frozen at the reference run: the
                    laser head stands 150 mm beyond the travel's far end (the end away from
                    the fixed end), and a reading carries +0.93 um/m/K x beam length (head to
                    target) x (T_air - T_air at the point's reference run)
  probe_holder      the eddy-current probe's bracket is bolted to the bed casting: the reading
                    moves by -2.5 um/K x the bracket's temperature rise, the bracket following
                    the structure temperature through a 15-min lag
  pt100_step        the structure PT100 (TC06) reads 0.5 K low from 40 % of the recording on
                    (a contact that worked loose)
  pt100_drift       the ambient PT100 (TC01) drifts upwards at 0.25 K/h from 30 % of the
                    recording on (self-heating after a cable fault); the interferometer's own
                    compensation reads the true air
The fault and its law go to the manifest's "othersim" block (not read by DriftLab).
"""

import argparse
import json
import math
import os
import random
import sys

EFFECTS = ("none", "structure_offset", "free_end_bearing_heat", "holding_heat", "screw_coolant")
SENSOR_FAULTS = ("none", "air_compensation", "probe_holder", "pt100_step", "pt100_drift")


# ----------------------------------------------------------------------------------------------
# Machine

def nominal_machine():
    """The simulated machine (SI units unless the name says otherwise)."""
    return {
        "length_m": 1.0,
        "diameter_m": 0.040,
        "nut_length_m": 0.150,
        "fixed_bearing_length_m": 0.030,
        "free_bearing_length_m": 0.030,
        "density_kg_m3": 7800.0,
        "specific_heat_J_kgK": 460.0,
        "expansion_per_K": 11.5e-6,
        "conductivity_W_mK": 46.0,         # truth; the manifest says null (unknown)
        "drawing_fixed_end_mm": -120.0,    # manifest P_f
        "true_fixed_end_mm": -124.5,       # where the fixed end really is
        "travel_mm": (0.0, 700.0),
        "k_bearing_W_per_mm_min": 0.75e-3,  # Q_B = k_B v
        "k_nut_W_per_mm_min": 1.10e-3,      # Q_N = k_N v
        "h0_W_m2K": 14.0,                   # h = h0 + h1 v
        "h1_W_m2K_per_mm_min": 1.0e-3,
        "cells": 64,
        # effects (only the selected one is switched on)
        "k_free_W_per_mm_min": 0.6e-3,      # 0.8 k_B
        "structure_offset_um_K": 8.0,
        "holding_W": 4.0,
        "coolant_W_mK": 8.0,
        # structure: a slow body heated by a hydraulic unit and a little by the axis
        "structure_rise_K": 2.5,
        "structure_feed_K_per_m_min": 0.15,
        "structure_tau_s": 7200.0,
        # geometric pitch error (um) = a x/L_travel + b sin(2 pi x / p)
        "pitch_slope_um": 3.0,
        "pitch_wave_um": -1.2,
        "pitch_period_mm": 233.0,
    }


def mirror_machine(m):
    """The same machine with the fixed end on the positive side of the travel (P_f > travel)."""
    m = dict(m)
    lo, hi = m["travel_mm"]
    m["drawing_fixed_end_mm"] = hi + (lo - m["drawing_fixed_end_mm"])
    m["true_fixed_end_mm"] = hi + (lo - m["true_fixed_end_mm"])
    return m


def perturb_machine(m, machine_seed):
    """Optional spread of the heat and convection laws (machine_seed 0 = nominal)."""
    if machine_seed == 0:
        return m
    r = random.Random(machine_seed * 7919 + 17)
    m = dict(m)
    for key in ("k_bearing_W_per_mm_min", "k_nut_W_per_mm_min", "h0_W_m2K", "h1_W_m2K_per_mm_min",
                "conductivity_W_mK", "k_free_W_per_mm_min", "holding_W", "coolant_W_mK"):
        m[key] *= math.exp(r.gauss(0.0, 0.12))
    m["true_fixed_end_mm"] = m["drawing_fixed_end_mm"] + r.choice((-1.0, 1.0)) * r.uniform(2.0, 6.0)
    m["structure_offset_um_K"] *= r.choice((-1.0, 1.0)) * r.uniform(0.8, 1.2)
    return m


# ----------------------------------------------------------------------------------------------
# Screw: explicit finite volumes along the axis (fixed end adiabatic, free-end face convective)

class Screw:
    def __init__(self, length_m, diameter_m, cells, density, heat_capacity, conductivity, t0):
        self.n = cells
        self.length = length_m
        self.dx = length_m / cells
        self.area = math.pi * diameter_m ** 2 / 4.0
        self.perimeter = math.pi * diameter_m
        self.capacity = density * heat_capacity * self.area * self.dx      # J/K per cell
        self.conductance = conductivity * self.area / self.dx             # W/K between cells
        self.T = [t0] * cells

    def stable_step(self, h_max, g_max=0.0):
        """Largest explicit step: every cell's outflow coefficients times dt below its capacity."""
        worst = 2.0 * self.conductance + h_max * (self.perimeter * self.dx + self.area) + g_max * self.dx
        return self.capacity / worst

    def overlap(self, a, b):
        """[(cell, overlap length m)] of the interval [a, b] (m from the fixed end) with the cells."""
        a = max(a, 0.0)
        b = min(b, self.length)
        out = []
        if b <= a:
            return out
        i0 = int(a / self.dx)
        i1 = min(int(b / self.dx), self.n - 1)
        for i in range(i0, i1 + 1):
            lo = max(a, i * self.dx)
            hi = min(b, (i + 1) * self.dx)
            if hi > lo:
                out.append((i, hi - lo))
        return out

    def step(self, dt, q, exposed, h, t_amb, g=0.0, t_cool=0.0):
        """One explicit step. q: W per cell; exposed: fraction of each cell's surface in air."""
        T = self.T
        n = self.n
        G = self.conductance
        hs = h * self.perimeter * self.dx
        gd = g * self.dx
        k = dt / self.capacity
        new = [0.0] * n
        for i in range(n):
            Ti = T[i]
            flow = q[i] - hs * exposed[i] * (Ti - t_amb)
            if i > 0:
                flow += G * (T[i - 1] - Ti)
            if i < n - 1:
                flow += G * (T[i + 1] - Ti)
            else:
                flow -= h * self.area * (Ti - t_amb)
            if gd:
                flow -= gd * (Ti - t_cool)
            new[i] = Ti + k * flow
        self.T = new

    def energy(self, t_ref):
        return self.capacity * sum(t - t_ref for t in self.T)

    def expansion_m(self, s_m, t_ref, alpha):
        """alpha * integral_0^s (T - t_ref) ds: displacement of the screw section at s (m)."""
        s_m = min(max(s_m, 0.0), self.length)
        total = 0.0
        full = int(s_m / self.dx)
        for i in range(min(full, self.n)):
            total += self.T[i] - t_ref
        total *= self.dx
        if full < self.n:
            total += (self.T[full] - t_ref) * (s_m - full * self.dx)
        return alpha * total


# ----------------------------------------------------------------------------------------------
# Duty cycle, ambient, interferometer runs

def duty_cycle(seed, total_s, kind):
    """[(start_s, end_s, feed_mm_min)] phases; feed 0 is a standstill."""
    r = random.Random(seed * 104729 + 3)
    phases = [(0.0, 180.0, 0.0)]    # the cold reference run comes first
    t = 180.0
    if kind == "table2":
        feed = 3000.0 + 3000.0 * (seed % 3)
        for dur, f in ((84, feed), (42, 0.0), (42, feed)):
            phases.append((t, t + 60.0 * dur, f))
            t += 60.0 * dur
        while t < total_s:
            phases.append((t, t + 3600.0, 0.0))
            t += 3600.0
        return phases
    moving = r.random() < 0.75
    while t < total_s:
        if moving:
            dur = 60.0 * r.uniform(30.0, 80.0)
            feed = 100.0 * round(r.uniform(3000.0, 9000.0) / 100.0)
        else:
            dur = 60.0 * r.uniform(20.0, 50.0)
            feed = 0.0
        phases.append((t, t + dur, feed))
        t += dur
        moving = not moving
    return phases


def ambient(t, seed, start_C, trend_K_h=None):
    """Slowly drifting hall temperature: a linear trend and a 6-hour swing (0.1 - 0.2 K/h);
    trend_K_h replaces the seeded trend (--hall-trend)."""
    r = random.Random(seed * 31 + 5)
    trend = r.uniform(-0.15, 0.15) / 3600.0
    if trend_K_h is not None:
        trend = trend_K_h / 3600.0
    amp = r.uniform(0.1, 0.25)
    phase = r.uniform(0.0, 2.0 * math.pi)
    return start_C + trend * t + amp * (math.sin(2.0 * math.pi * t / 21600.0 + phase) - math.sin(phase))


class Lag:
    """First-order lag y' = (target - y) / tau, exact for a step-constant target."""

    def __init__(self, y0, tau_s):
        self.y = y0
        self.tau = tau_s

    def update(self, target, dt):
        self.y += (target - self.y) * (1.0 - math.exp(-dt / self.tau))
        return self.y


# ----------------------------------------------------------------------------------------------
# Simulation

def simulate(args, m):
    rnd = random.Random(args.seed * 1000003 + 11)
    total_s = args.hours * 3600.0
    travel = m["travel_mm"]
    alpha = m["expansion_per_K"]
    pf_true = m["true_fixed_end_mm"]
    error_sign = 1.0 if pf_true < travel[0] else -1.0
    t_amb0 = args.ambient_start
    wide = getattr(args, "wide", False)
    if wide:
        m = dict(m)
        m["cells"] = 40
    screw = Screw(m["length_m"], m["diameter_m"], m["cells"], m["density_kg_m3"], m["specific_heat_J_kgK"],
                  m["conductivity_W_mK"], t_amb0)
    v_max = 9000.0
    h_max = m["h0_W_m2K"] + m["h1_W_m2K_per_mm_min"] * v_max
    g_on = args.effect == "screw_coolant"
    dt = min(args.dt, 0.8 * screw.stable_step(h_max, m["coolant_W_mK"] if g_on else 0.0))
    sub_dt = 0.25           # kinematics substep; the heat step is a whole number of them
    substeps = max(1, int(dt / sub_dt))
    dt = substeps * sub_dt

    phases = duty_cycle(args.seed, total_s + 3600.0, args.duty)
    targets = [travel[0] + 15.0 + (travel[1] - travel[0] - 30.0) * k / (args.targets - 1) for k in range(args.targets)]
    run_feed = 2000.0       # mm/min between targets
    dwell_s = 5.0 if wide else 3.0
    kin_period = 2.0 if wide else 1.0
    run_times = []
    t = 30.0
    while t < total_s - 120.0:
        run_times.append(t)
        t += 60.0 * args.interval_min

    # kinematics state: the axis homes at the end of the travel nearest the fixed end, and a
    # run visits the targets from that end outwards
    pos = travel[0] if error_sign > 0 else travel[1]
    direction = error_sign
    if error_sign < 0:
        targets.reverse()
    phase_index = 0
    run_index = -1
    run_target = 0
    run_dwell_left = 0.0
    in_run = False
    run_order = list(targets)
    measurements = []       # (time_s, run, target_mm, thermal_um) thermal error before noise
    pending = []            # targets measured inside the current step: (time, run, x)

    # bearing and nut geometry (m from the fixed end)
    L = m["length_m"]
    LB = m["fixed_bearing_length_m"]
    LF = m["free_bearing_length_m"]
    LN = m["nut_length_m"]
    bearing_cells = screw.overlap(0.0, LB)
    free_cells = screw.overlap(L - LF, L)
    # no convection under the fixed bearing and the nut (paper eq. 10); the free-end support
    # section convects like the rest of the screw
    covered_fixed = [0.0] * screw.n
    for i, w in bearing_cells:
        covered_fixed[i] += w / screw.dx

    # auxiliary bodies
    housing_fixed = Lag(t_amb0, 1500.0)
    housing_body = t_amb0          # --wide: the fixed-bearing housing as a body of its own
    housing_capacity = 4000.0      # J/K
    housing_loss = 2.5             # W/K to the air
    housing_contact = 0.25         # W/K to the screw's bearing section
    housing_free = Lag(t_amb0, 1500.0)
    housing_nut = Lag(t_amb0, 900.0)
    motor = Lag(t_amb0, 2100.0)
    structure = Lag(t_amb0 + 0.1, m["structure_tau_s"])
    oil = Lag(t_amb0 + 0.5, 3600.0)
    chiller_mean = t_amb0 - 0.8

    def chiller(t):
        return chiller_mean + 0.4 * math.sin(2.0 * math.pi * t / 2700.0)

    kin_t = []              # 1 Hz position/feed (integer seconds)
    kin_x = []
    kin_f = []
    state_t = [0.0]         # step end times
    state_probe = [0.0]
    state_aux = [(t_amb0, t_amb0, t_amb0, t_amb0, t_amb0, t_amb0 + 0.1, chiller(0.0), t_amb0 + 0.5)]
    energy_in = 0.0
    events = []
    struct0 = structure.y
    next_kin = 0.0

    def phase_at(t):
        nonlocal phase_index
        while phase_index + 1 < len(phases) and phases[phase_index][1] <= t:
            phase_index += 1
        return phases[phase_index]

    last_feed_label = None
    t = 0.0
    nsteps = int(math.ceil(total_s / dt))
    zero_q = [0.0] * screw.n
    for step in range(nsteps):
        q = list(zero_q)
        nut_cover = [0.0] * screw.n
        speed_sum = 0.0
        standstill_time = 0.0
        for sub in range(substeps):
            ts = step * dt + sub * sub_dt
            x_start = pos
            # what is the axis doing?
            if not in_run and run_index + 1 < len(run_times) and ts >= run_times[run_index + 1]:
                run_index += 1
                in_run = True
                run_target = 0
                if wide and run_index > 0:
                    run_order = list(targets) if run_index % 2 == 0 else list(reversed(targets))
                else:
                    run_order = list(targets)
                run_dwell_left = dwell_s
                events.append((ts, "interferometer run %d" % run_index))
            speed = 0.0     # mm/min
            if in_run:
                x_goal = run_order[run_target]
                gap = x_goal - pos
                if abs(gap) > 1e-9:
                    move = min(abs(gap), run_feed / 60.0 * sub_dt)
                    pos += math.copysign(move, gap)
                    speed = run_feed * move / (run_feed / 60.0 * sub_dt)
                else:
                    run_dwell_left -= sub_dt
                    if run_dwell_left <= 1e-9:
                        pending.append((ts + sub_dt, run_index, x_goal))
                        run_target += 1
                        run_dwell_left = dwell_s
                        if run_target == len(targets):
                            in_run = False
                feed_cmd = run_feed if speed > 0 else 0.0
            else:
                ph = phase_at(ts)
                feed_cmd = ph[2]
                label = ("feed %d mm/min" % int(feed_cmd)) if feed_cmd > 0 else "standstill"
                if label != last_feed_label:
                    events.append((ts, label))
                    last_feed_label = label
                if feed_cmd > 0:
                    remaining = feed_cmd / 60.0 * sub_dt
                    while remaining > 1e-12:
                        limit = travel[1] if direction > 0 else travel[0]
                        d = min(remaining, abs(limit - pos))
                        pos += direction * d
                        remaining -= d
                        if remaining > 1e-12:
                            direction = -direction
                    speed = feed_cmd
            # 1 Hz kinematics at the integer seconds (substep starts: sub_dt = 0.25 s exactly)
            if ts == next_kin and ts <= total_s:
                kin_t.append(ts)
                kin_x.append(x_start)
                kin_f.append(feed_cmd)
                next_kin += kin_period
            speed_sum += speed
            if speed == 0.0:
                standstill_time += sub_dt
            # nut heat and nut cover at this substep (the nut centre sits |X - P_f| from the fixed end)
            s = abs(pos - pf_true) / 1000.0
            qn = m["k_nut_W_per_mm_min"] * speed / substeps
            for i, w in screw.overlap(s - LN / 2.0, s + LN / 2.0):
                q[i] += qn * w / LN
                nut_cover[i] += (w / screw.dx) / substeps
        v_mean = speed_sum / substeps
        qb = m["k_bearing_W_per_mm_min"] * v_mean
        if wide:
            # 30 % of the bearing heat goes into the housing body, which exchanges heat with the
            # screw's bearing section (both ways) and with the air
            t_bearing = sum(screw.T[i] * w for i, w in bearing_cells) / LB
            q_contact = housing_contact * (housing_body - t_bearing)
            for i, w in bearing_cells:
                q[i] += (0.7 * qb + q_contact) * w / LB
        else:
            for i, w in bearing_cells:
                q[i] += qb * w / LB
        qf = 0.0
        if args.effect == "free_end_bearing_heat":
            qf = m["k_free_W_per_mm_min"] * v_mean
            for i, w in free_cells:
                q[i] += qf * w / LF
        qh = 0.0
        if args.effect == "holding_heat":
            qh = m["holding_W"] * standstill_time / dt
            for i, w in bearing_cells:
                q[i] += qh * w / LB
        exposed = [max(0.0, 1.0 - covered_fixed[i] - nut_cover[i]) for i in range(screw.n)]
        h = m["h0_W_m2K"] + m["h1_W_m2K_per_mm_min"] * v_mean
        ta = ambient(t + 0.5 * dt, args.seed, t_amb0, getattr(args, "hall_trend", None))
        tc = chiller(t + 0.5 * dt)
        screw.step(dt, q, exposed, h, ta, m["coolant_W_mK"] if g_on else 0.0, tc)
        energy_in += sum(q) * dt
        if wide:
            ta_mid = ambient(t + 0.5 * dt, args.seed, t_amb0, getattr(args, "hall_trend", None))
            housing_body += dt / housing_capacity * (0.3 * qb - q_contact - housing_loss * (housing_body - ta_mid))
        t += dt
        # auxiliary temperatures
        hf = housing_fixed.update(ta + 0.9 * qb + (0.9 * qh if args.effect == "holding_heat" else 0.0), dt)
        if wide:
            hf = housing_body
        hfr = housing_free.update(ta + 0.9 * qf + 0.15 * (screw.T[-1] - ta), dt)
        hn = housing_nut.update(ta + 0.35 * m["k_nut_W_per_mm_min"] * v_mean, dt)
        mo = motor.update(ta + 1.2e-3 * v_mean + (0.6 * standstill_time / dt if args.effect == "holding_heat" else 0.1), dt)
        st = structure.update(ta + 0.1 + m["structure_rise_K"] + m["structure_feed_K_per_m_min"] * v_mean / 1000.0, dt)
        oi = oil.update(ta + 3.0, dt)
        state_t.append(t)
        state_probe.append(screw.expansion_m(L, t_amb0, alpha) * 1e6)
        state_aux.append((ta, hf, hfr, hn, mo, st, tc, oi))
        # interferometer readings taken in this step
        for (tm, run, x) in pending:
            # the nut section moves away from the fixed end: +u on the negative side, -u on the positive
            thermal = error_sign * screw.expansion_m(abs(x - pf_true) / 1000.0, t_amb0, alpha) * 1e6
            if args.effect == "structure_offset":
                thermal += m["structure_offset_um_K"] * (st - struct0)
            measurements.append((tm, run, x, thermal))
        pending = []

    return {
        "dt": dt, "kin": (kin_t, kin_x, kin_f), "state_t": state_t, "probe": state_probe, "aux": state_aux,
        "measurements": measurements, "events": events, "targets": targets, "screw": screw, "cells": m["cells"],
        "energy_in": energy_in, "rnd": rnd, "total_s": total_s, "run_times": run_times,
    }


def interp(ts, ys, t):
    """Linear interpolation in the step-end series (ts sorted, uniform)."""
    if t <= ts[0]:
        return ys[0]
    if t >= ts[-1]:
        return ys[-1]
    d = ts[1] - ts[0]
    i = min(int(t / d), len(ts) - 2)
    while ts[i + 1] < t:
        i += 1
    while ts[i] > t:
        i -= 1
    f = (t - ts[i]) / (ts[i + 1] - ts[i])
    return ys[i] + f * (ys[i + 1] - ys[i])


# ----------------------------------------------------------------------------------------------
# Bundle writer

CHANNELS = [
    # id, kind, sensor, unit, role, location, aux index (temperatures) or special
    ("TC01", "temperature", "PT100", "degC", "ambient", "hall air 0.5 m above the slide", 0),
    ("TC02", "temperature", "PT100", "degC", "fixed_bearing", "fixed-end bearing block (negative side)", 1),
    ("TC03", "temperature", "PT100", "degC", "free_bearing", "support bearing at the free end", 2),
    ("TC04", "temperature", "PT100", "degC", "nut", "nut flange on the carriage", 3),
    ("TC05", "temperature", "PT100", "degC", "motor", "servo motor housing", 4),
    ("TC06", "temperature", "PT100", "degC", "structure", "bed casting under the slide", 5),
    ("TC07", "temperature", "PT100", "degC", "coolant", "chiller return line", 6),
    ("TC08", "temperature", "PT100", "degC", "hydraulic_oil", "hydraulic tank", 7),
    ("EC1", "displacement", "eddy-current", "um", "screw_elongation", "free end of the screw, axial", "probe"),
    ("AXPOS", "position", "cnc", "mm", "axis_position", "Y axis actual position", "x"),
    ("FEED", "feed", "cnc", "mm/min", "feed_rate", "programmed feed", "f"),
]
COLUMN_ORDER = ["TC05", "FEED", "TC02", "EC1", "TC07", "TC01", "AXPOS", "TC04", "TC08", "TC06", "TC03"]


def fmt(v, digits):
    return ("%." + str(digits) + "f") % v


def write_bundle(args, m, sim):
    out = args.out
    os.makedirs(out, exist_ok=True)
    rnd = sim["rnd"]
    total_s = sim["total_s"]
    kin_t, kin_x, kin_f = sim["kin"]
    st = sim["state_t"]
    aux = sim["aux"]
    probe = sim["probe"]
    rows = {}   # time -> {id: text}

    def put(t, cid, text):
        rows.setdefault(t, {})[cid] = text

    wide = getattr(args, "wide", False)
    # axis position and feed: 1 Hz on integer seconds (0.5 Hz with --wide)
    for t, x, f in zip(kin_t, kin_x, kin_f):
        if t > total_s:
            break
        put(t, "AXPOS", fmt(x, 3))
        put(t, "FEED", "%d" % int(round(f)))
    # PT100s: 0.5 Hz on their own clock (0.7 s after the even seconds), 0.03 K noise, 0.01 K
    # resolution, ~1 % dropouts
    pt = [c for c in CHANNELS if c[1] == "temperature"]
    series = [[a[c[6]] for a in aux] for c in pt]
    # --wide: 0.2 Hz, 0.05 K noise, a calibration offset per sensor and a slow random walk
    pt_period = 5.0 if wide else 2.0
    pt_noise = 0.05 if wide else 0.03
    offsets = [rnd.uniform(-0.15, 0.15) if wide else 0.0 for _ in pt]
    wander = [0.0 for _ in pt]
    wander_step = 0.02 * math.sqrt(pt_period / 3600.0)
    fault = getattr(args, "sensor_fault", "none")
    size = getattr(args, "fault_size", 1.0)

    def pt100_fault(cid, t):
        """What a faulty PT100 adds to its reading (K)."""
        if fault == "pt100_step" and cid == "TC06" and t >= 0.4 * total_s:
            return -0.5 * size
        if fault == "pt100_drift" and cid == "TC01" and t >= 0.3 * total_s:
            return 0.25 * size * (t - 0.3 * total_s) / 3600.0
        return 0.0

    t = 0.7
    while t <= total_s:
        for k, (c, ys) in enumerate(zip(pt, series)):
            if wide:
                wander[k] += rnd.gauss(0.0, wander_step)
            if rnd.random() < 0.01:
                continue
            put(t, c[0], fmt(interp(st, ys, t) + offsets[k] + wander[k] + pt100_fault(c[0], t) + rnd.gauss(0.0, pt_noise), 2))
        t += pt_period
    # eddy-current probe: every 2 s on the even seconds, 0.2 um noise, +2.0 um zero offset,
    # ~0.5 % dropouts written as "nan"
    # --wide: 1 Hz, the holder drifting 0.3 um/h
    probe_period = 1.0 if wide else 2.0
    drift_um_s = 0.3 / 3600.0 if wide else 0.0
    # probe_holder: the bracket follows the bed casting (aux 5) through a 15-min lag
    holder = [0.0] * len(st)
    if fault == "probe_holder":
        bracket = Lag(aux[0][5], 900.0)
        for i in range(1, len(st)):
            holder[i] = -2.5 * size * (bracket.update(aux[i][5], st[i] - st[i - 1]) - aux[0][5])
    t = 0.0
    while t <= total_s:
        if rnd.random() < 0.005:
            put(t, "EC1", "nan")
        else:
            put(t, "EC1", fmt(interp(st, probe, t) + interp(st, holder, t) + 2.0 + drift_um_s * t + rnd.gauss(0.0, 0.2), 2))
        t += probe_period

    with open(os.path.join(out, "channels.csv"), "w", encoding="utf-8", newline="\n") as fh:
        fh.write("time_s," + ",".join(COLUMN_ORDER) + "\n")
        for tt in sorted(rows):
            cell = rows[tt]
            fh.write(("%.1f" % tt) + "," + ",".join(cell.get(cid) or "" for cid in COLUMN_ORDER) + "\n")

    # interferometer: geometric pitch error + thermal error + 0.25 um noise
    trav = m["travel_mm"][1] - m["travel_mm"][0]

    def pitch(x):
        return (m["pitch_slope_um"] * (x - m["travel_mm"][0]) / trav
                + m["pitch_wave_um"] * math.sin(2.0 * math.pi * x / m["pitch_period_mm"]))

    with open(os.path.join(out, "interferometer.csv"), "w", encoding="utf-8", newline="\n") as fh:
        fh.write("time_s,run,position_mm,error_um\n")
        # --wide: 0.3 um white noise and an air-refraction drift proportional to the distance from
        # the laser head (at the travel's low end): a random walk of 0.4 ppm per sqrt(h) over the
        # beam path, from the reference run on
        refraction_ppm = 0.0
        last_t = None
        # air_compensation: the compensation frozen at the start of the reference run; the laser
        # head 150 mm beyond the travel's end away from the fixed end
        air = [a[0] for a in aux]
        air_frozen = interp(st, air, sim["run_times"][0]) if sim["run_times"] else air[0]
        far_positive = m["true_fixed_end_mm"] < m["travel_mm"][0]

        def air_beam_m(x):
            head = m["travel_mm"][1] + 150.0 if far_positive else m["travel_mm"][0] - 150.0
            return abs(head - x) / 1000.0
        for (tm, run, x, thermal) in sim["measurements"]:
            if wide and run > 0:
                refraction_ppm += rnd.gauss(0.0, 0.4 * math.sqrt(max(0.0, tm - last_t) / 3600.0)) if last_t is not None else 0.0
                last_t = tm
            elif wide:
                last_t = tm
            drift = refraction_ppm * 1e-6 * (x - m["travel_mm"][0]) * 1e3
            if fault == "air_compensation":
                drift += 0.93 * size * air_beam_m(x) * (interp(st, air, tm) - air_frozen)
            noise = rnd.gauss(0.0, 0.3 if wide else 0.25)
            fh.write("%.1f,%d,%.3f,%.3f\n" % (tm, run, x, pitch(x) + thermal + drift + noise))

    with open(os.path.join(out, "events.csv"), "w", encoding="utf-8", newline="\n") as fh:
        fh.write("time_s,label\n")
        for (te, label) in sim["events"]:
            if te <= total_s:
                fh.write("%.1f,%s\n" % (te, label))

    started = args.started
    screw = {
        "length_m": m["length_m"], "diameter_m": m["diameter_m"], "nut_length_m": m["nut_length_m"],
        "fixed_bearing_length_m": m["fixed_bearing_length_m"], "density_kg_m3": m["density_kg_m3"],
        "specific_heat_J_kgK": m["specific_heat_J_kgK"], "expansion_per_K": m["expansion_per_K"],
        "conductivity_W_mK": None, "mounting": "fixed-free",
    }
    channels = []
    for (cid, kind, sensor, unit, role, location, _) in CHANNELS:
        ch = {"id": cid, "kind": kind, "sensor": sensor, "unit": unit, "location": location, "role": role}
        if role == "fixed_bearing":
            ch["screw_position_m"] = 0.0
        if role == "free_bearing":
            ch["screw_position_m"] = m["length_m"]
        channels.append(ch)
    manifest = {
        "format": "thermal-error-bundle",
        "version": 1,
        "session": {"name": args.name or ("othersim %s seed %d" % (args.effect, args.seed)),
                    "started": started, "operator": "othersim.py",
                    "notes": "independent simulator (scripts/othersim.py), %g h, duty %s" % (args.hours, args.duty)},
        "machine": {"name": "two-axis grinding slide (othersim)", "axis": "Y", "loop": "semi-closed",
                    "screw": screw, "fixed_end_position_mm": m["drawing_fixed_end_mm"],
                    "travel_mm": list(m["travel_mm"])},
        "channels": channels,
        "interferometer": {"file": "interferometer.csv", "unit": "um", "reference_run": 0},
        "events": "events.csv",
        "othersim": {"generator": "scripts/othersim.py", "grid_cells": sim["cells"], "wide": bool(getattr(args, "wide", False)), "step_s": sim["dt"],
                    "sensor_fault": fault, "fault_size": size},
    }
    with open(os.path.join(out, "manifest.json"), "w", encoding="utf-8", newline="\n") as fh:
        json.dump(manifest, fh, indent=2)
        fh.write("\n")


# ----------------------------------------------------------------------------------------------
# Self-test of the physics

def selftest():
    ok = True

    def check(name, value, expected, tol):
        nonlocal ok
        good = abs(value - expected) <= tol
        ok = ok and good
        print("%-58s %12.6g  expected %12.6g  (tol %g)  %s" % (name, value, expected, tol, "ok" if good else "FAIL"))

    m = nominal_machine()
    L, D, LB = m["length_m"], m["diameter_m"], m["fixed_bearing_length_m"]
    lam, rho, c = m["conductivity_W_mK"], m["density_kg_m3"], m["specific_heat_J_kgK"]

    # 1. Steady state without motion: heat Q into [0, LB] (no convection there), convection h
    # on the rest of the surface and on the free-end face, adiabatic fixed end. Analytic fin:
    #   [0,a]: theta = C1 - q' x^2 / (2 lam A)           (q' = Q / a)
    #   [a,L]: theta = C2 (cosh m(L-x) + beta sinh m(L-x)),  m^2 = h P / (lam A), beta = h / (lam m)
    # matched in value and flux at x = a.
    for cells in (64, 128):
        screw = Screw(L, D, cells, rho, c, lam, 20.0)
        h, Q = 20.0, 5.0
        A, P = screw.area, screw.perimeter
        mm = math.sqrt(h * P / (lam * A))
        beta = h / (lam * mm)
        a = LB
        qp = Q / a
        # flux continuity: -lam A theta'(a) = q' a = Q (all heat passes x=a)
        # theta'(a) on the right = -C2 m (sinh m(L-a) + beta cosh m(L-a))
        C2 = Q / (lam * A * mm * (math.sinh(mm * (L - a)) + beta * math.cosh(mm * (L - a))))
        theta_a = C2 * (math.cosh(mm * (L - a)) + beta * math.sinh(mm * (L - a)))
        C1 = theta_a + qp * a * a / (2.0 * lam * A)

        def analytic(x):
            if x <= a:
                return C1 - qp * x * x / (2.0 * lam * A)
            return C2 * (math.cosh(mm * (L - x)) + beta * math.sinh(mm * (L - x)))

        q = [0.0] * cells
        exposed = [1.0] * cells
        for i, w in screw.overlap(0.0, a):
            q[i] += Q * w / a
            exposed[i] -= w / screw.dx
        dt = 0.9 * screw.stable_step(h)
        for _ in range(int(6 * 3600 / dt)):
            screw.step(dt, q, exposed, h, 20.0)
        err = max(abs(screw.T[i] - 20.0 - analytic((i + 0.5) * screw.dx)) for i in range(cells))
        peak = analytic(0.0)
        check("steady fin, %d cells: max |T - analytic| / peak rise" % cells, err / peak, 0.0, 0.03 if cells == 64 else 0.01)
        # energy balance at steady state: Q = convection out
        out = sum(h * P * screw.dx * exposed[i] * (screw.T[i] - 20.0) for i in range(cells)) + h * A * (screw.T[-1] - 20.0)
        check("steady fin, %d cells: convection out / heat in" % cells, out / Q, 1.0, 1e-3)

    # 2. Energy conservation without convection: stored heat = injected heat (moving source)
    screw = Screw(L, D, 64, rho, c, lam, 20.0)
    dt = 2.0
    injected = 0.0
    for k in range(3000):
        s = 0.2 + 0.6 * abs(math.sin(k * 0.05))
        q = [0.0] * 64
        for i, w in screw.overlap(s - 0.075, s + 0.075):
            q[i] += 6.0 * w / 0.15
        for i, w in screw.overlap(0.0, LB):
            q[i] += 4.0 * w / LB
        screw.step(dt, q, [1.0] * 64, 0.0, 20.0)
        injected += sum(q) * dt
    check("adiabatic screw: stored energy / injected energy", screw.energy(20.0) / injected, 1.0, 1e-9)

    # 3. Lumped cooling: uniform screw, convection only, decays with tau = rho c A / (h (P + A/L))
    screw = Screw(L, D, 64, rho, c, lam, 25.0)
    h = 25.0
    tau = rho * c * screw.area * L / (h * (screw.perimeter * L + screw.area))
    dt = 2.0
    steps = int(1800 / dt)
    for _ in range(steps):
        screw.step(dt, [0.0] * 64, [1.0] * 64, h, 20.0)
    mean = sum(screw.T) / 64 - 20.0
    check("uniform cooling after 30 min: mean rise (K)", mean, 5.0 * math.exp(-steps * dt / tau), 0.01)

    # 4. Expansion integral and the P_f convention: uniform rise dT gives alpha dT (X - P_f) at X
    screw = Screw(L, D, 64, rho, c, lam, 20.0)
    screw.T = [23.0] * 64
    pf = m["true_fixed_end_mm"]
    for x in (0.0, 333.3, 700.0):
        got = screw.expansion_m((x - pf) / 1000.0, 20.0, m["expansion_per_K"]) * 1e6
        check("uniform +3 K: thermal error at X=%g mm (um)" % x, got, m["expansion_per_K"] * 3.0 * (x - pf) * 1e3, 1e-9)
    mp = mirror_machine(m)
    ns = argparse.Namespace(effect="none", seed=3, hours=0.5, dt=2.0, duty="random", targets=4, interval_min=10.0,
                            ambient_start=20.0, started="2026-11-20T08:00:00Z", name="", out="")
    sim_n = simulate(ns, m)
    sim_p = simulate(ns, mp)
    # mirrored machine, mirrored duty: the nut sits at the same screw sections, so the errors at
    # mirrored targets are equal and opposite (eq. 15 vs eq. 16 of the paper)
    pairs = list(zip(sim_n["measurements"], sim_p["measurements"]))
    worst = max(abs(a[3] + b[3]) for a, b in pairs) if pairs else 1.0
    check("P_f > travel: error = -(error of the mirrored machine) (um)", worst, 0.0, 1e-6)
    check("uniform +3 K: probe elongation (um)", screw.expansion_m(L, 20.0, m["expansion_per_K"]) * 1e6,
          m["expansion_per_K"] * 3.0 * L * 1e6, 1e-9)

    # 5. Whole simulation: the far interferometer target is never past the probe's elongation in
    # a warming screw, and the probe matches the expansion integral at the end.
    ns = argparse.Namespace(effect="none", seed=3, hours=1.0, dt=2.0, duty="random", targets=8, interval_min=20.0,
                            ambient_start=20.0, started="2026-11-20T08:00:00Z", name="", out="")
    sim = simulate(ns, m)
    far = [meas for meas in sim["measurements"] if abs(meas[2] - 685.0) < 1e-6]
    probe_end = sim["probe"][-1]
    check("1 h run: probe at end = alpha * integral over the screw (um)", probe_end,
          sim["screw"].expansion_m(L, 20.0, m["expansion_per_K"]) * 1e6, 1e-9)
    check("1 h run: far target error <= probe elongation (0 = true)",
          0.0 if all(meas[3] <= interp(sim["state_t"], sim["probe"], meas[0]) + 1e-6 for meas in far) else 1.0, 0.0, 0.0)
    # 6. --wide: the coarser grid is used and the probe still reads the expansion integral.
    ns = argparse.Namespace(effect="none", seed=3, hours=1.0, dt=2.0, duty="random", targets=8, interval_min=20.0,
                            ambient_start=20.0, started="2026-11-20T08:00:00Z", name="", out="", wide=True)
    sim = simulate(ns, m)
    check("--wide 1 h run: grid cells", sim["cells"], 40, 0)
    check("--wide 1 h run: probe at end = alpha * integral over the screw (um)", sim["probe"][-1],
          sim["screw"].expansion_m(L, 20.0, m["expansion_per_K"]) * 1e6, 1e-9)
    print("selftest", "passed" if ok else "FAILED")
    return 0 if ok else 1


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--effect", choices=EFFECTS, default="none")
    p.add_argument("--seed", type=int, default=1, help="duty cycle, ambient and noise seed")
    p.add_argument("--machine-seed", type=int, default=0, help="spread of the machine's laws (0 = nominal)")
    p.add_argument("--fixed-end", choices=("negative", "positive"), default="negative",
                   help="side of the travel the screw's fixed end is on (P_f < travel or P_f > travel)")
    p.add_argument("--hours", type=float, default=4.0)
    p.add_argument("--out", help="bundle directory to write")
    p.add_argument("--duty", choices=("random", "table2"), default="random")
    p.add_argument("--dt", type=float, default=3.0, help="explicit step, s (cut to the stability limit)")
    p.add_argument("--targets", type=int, default=8)
    p.add_argument("--interval-min", type=float, default=20.0, help="interferometer run interval")
    p.add_argument("--ambient-start", type=float, default=None, help="hall temperature at t = 0 (degC)")
    p.add_argument("--started", default=None, help="ISO start time")
    p.add_argument("--name", default="")
    p.add_argument("--wide", action="store_true",
                   help="widen the differences from DriftLab's rig: grid, housing body, noise and sampling (see above)")
    p.add_argument("--hall-trend", type=float, default=None,
                   help="the hall temperature's linear trend, K/h (default: seeded, -0.15..0.15)")
    p.add_argument("--sensor-fault", choices=SENSOR_FAULTS, default="none",
                   help="a measurement-chain fault (see above); the machine is unchanged")
    p.add_argument("--fault-size", type=float, default=1.0, help="scale of the sensor fault's law")
    p.add_argument("--selftest", action="store_true", help="run the physics checks and exit")
    args = p.parse_args(argv)
    if args.selftest:
        return selftest()
    if not args.out:
        p.error("--out is required")
    if args.targets < 2:
        p.error("--targets must be at least 2")
    r = random.Random(args.seed * 17 + 1)
    if args.ambient_start is None:
        args.ambient_start = round(r.uniform(19.5, 22.0), 2)
    if args.started is None:
        args.started = "2026-11-%02dT%02d:%02d:00Z" % (10 + args.seed % 18, 6 + args.seed % 5, (args.seed * 7) % 60)
    m = nominal_machine()
    if args.fixed_end == "positive":
        m = mirror_machine(m)
    m = perturb_machine(m, args.machine_seed)
    sim = simulate(args, m)
    write_bundle(args, m, sim)
    print("othersim: %s (%s, sensor fault %s, seed %d, %g h, step %.2f s, %d interferometer points)"
          % (args.out, args.effect, args.sensor_fault, args.seed, args.hours, sim["dt"], len(sim["measurements"])),
          file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
