#!/usr/bin/python3
"""Seed 002 sensitivity study (issue 37): which modelling choice explains the seed's magnitudes.

Builds scene variants from the three seed002 cases (cases/seed002_power_loss, seed002_steady,
seed002_startup) by substituting named parameters in one train of the case's .prm, runs gearkit
on each (one at a time), reads results.h5 and prints one table per case plus a few derived
numbers (energy budgets, spectral bounds). Every variant says what it changes and why.

usage: seed002_sensitivity.py OUTDIR [--quick] [--gearkit PATH] [--cases power_loss,steady,startup]
                              [--only NAME[,NAME...]] [--list]

OUTDIR      scenes, logs, gearkit result folders and summary.json go here (never the repository)
--quick     a subset (the discriminating variants) with shortened runs: steady 1.5 s (spectrum
            from 0.5 s: 1 Hz bins, too coarse for the +-1.993 Hz sidebands), start-up 50 ms
--gearkit   the executable (default: build/gearkit of this repository; copy it first when the
            build directory is being rebuilt)
--cases     which cases to run
--only      only these variants (names as --list prints them)

Reading the tables: d/c = drive/coast impacts (first touches of a flank side after separation),
t1 = first contact, Fmax = the largest force located by the integrator, E_rel = the kinetic
energy of the initial speeds' motion relative to the rigid train (the energy an undamped,
frictionless train can put into impacts), F(E_rel) = the force of one tooth pair that takes all
of it: K^(1/(e+1)) ((e+1) E_rel)^(e/(e+1)). Spectra: single-sided amplitude of |F| (Hann,
coherent gain divided out); 2 mean|F| bounds every line of a non-negative force.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time

import h5py
import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CASES = os.path.join(REPO, 'cases')

# ---------------------------------------------------------------------------------------------
# .prm text editing (deal.II ParameterHandler syntax: subsection NAME ... end, set key = value)


def parse_line(line):
    """('subsection', name) | ('end', None) | ('set', key) | (None, None) for one .prm line."""
    s = line.split('#', 1)[0].strip()
    if s.startswith('subsection '):
        return 'subsection', s[len('subsection '):].strip()
    if s == 'end':
        return 'end', None
    if s.startswith('set ') and '=' in s:
        return 'set', s[4:].split('=', 1)[0].strip()
    return None, None


class Prm:
    def __init__(self, text):
        self.lines = text.splitlines()

    def text(self):
        return '\n'.join(self.lines) + '\n'

    def block(self, path):
        """(first, last) line indices of subsection path (its 'subsection' and 'end' lines)."""
        lo, hi, depth0 = 0, len(self.lines) - 1, 0
        for name in path:
            depth, found = 0, None
            i = lo + (1 if depth0 else 0)
            while i < hi + (0 if depth0 else 1):
                kind, value = parse_line(self.lines[i])
                if kind == 'subsection':
                    if depth == 0 and value == name and found is None:
                        found = i
                    depth += 1
                elif kind == 'end':
                    depth -= 1
                    if depth == 0 and found is not None:
                        break
                i += 1
            if found is None:
                raise KeyError('subsection ' + '/'.join(path) + ' not found')
            lo, hi, depth0 = found, i, 1
        return lo, hi

    def set(self, path, key, value):
        """Replaces set key = ... among path's direct entries, or adds it."""
        lo, hi = self.block(path) if path else (-1, len(self.lines))
        depth = 0
        for i in range(lo + 1, hi):
            kind, name = parse_line(self.lines[i])
            if kind == 'subsection':
                depth += 1
            elif kind == 'end':
                depth -= 1
            elif kind == 'set' and depth == 0 and name == key:
                indent = self.lines[i][:len(self.lines[i]) - len(self.lines[i].lstrip())]
                self.lines[i] = '%sset %s = %s' % (indent, key, value)
                return
        indent = ' ' * (2 * len(path))
        self.lines.insert(lo + 1, '%sset %s = %s' % (indent, key, value))

    def drop(self, path):
        lo, hi = self.block(path)
        del self.lines[lo:hi + 1]

    def copy(self, path, new_name):
        """Duplicates subsection path right after itself under new_name."""
        lo, hi = self.block(path)
        dup = list(self.lines[lo:hi + 1])
        dup[0] = dup[0].replace('subsection ' + path[-1], 'subsection ' + new_name, 1)
        self.lines[hi + 1:hi + 1] = dup

    def children(self, path):
        lo, hi = self.block(path)
        names, depth = [], 0
        for i in range(lo + 1, hi):
            kind, name = parse_line(self.lines[i])
            if kind == 'subsection':
                if depth == 0:
                    names.append(name)
                depth += 1
            elif kind == 'end':
                depth -= 1
        return names


# ---------------------------------------------------------------------------------------------
# the seed's numbers and the variants

SEED_K = 2e7          # N/mm^e (Table 2)
SEED_E = 2.2
K_SI = SEED_K / 1e-3 ** SEED_E   # N/m^2.2: 7.96e13
RATED = 149.123       # N m at the input (section 4)
R1, R2 = 60.0 / 17.0, 72.0 / 19.0
W_IN = 167.5          # rad/s
W_INT = W_IN / R1     # 47.458
W_OUT = W_INT / R2    # 12.5237

# (path below Train/<train>, key, value)
C0 = [(['Contact'], 'damping', '0'), (['Contact'], 'damping unit', 'N s/mm')]


def c(value):
    return [(['Contact'], 'damping', value), (['Contact'], 'damping unit', 'N s/mm')]


NOFRICTION = [(['Bodies', b], 'torque', '0') for b in ('input', 'intermediate', 'output')]
SEED_SPEEDS = [(['Bodies', 'input'], 'initial speed', '167.5'),
               (['Bodies', 'intermediate'], 'initial speed', 'kinematic'),
               (['Bodies', 'output'], 'initial speed', '12.5')]
SEED_SPEEDS_735 = [(['Bodies', 'input'], 'initial speed', '167.5'),
                   (['Bodies', 'intermediate'], 'initial speed', '73.5'),
                   (['Bodies', 'output'], 'initial speed', '12.5')]
LINEAR = [(['Contact'], 'exponent', '1')]          # 2e7 N/mm as a linear spring
# undamped rattles and the -73.5 rad/s start press the soft contact 100-200 um deep: the tooth
# pair curves must reach beyond that (the case's 200 um would let pairs leave them still touching)
DEEP = [(['Contact'], 'tooth pair recess', '500')]
LIGHT_OUTPUT = [(['Bodies', 'output'], 'shaft inertia', '0.22')]  # 0.54 kg m^2: 10 x intermediate


def torques(scale, bodies=('input', 'intermediate', 'output')):
    full = {'input': -RATED, 'intermediate': -RATED * R1, 'output': -RATED * R1 * R2}
    return [(['Bodies', b], 'torque', '%.6g' % (0.01 * scale * full[b])) for b in bodies]


def V(name, case, train, changes, why, quick=False, extra=None):
    return dict(name=name, case=case, train=train, changes=changes, why=why, quick=quick,
                extra=extra or [])


# eccentric tooth on gear A (the seed's section 2: "an eccentric tooth on Gear A ... 0.0045 mm")
def add_gear_a_eccentric(prm, train, flank, offset):
    prm.copy(['Flanks', 'stage1'], 'stage1_eccA')
    lo, _ = prm.block(['Flanks', 'stage1_eccA', 'Pinion'])
    prm.lines[lo + 1:lo + 1] = [
        '      subsection Deviations', '        set eccentric tooth        = 3',
        '        set eccentric tooth flank  = %s' % flank,
        '        set eccentric tooth offset = %s' % offset, '      end']
    prm.set(['Scene'], 'pairs', prm_get(prm, ['Scene'], 'pairs') + ', stage1_eccA')
    prm.set(['Train', train, 'Meshes', 'stage1'], 'pair', 'stage1_eccA')


def prm_get(prm, path, key):
    lo, hi = prm.block(path)
    for i in range(lo + 1, hi):
        kind, name = parse_line(prm.lines[i])
        if kind == 'set' and name == key:
            return prm.lines[i].split('#', 1)[0].split('=', 1)[1].strip()
    raise KeyError(key)


VARIANTS = [
    # --- power loss: perfect train, 50 ms
    V('pl_case', 'power_loss', 'perfect', [], 'the case: c 10 N s/mm, 1 % friction, exact '
      'kinematic speeds', quick=True),
    V('pl_c0', 'power_loss', 'perfect', C0, 'no damping (the seed: "as near to zero as '
      'possible")', quick=True),
    V('pl_c4000', 'power_loss', 'perfect', c('4000'), "seed 001's 2e-2 % of K = 4000 N s/mm"),
    V('pl_c0_nofric', 'power_loss', 'perfect', C0 + NOFRICTION, 'no damping, frictionless '
      'bearings (the seed, section 3), exact speeds'),
    V('pl_seed_c0', 'power_loss', 'perfect', C0 + NOFRICTION + SEED_SPEEDS, 'frictionless, '
      'no damping, the seed\'s speeds 167.5 / (47.458 as its Fig. 4b) / 12.5 rad/s', quick=True),
    V('pl_seed_c10', 'power_loss', 'perfect', NOFRICTION + SEED_SPEEDS, 'as pl_seed_c0 with '
      'c 10 N s/mm'),
    V('pl_seed_c100', 'power_loss', 'perfect', c('100') + NOFRICTION + SEED_SPEEDS,
      'as pl_seed_c0 with c 100 N s/mm'),
    V('pl_seed_c1000', 'power_loss', 'perfect', c('1000') + NOFRICTION + SEED_SPEEDS,
      'as pl_seed_c0 with c 1000 N s/mm'),
    V('pl_seed_c4000', 'power_loss', 'perfect', c('4000') + NOFRICTION + SEED_SPEEDS,
      'as pl_seed_c0 with c 4000 N s/mm', quick=True),
    V('pl_seed_c4000_d', 'power_loss', 'perfect', c('4000') + NOFRICTION + SEED_SPEEDS
      + [(['Contact'], 'penetration depth', '1e-4')], 'as pl_seed_c4000, penetration depth '
      '1e-7 m (1e-4 mm) instead of 1e-7 mm'),
    V('pl_seed_lin', 'power_loss', 'perfect', C0 + NOFRICTION + SEED_SPEEDS + LINEAR,
      'as pl_seed_c0, K read as 2e7 N/mm linear (e = 1)', quick=True),
    V('pl_seed_light', 'power_loss', 'perfect', C0 + NOFRICTION + SEED_SPEEDS + LIGHT_OUTPUT,
      'as pl_seed_c0, output 0.54 kg m^2 (just 10 x the intermediate)'),
    V('pl_seed_fric', 'power_loss', 'perfect', C0 + SEED_SPEEDS, 'as pl_seed_c0 with the 1 % '
      'friction'),
    V('pl_735_c0', 'power_loss', 'perfect', C0 + NOFRICTION + SEED_SPEEDS_735 + DEEP,
      'the seed\'s text speeds 167.5 / 73.5 / 12.5, frictionless, no damping', quick=True),
    V('pl_735_c10', 'power_loss', 'perfect', SEED_SPEEDS_735 + DEEP,
      'the text speeds with the case\'s c 10 N s/mm and 1 % friction'),
    # --- steady: input held (stage 1 spectrum, Fig. 10a), output held (stage 2, Fig. 10b)
    V('st_in_case', 'steady', 'perfect_input', [], 'the case (c 10 N s/mm, 1 % torques)',
      quick=True),
    V('st_in_c0', 'steady', 'perfect_input', C0 + DEEP, 'no damping', quick=True),
    V('st_in_c0p1', 'steady', 'perfect_input', c('0.1') + DEEP, 'c 0.1 N s/mm'),
    V('st_in_c0p3', 'steady', 'perfect_input', c('0.3'), 'c 0.3 N s/mm'),
    V('st_in_c1', 'steady', 'perfect_input', c('1'), 'c 1 N s/mm', quick=True),
    V('st_in_c4000', 'steady', 'perfect_input', c('4000'), "seed 001's reading (the case's "
      'damper_input)'),
    V('st_in_c20000', 'steady', 'perfect_input', c('20000'), 'the seed\'s "0.1 % of K" = 2e4 '
      'N s/mm'),
    V('st_in_t10', 'steady', 'perfect_input', torques(10, ('intermediate', 'output')),
      '10 % of the rated torques instead of 1 %', quick=True),
    V('st_in_lin', 'steady', 'perfect_input', LINEAR, 'K read as 2e7 N/mm linear (e = 1)'),
    V('st_in_light', 'steady', 'perfect_input', LIGHT_OUTPUT,
      'output 0.54 kg m^2 (the crank-slider\'s inertia variation 38 x larger against it)',
      quick=True),
    V('st_out_case', 'steady', 'perfect_output', [], 'the case (output held)', quick=True),
    V('st_out_c0', 'steady', 'perfect_output', C0 + DEEP, 'no damping', quick=True),
    V('st_out_c100', 'steady', 'perfect_output', c('100'), 'c 100 N s/mm'),
    V('st_out_t5in', 'steady', 'perfect_output', torques(5, ('input',)), 'input resisting 5 % '
      '(7.46 N m) instead of 1 %'),
    V('st_out_t10', 'steady', 'perfect_output', torques(10, ('input', 'intermediate')),
      '10 % of the rated torques', quick=True),
    V('st_out_eccA', 'steady', 'perfect_output', [], 'gear A tooth 3 coast flank 4.5 um proud '
      '(the seed\'s "eccentric tooth on Gear A ... 0.0045 mm")', quick=True,
      extra=[('eccA', ('coast', '4.5'))]),
    V('st_out_eccA45', 'steady', 'perfect_output', [], 'as st_out_eccA with 45 um (the seed\'s '
      'figure label)', extra=[('eccA', ('coast', '45'))]),
    # --- start-up: the first 50 ms (the seed's Figures 7, 8 span 0-40 ms)
    V('su_case', 'startup', 'perfect', [], 'the case (c 10 N s/mm)', quick=True),
    V('su_c0', 'startup', 'perfect', C0, 'no damping', quick=True),
    V('su_c4000', 'startup', 'perfect', c('4000'), "seed 001's reading"),
    V('su_lin', 'startup', 'perfect', LINEAR, 'K read as 2e7 N/mm linear (e = 1)'),
    V('su_light', 'startup', 'perfect', LIGHT_OUTPUT, 'output 0.54 kg m^2'),
    V('su_case_700ms', 'startup', 'perfect', [], 'the case to 0.7 s (spectrogram at 0.6 s)',
      extra=[('duration', '0.7')]),
    V('su_c1_700ms', 'startup', 'perfect', c('1'), 'c 1 N s/mm to 0.7 s',
      extra=[('duration', '0.7')]),
    V('su_c0_700ms', 'startup', 'perfect', C0 + DEEP, 'no damping to 0.7 s',
      extra=[('duration', '0.7')]),
]


def build_scene(v, quick):
    path = os.path.join(CASES, 'seed002_' + v['case'], 'seed002_%s.prm' % v['case'])
    with open(path) as f:
        prm = Prm(f.read())
    for t in prm.children(['Train']):
        if t != v['train']:
            prm.drop(['Train', t])
    prm.set(['Scene'], 'trains', v['train'])
    base = ['Train', v['train']]
    for sub, key, value in v['changes']:
        prm.set(base + sub, key, value)
    for kind, arg in v['extra']:
        if kind == 'eccA':
            add_gear_a_eccentric(prm, v['train'], *arg)
    if v['case'] == 'power_loss':
        # the spectrum over the whole run: gearkit 0.x writes NaN line frequencies (and refuses
        # the results) when a mesh's force is zero over the whole spectrum window (its default,
        # the second half: stage 2 can be apart from 25 to 50 ms)
        prm.set(base + ['Spectrum'], 'start', '1e-5')
    if v['case'] == 'steady' and quick:
        prm.set(base + ['Run'], 'duration', '1.5')
        prm.set(base + ['Spectrum'], 'start', '0.5')
    duration = dict(v['extra']).get('duration')
    if v['case'] == 'startup' and duration:
        prm.set(base + ['Run'], 'duration', duration)
        prm.set(base + ['Spectrum'], 'start', '%g' % (float(duration) / 2))
    elif v['case'] == 'startup':
        prm.set(base + ['Run'], 'duration', '0.05')
        prm.set(base + ['Spectrum'], 'start', '0.01')
        prm.set(base + ['Spectrum'], 'spectrogram window', '10')
    return prm.text()


# ---------------------------------------------------------------------------------------------
# results


def scalar(g, name, default=float('nan')):
    return float(g[name][()]) if name in g else default


def relative_energy(tg):
    """Kinetic energy of the initial speeds relative to the rigid train with the same momentum."""
    J = tg['inertia'][()]
    w = tg['initial_speed'][()]
    k = np.array([1.0, 1.0 / R1, 1.0 / (R1 * R2)])
    E0 = 0.5 * np.sum(J * w * w)
    p = np.sum(J * w * k)
    return E0 - 0.5 * p * p / np.sum(J * k * k)


def force_bound(E, K, e):
    return K ** (1 / (e + 1)) * ((e + 1) * E) ** (e / (e + 1)) if E > 0 else 0.0


def law_of(v):
    K, e = K_SI, SEED_E
    for _, key, value in v['changes']:
        if key == 'exponent':
            e = float(value)
        if key == 'stiffness':
            K = float(value) / 1e-3 ** e
    if e != SEED_E and not any(k == 'stiffness' for _, k, _ in v['changes']):
        K = SEED_K / 1e-3 ** e
    return K, e


def mesh_summary(tg, m, t0=None, t1=None):
    g = tg['meshes'][m]
    out = dict(impacts=int(scalar(g, 'impacts')), drive=int(scalar(g, 'drive_impacts')),
               coast=int(scalar(g, 'coast_impacts')), first_ms=1e3 * scalar(g, 'first_contact'),
               fmax=scalar(g, 'max_force'), pen_um=1e6 * scalar(g, 'max_penetration'))
    if 'contacts' in g and 'peak' in g['contacts']:
        peak = g['contacts/peak'][()]
        pt = g['contacts/peak_time'][()]
        side = g['contacts/side'][()]
        out['first_peaks'] = [round(float(x)) for x in peak[:3]]
        if t0 is not None:
            sel = (pt >= t0) & (pt <= t1)
            out['fmax_window'] = float(peak[sel].max()) if sel.any() else 0.0
            out['contacts_window'] = int(sel.sum())
            out['sides_window'] = sorted(set(int(s) for s in side[sel]))
    return out


def spectrum_summary(tg, m):
    g = tg['meshes'][m]
    L = g['spectrum/lines']
    h, s, sb = L['harmonic'][()], L['shaft'][()], L['sideband'][()]
    amp, found, floor = L['amplitude'][()], L['found'][()], L['floor'][()]
    t = tg['time'][()]
    start = scalar(g['spectrum'], 'start')
    F = np.abs(g['force'][()][t >= start])
    res = dict(mean=float(F.mean()), res=scalar(g['spectrum'], 'resolution'))
    # a run still building up (undamped rattle) is not a steady state: first against last second
    tw = t[t >= start]
    res['mean_first_s'] = float(F[tw < tw[0] + 1.0].mean())
    res['mean_last_s'] = float(F[tw > tw[-1] - 1.0].mean())
    res['gmf'] = [float(amp[(h == k) & (s < 0) & (sb == 0)][0]) for k in range(1, 5)]
    res['floor'] = float(np.median(floor))
    for shaft, label in ((0, 'sb_in'), (2, 'sb_out')):
        sel = (h >= 1) & (s == shaft) & (np.abs(sb) == 1)
        # lines closer to their GMF than the spectrum resolves are not searched (quick runs)
        res[label] = float(amp[sel].max()) if sel.any() else float('nan')
        res[label + '_found'] = int(found[sel].sum())
        res[label + '_of'] = int(sel.sum())
    return res


def startup_mesh(tg, m):
    out = mesh_summary(tg, m, 0.0, 0.040)
    t = tg['time'][()]
    F = np.abs(tg['meshes'][m]['force'][()])
    out['fmax_window'] = max(out.get('fmax_window', 0.0), float(F[t <= 0.040].max()))
    return out


def rattle_criterion(tg):
    """Stage 1 with the output held: the input pinion's free deceleration under its resisting
    torque against the intermediate's angular acceleration, both along stage 1's line of
    action [m/s^2]."""
    J = tg['inertia'][()]
    t = tg['time'][()]
    w = tg['speed'][()]
    sel = t >= 0.5 * t[-1]
    a_int = np.gradient(w[1][sel], t[sel])
    rb1 = scalar(tg['meshes/stage1'], 'pinion_base_radius')
    rb2 = scalar(tg['meshes/stage1'], 'gear_base_radius')
    return rb2 * float(np.percentile(np.abs(a_int), 99)), rb1, J[0]


def analyse(v, h5):
    with h5py.File(h5, 'r') as f:
        tg = f['train'][v['train']]
        row = dict(energy_error=scalar(tg, 'energy_error'), seconds=scalar(tg, 'seconds'),
                   initial_speed=[float(x) for x in tg['initial_speed'][()]],
                   inertia=[float(x) for x in tg['inertia'][()]])
        if v['case'] == 'power_loss':
            K, e = law_of(v)
            row['E_rel'] = float(relative_energy(tg))
            row['F_bound'] = force_bound(row['E_rel'], K, e)
            for m in ('stage1', 'stage2'):
                row[m] = mesh_summary(tg, m, 0.010, 0.030)
        elif v['case'] == 'steady':
            for m in ('stage1', 'stage2'):
                row[m] = mesh_summary(tg, m)
                row[m].update(spectrum_summary(tg, m))
            if v['train'].endswith('output'):
                a, rb1, Jin = rattle_criterion(tg)
                row['a_int_los'] = a
                tin = [float(val) for sub, key, val in v['changes'] if sub == ['Bodies', 'input']
                       and key == 'torque']
                row['a_pinion_free'] = abs(tin[0] if tin else 0.01 * RATED) / Jin * rb1
        else:
            for m in ('stage1', 'stage2'):
                row[m] = startup_mesh(tg, m)
            t = tg['time'][()]
            if t[-1] >= 0.62:
                # the spectrogram slice at 600 ms: GMF1 line height and the force there
                sg = tg['spectrogram']
                ts, fr, A = sg['time'][()], sg['frequency'][()], sg['amplitude'][()]
                i = int(np.argmin(np.abs(ts - 0.6)))
                w = float(np.interp(ts[i], t, tg['speed'][()][0]))
                gmf = 17 * w / (2 * math.pi)
                band = np.abs(fr - gmf) < 0.05 * gmf
                row['gmf1_600'] = gmf
                row['gmf1_line_600'] = float(A[i][band].max())
                row['line_max_600'] = float(A[i][fr > 50].max())
                F = np.abs(tg['meshes/stage1/force'][()])
                sel = np.abs(t - ts[i]) <= 0.025
                row['f1_600'] = (float(F[sel].mean()), float(F[sel].max()))
    return row


# ---------------------------------------------------------------------------------------------
# tables


def fmt(x, unit=''):
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return '-'
    a = abs(x)
    if a >= 1e5:
        return '%.3g k%s' % (x / 1e3, unit) if a < 1e6 else '%.3g M%s' % (x / 1e6, unit)
    if a >= 1e4:
        return '%.1f k%s' % (x / 1e3, unit)
    if a >= 100:
        return '%.0f %s' % (x, unit)
    return '%.3g %s' % (x, unit)


def table(rows, head):
    widths = [max(len(str(r[i])) for r in [head] + rows) for i in range(len(head))]
    line = lambda r: '| ' + ' | '.join(str(x).ljust(w) for x, w in zip(r, widths)) + ' |'
    print(line(head))
    print('|' + '|'.join('-' * (w + 2) for w in widths) + '|')
    for r in rows:
        print(line(r))


def print_power_loss(results):
    rows = []
    for name, v, r in results:
        s1, s2 = r['stage1'], r['stage2']
        rows.append([name, '%.2f/%.2f/%.3f' % tuple(r['initial_speed']),
                     '%d/%d' % (s1['drive'], s1['coast']), '%.2f' % s1['first_ms'],
                     fmt(s1['fmax'], 'N'), '%d/%d' % (s2['drive'], s2['coast']),
                     '%.2f' % s2['first_ms'], fmt(s2['fmax'], 'N'),
                     '%d %s' % (s1.get('contacts_window', 0), sides(s1)),
                     '%d %s' % (s2.get('contacts_window', 0), sides(s2)),
                     '%.3g J' % r['E_rel'], fmt(r['F_bound'], 'N'), '%.0e' % r['energy_error']])
    print('\n## power loss (train perfect, 50 ms; seed: stage 2 first ~12 ms, stage 1 ~15 ms, '
          'stage 1 peaks ~40 kN double-sided, stage 2 <= ~700 N)\n')
    table(rows, ['variant', 'speeds in/int/out rad/s', 's1 d/c', 's1 t1 ms', 's1 Fmax',
                 's2 d/c', 's2 t1 ms', 's2 Fmax', 's1 10-30 ms', 's2 10-30 ms', 'E_rel',
                 'F(E_rel)', 'energy err'])


def sides(m):
    return '/'.join({1: 'd', -1: 'c'}[s] for s in m.get('sides_window', []))


def print_steady(results):
    rows = []
    for name, v, r in results:
        s = r['stage1'] if v['train'].endswith('input') else r['stage2']
        o = r['stage2'] if v['train'].endswith('input') else r['stage1']
        rows.append([name, 's1' if v['train'].endswith('input') else 's2',
                     '%d/%d' % (s['drive'], s['coast']),
                     '%.1f (%.0f..%.0f)' % (s['mean'], s['mean_first_s'], s['mean_last_s']),
                     ' '.join('%.1f' % a for a in s['gmf']), '%.2f' % s['floor'],
                     sideband(s, 'sb_in'), sideband(s, 'sb_out'),
                     '%d/%d' % (o['drive'], o['coast']), fmt(s['fmax'], 'N'),
                     '%.3g' % s['res']])
    print('\n## steady (spectrum of |F| of the held shaft\'s mesh; seed: lines of hundreds of N, '
          'below 1 kN; +-26.66 Hz around GMF2 "relatively large", +-1.993 Hz around GMF1 '
          '"relatively small")\n')
    table(rows, ['variant', 'mesh', 'd/c', 'mean|F| N (first..last s)', 'GMF x1..4 N', 'floor N',
                 '+-26.66 Hz max N (found)', '+-1.993 Hz max N (found)', 'other mesh d/c',
                 'Fmax', 'bin Hz'])
    for name, v, r in results:
        if 'a_int_los' in r:
            print('%s: stage 1 rattle criterion: intermediate acceleration on stage 1\'s line of '
                  'action (99th percentile) %.0f m/s^2 against the input pinion\'s free '
                  'deceleration %.0f m/s^2' % (name, r['a_int_los'], r['a_pinion_free']))


def sideband(s, label):
    if not s[label + '_of']:
        return 'not searched'
    return '%.2f (%d/%d)' % (s[label], s[label + '_found'], s[label + '_of'])


def print_startup(results):
    rows = []
    for name, v, r in results:
        s1, s2 = r['stage1'], r['stage2']
        rows.append([name, '%d/%d' % (s1['drive'], s1['coast']), '%.2f' % s1['first_ms'],
                     fmt(s1['fmax_window'], 'N'), '%d/%d' % (s2['drive'], s2['coast']),
                     '%.2f' % s2['first_ms'], fmt(s2['fmax_window'], 'N'),
                     '%.0f/%.0f' % (s1['pen_um'], s2['pen_um'])])
    print('\n## start-up (first 50 ms; seed Fig. 8: forces rising to ~7 kN by 40 ms, stage 2 '
          'larger)\n')
    table(rows, ['variant', 's1 d/c', 's1 t1 ms', 's1 Fmax 0-40 ms', 's2 d/c', 's2 t1 ms',
                 's2 Fmax 0-40 ms', 'penetration um s1/s2'])
    for name, v, r in results:
        if 'gmf1_600' in r:
            print('%s: at 600 ms GMF1 %.0f Hz, its spectrogram line %.0f N (largest line above '
                  '50 Hz %.0f N); stage 1 |F| in that window mean %.0f N, max %.0f N'
                  % (name, r['gmf1_600'], r['gmf1_line_600'], r['line_max_600'], *r['f1_600']))


def print_derived():
    """Numbers that need no run: the stiffness readings, the energy of a 40 kN impact, the
    start-up's speed ratio."""
    print('\n## derived (no run)\n')
    rb_b = 0.120 * math.cos(math.radians(20))   # gear B's base radius
    f1 = 0.01 * RATED * R1 * 2 / rb_b   # intermediate's and output's resisting torques
    print('stage 1 mean force at 1 %% of the rated torques (input held): %.1f N; every line of '
          'a single-sided |F| <= 2 mean = %.0f N' % (f1, 2 * f1))
    for label, K, e in (('2e7 N/mm^2.2 (gearkit)', K_SI, SEED_E), ('2e7 N/m^2.2', SEED_K, SEED_E),
                        ('2e7 N/mm, e = 1', SEED_K / 1e-3, 1.0)):
        d = (f1 / K) ** (1 / e)
        E40 = K * (40e3 / K) ** ((e + 1) / e) / (e + 1)
        print('K %-24s static penetration at %.0f N: %.3g um; one pair at 40 kN stores %.3g J'
              % (label, f1, d * 1e6, E40))
    ratio = lambda tau: ((0.35 - tau * (1 - math.exp(-0.35 / tau)))
                         / (0.6 - tau * (1 - math.exp(-0.6 / tau))))
    print('start-up from rest, T (1 - exp(-t/tau)), constant inertia, no load: w(350 ms) / '
          'w(600 ms) = %.3f at tau 100 ms, > %.3f for any tau; the seed (167.5 rad/s at 350 ms, '
          'GMF1 1653 Hz = %.1f rad/s at 600 ms): %.3f'
          % (ratio(0.1), (0.35 / 0.6) ** 2, 1653 * 2 * math.pi / 17,
             167.5 / (1653 * 2 * math.pi / 17)))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('outdir', nargs='?')
    ap.add_argument('--quick', action='store_true')
    ap.add_argument('--gearkit', default=os.path.join(REPO, 'build', 'gearkit'))
    ap.add_argument('--cases', default='power_loss,steady,startup')
    ap.add_argument('--only', default='')
    ap.add_argument('--list', action='store_true')
    a = ap.parse_args()
    cases = a.cases.split(',')
    only = set(x for x in a.only.split(',') if x)
    chosen = [v for v in VARIANTS if v['case'] in cases and (not a.quick or v['quick'])
              and (not only or v['name'] in only)]
    if a.list or not a.outdir:
        for v in VARIANTS:
            print('%-16s %-11s %-15s%s %s' % (v['name'], v['case'], v['train'],
                                             ' (quick)' if v['quick'] else '', v['why']))
        return 0 if a.list else 2
    out = os.path.abspath(a.outdir)
    if os.path.commonpath([out, REPO]) == REPO:
        sys.exit('seed002_sensitivity: write outside the repository (%s)' % out)
    for d in ('scenes', 'logs', 'runs'):
        os.makedirs(os.path.join(out, d), exist_ok=True)
    results = {c: [] for c in cases}
    summary = {}
    total = time.time()
    for v in chosen:
        scene = os.path.join(out, 'scenes', v['name'] + '.prm')
        with open(scene, 'w') as f:
            f.write(build_scene(v, a.quick))
        t = time.time()
        with open(os.path.join(out, 'logs', v['name'] + '.log'), 'w') as log:
            p = subprocess.run([a.gearkit, '--output-root', os.path.join(out, 'runs'), scene],
                               stdout=log, stderr=subprocess.STDOUT)
        wall = time.time() - t
        h5 = os.path.join(out, 'runs', v['name'], 'results.h5')
        if p.returncode not in (0, 3) or not os.path.exists(h5):
            print('%s: gearkit failed (exit %d): see %s' % (v['name'], p.returncode,
                  os.path.join(out, 'logs', v['name'] + '.log')), file=sys.stderr)
            continue
        try:
            row = analyse(v, h5)
        except (KeyError, ValueError, IndexError) as e:
            print('%s: results not understood (%s): %s' % (v['name'], e, h5), file=sys.stderr)
            continue
        row['wall'] = wall
        with open(os.path.join(out, 'logs', v['name'] + '.log')) as log:
            row['warnings'] = [l.strip() for l in log if 'WARNING' in l]
        print('%-16s %6.1f s  %s' % (v['name'], wall, v['why']), file=sys.stderr)
        results[v['case']].append((v['name'], v, row))
        summary[v['name']] = dict(case=v['case'], train=v['train'], why=v['why'],
                                  changes=v['changes'], **row)
    with open(os.path.join(out, 'summary.json'), 'w') as f:
        json.dump(summary, f, indent=1)
    if results.get('power_loss'):
        print_power_loss(results['power_loss'])
    if results.get('steady'):
        print_steady(results['steady'])
    if results.get('startup'):
        print_startup(results['startup'])
    print_derived()
    for name, row in summary.items():
        for w in row['warnings']:
            print('%s: %s' % (name, w))
    print('\n%d runs, %.0f s (%s)' % (len(summary), time.time() - total,
                                      'quick' if a.quick else 'full'))
    return 0


if __name__ == '__main__':
    sys.exit(main())
