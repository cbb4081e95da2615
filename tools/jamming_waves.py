#!/usr/bin/python3
"""Limit cycles and homoclinic orbits of the travelling-wave equations of the jamming model
(Kanehl (thesis) eq 6.13-6.14, fig 6.14 right, fig 6.18 a and c), in numpy.

For each wave speed c and fixed point phi0 (q = phi0 (v_ss(phi0) - c), eq 6.18) that is a focus
or node (eq 6.20), a trajectory starts next to the fixed point and is followed in the direction
of z in which the fixed point repels (forward from a source, backward from a sink) by RK4 in
steps dz = 0.01 for a length Z (default 300), many (c, phi0) at once (vectorised). It either
leaves the physical range (phi outside (0, 1), |v| > 10 or v = c: no cycle) or stays: then it
has converged to a closed orbit (a limit cycle; phi still varies over the last quarter of Z).
The cycles exist in an area (striped in fig 6.14 right) bounded by the Hopf line (eq 6.21),
where they are born, and by the homoclinic line, where the cycle grows into one of the saddles
and its period diverges. The area is thin (down to 1e-4 in phi0), so it is searched from each
Hopf point outwards on offsets 1e-5 2^j and the homoclinic edge refined on 16 points between
the last offset with a cycle and the next. Close to where the Hopf bifurcation turns from sub-
to supercritical the trajectories converge slowly (the thesis' dotted line): there Z may not
decide.

The same functions as src/engines/continuum/travelling_wave.cpp (fixed points, Jacobian,
limit_cycle), written again vectorised in numpy: the C++ ones are validated by
tests/validation/test_continuum_travelling_wave.cpp; this draws.
"""

import numpy as np

DZ = 0.01  # RK4 step in z: |lambda dz| < 1.2 up to xi ~ 300 (phi ~ 0.83 for mu = 1)


def _rhs(m, C, Q, p, v):
    return ((v - C) * p - Q) / m.D, (m.sigma - m.xi(p) * v) / (v - C)


def follow(m, C, P, Z, record=None, dz=DZ):
    """From (P + 1e-4, v_ss(P)) next to the fixed point P at speed C (arrays of one shape), in
    the direction of z in which it repels. Returns (alive, pmin, pmax) over the last quarter of
    Z, whether that range is the one of the third quarter (settled on a closed orbit) and,
    with record = index array, the trajectories of those points (z, phi, v)."""
    C, P = np.broadcast_arrays(np.asarray(C, float), np.asarray(P, float))
    V0 = m.vss(P)
    Q = P * (V0 - C)
    l1, l2 = m.jacobian_eigs(C, P)
    s = np.where((l1 + l2).real > 0, 1.0, -1.0)
    p, v = P + 1e-4, V0.copy()
    alive = np.ones(P.shape, bool)
    pmin, pmax = np.full(P.shape, np.inf), np.full(P.shape, -np.inf)
    qmin, qmax = pmin.copy(), pmax.copy()  # over the third quarter of Z
    n = int(round(Z / dz))
    rec = []
    with np.errstate(all="ignore"):
        for i in range(n):
            h = s * dz * alive
            k1 = _rhs(m, C, Q, p, v)
            k2 = _rhs(m, C, Q, p + h / 2 * k1[0], v + h / 2 * k1[1])
            k3 = _rhs(m, C, Q, p + h / 2 * k2[0], v + h / 2 * k2[1])
            k4 = _rhs(m, C, Q, p + h * k3[0], v + h * k3[1])
            p = p + h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
            v = v + h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
            ok = (p > 0) & (p < 1) & np.isfinite(v) & (np.abs(v - C) > 1e-6) & (np.abs(v) < 10)
            alive &= ok
            p = np.where(alive, p, P)
            v = np.where(alive, v, V0)
            if 4 * i >= 3 * n:
                pmin, pmax = np.minimum(pmin, p), np.maximum(pmax, p)
            elif 2 * i >= n:
                qmin, qmax = np.minimum(qmin, p), np.maximum(qmax, p)
            if record is not None:
                rec.append((p[record].copy(), v[record].copy()))
    # Converged: the range of phi is the same over the third and the last quarter of Z.
    settled = np.abs((pmax - pmin) - (qmax - qmin)) <= 1e-3 * (pmax - pmin)
    out = (alive, pmin, pmax, settled)
    if record is not None:
        ps = np.array([r[0] for r in rec])
        vs = np.array([r[1] for r in rec])
        out += (np.arange(1, n + 1)[:, None] * dz * s[record][None, :], ps, vs)
    return out


def has_cycle(m, C, P, Z):
    """Around the fixed point P at speed C (not a saddle): 1 a limit cycle (the trajectory from
    next to it stays in the physical range and settles on a closed orbit: its range of phi,
    > 1e-5, is the same to 1e-3 over the third and the last quarter of Z), 0 none (it leaves),
    -1 undecided within Z (still spiralling, or a saddle)."""
    l1, l2 = m.jacobian_eigs(C, P)
    saddle = (np.abs(l1.imag) == 0) & (l1.real * l2.real < 0)
    alive, pmin, pmax, settled = follow(m, C, P, Z)
    cycle = alive & settled & (pmax - pmin > 1e-5) & ~saddle
    return np.where(cycle, 1, np.where(alive | saddle, -1, 0))


def hopf_phi(m, c, lo, hi, n=4000):
    """The phi0 in (lo, hi) of the Hopf line at speed c (eq 6.21: trace zero, det > 0)."""
    p = np.linspace(lo, hi, n)
    f = (m.vss(p) - c) ** 2 - m.D * m.xi(p)
    out = []
    for i in np.nonzero(np.sign(f[:-1]) != np.sign(f[1:]))[0]:
        x = p[i] - f[i] * (p[i + 1] - p[i]) / (f[i + 1] - f[i])
        l1, l2 = m.jacobian_eigs(c, x)
        if abs(l1.imag) > 0 or abs(l1.real) < 1e-6:
            out.append(x)
    return out


def cycle_region(m, cs, lo, hi, Z):
    """The limit-cycle area next to each Hopf point: for every c and every phi_H of the Hopf
    line in (lo, hi), fixed points phi0 = phi_H +- 1e-5 2^j (j = 0..12, up to 0.04) are tried;
    the side where phi_H + 1e-5 (or - 1e-5) has a cycle is the area's side, and its far edge,
    the homoclinic line, lies between the last offset with a cycle and the next one, refined on
    16 points between them. Returns [(c, phi_H, phi_homoclinic or None if the area reaches
    0.04)], one per Hopf point with cycles on one side."""
    roots = [(c, ph) for c in cs for ph in hopf_phi(m, c, lo, hi)]
    if not roots:
        return []
    offs = 1e-5 * 2.0 ** np.arange(13)
    d = np.concatenate([-offs[::-1], offs])
    C = np.array([[c] * len(d) for c, _ in roots])
    P = np.array([[ph + x for x in d] for _, ph in roots])
    status = has_cycle(m, C, P, Z)
    n = len(offs)
    found = []  # (c, phi_H, side, last offset with a cycle, next offset (none there) or None)
    for (c, ph), row in zip(roots, status):
        for side, seq in ((+1, row[n:]), (-1, row[:n][::-1])):
            # the cycles next to the Hopf point (slow spirals there may leave the first
            # offsets undecided): from the first offset with a cycle to the first without
            yes = np.nonzero(seq == 1)[0]
            if len(yes) == 0 or (seq[:yes[0]] == 0).any():
                continue
            no = np.nonzero(seq[yes[0]:] == 0)[0]
            if len(no) == 0:
                found.append((c, ph, side, offs[yes[-1]], None))
            else:
                k = yes[0] + no[0]
                found.append((c, ph, side, offs[k - 1], offs[k]))
    out = []
    closed = [f for f in found if f[4] is not None]
    if closed:
        f16 = np.linspace(0.0, 1.0, 17)[1:]
        C = np.array([[f[0]] * 16 for f in closed])
        P = np.array([[f[1] + f[2] * (f[3] + x * (f[4] - f[3])) for x in f16] for f in closed])
        cyc = has_cycle(m, C, P, Z) != 0  # undecided next to the edge: the period diverges
        hom = {}
        for f, row, prow in zip(closed, cyc, P):
            if row.all():
                hom[f[:3]] = prow[-1]
            else:
                k = int(np.argmin(row))
                prev = prow[k - 1] if k > 0 else f[1] + f[2] * f[3]
                hom[f[:3]] = 0.5 * (prev + prow[k])
    for f in found:
        out.append((f[0], f[1], hom[f[:3]] if f[4] is not None else None))
    return out


def one_period(z, p, v, section):
    """The last full period of a recorded trajectory: between its last two upward crossings
    of phi = section (in the direction of integration); None if fewer than two."""
    up = np.nonzero((p[:-1] < section) & (p[1:] >= section))[0]
    if len(up) < 3:
        return None
    a, b = up[-2], up[-1]
    zz = np.abs(z[a:b + 1] - z[a])
    if z[1] < z[0]:  # integrated backwards: reverse so that z increases
        return zz[-1] - zz[::-1], p[a:b + 1][::-1], v[a:b + 1][::-1]
    return zz, p[a:b + 1], v[a:b + 1]


def figure(m, path, Z=300.0, c_mark=-2.8, q_mark=2.228):
    """jamming_waves.png: a) fixed-point classes with the cycle area, Hopf and homoclinic
    lines and the orbits I-III (fig 6.14 right, 6.18 a); b) the orbits I-III in the phase
    plane; c) their profiles phi(z), v(z) over one period (fig 6.18 c). Returns the homoclinic
    line and the orbits."""
    import matplotlib.colors
    import matplotlib.patches
    import narrows_h5

    cs = np.linspace(-4.0, -1.5, 26)
    lo, hi = 0.735, 0.795
    area = cycle_region(m, cs, lo, hi, Z)
    line = [(c, h) for c, _, h in area if h is not None]
    print(f"limit cycles next to {len(area)} Hopf points (c from {cs[0]:g} to {cs[-1]:g}, "
          f"phi0 from {lo:g} to {hi:g}; Z = {Z:g})")
    for c, ph, h in area:
        print(f"homoclinic c = {c:.4f} phi0 = " + (f"{h:.5f}" if h is not None else "beyond 0.04")
              + f" (Hopf phi0 = {ph:.5f}, width {abs(h - ph) if h is not None else 0.04:.2e})")
    # Orbits I-III: the fig 6.18 b point, and half-way between the Hopf and the homoclinic
    # line at the smallest and the largest |c| with an area.
    marks = []
    fps = m.fixed_points(c_mark, q_mark)
    if len(fps) == 3:
        marks.append(("II", c_mark, fps[1]))
    closed = sorted((c, ph, h) for c, ph, h in area if h is not None)
    if closed:
        for name, (c, ph, h) in (("I", closed[-1]), ("III", closed[0])):
            marks.append((name, c, ph + 0.9 * (h - ph)))
    marks.sort(key=lambda x: x[0])
    orbits = []
    if marks:
        Cm = np.array([x[1] for x in marks])
        Pm = np.array([x[2] for x in marks])
        alive, _, _, _, z, pt, vt = follow(m, Cm, Pm, 3 * Z, record=np.arange(len(marks)))
        for i, (name, c, p0) in enumerate(marks):
            per = one_period(z[:, i] if z.ndim > 1 else z, pt[:, i], vt[:, i], p0) if alive[i] \
                else None
            if per is None:
                print(f"orbit {name}: c = {c:g}, phi0 = {p0:.5f}: no closed orbit within Z")
                continue
            zz, pp, vv = per
            print(f"orbit {name}: c = {c:g}, phi0 = {p0:.5f}, q = {p0 * (m.vss(p0) - c):.5f}: "
                  f"period {zz[-1]:.4g}, phi {pp.min():.4f} to {pp.max():.4f}, "
                  f"v {vv.min():.4f} to {vv.max():.4f}")
            orbits.append((name, c, p0, zz, pp, vv))

    plt = narrows_h5.pyplot()
    fig, ax = plt.subplots(1, 3, figsize=(17, 5.2))
    kinds = ["saddle", "node sink", "node source", "focus sink", "focus source"]
    cf = np.linspace(cs[0], cs[-1], 300)
    pf = np.linspace(lo, hi, 300)
    C, P = np.meshgrid(cf, pf)
    l1, l2 = m.jacobian_eigs(C, P)
    grid = np.where(np.abs(l1.imag) > 0, np.where(l1.real < 0, 3, 4),
                    np.where(l1.real * l2.real < 0, 0, np.where(l1.real < 0, 1, 2)))
    cmap = matplotlib.colors.ListedColormap(["#bbbbbb", "#2c7bb6", "#d7191c", "#abd9e9", "#fdae61"])
    a = ax[0]
    a.pcolormesh(cf, pf, grid, cmap=cmap, vmin=-0.5, vmax=4.5, shading="auto")
    for side in (+1, -1):  # the area between the Hopf and the homoclinic line, per side
        pts = sorted((c, ph, h) for c, ph, h in area if h is not None and (h - ph) * side > 0)
        if len(pts) > 1:
            a.fill_between([x[0] for x in pts], [x[1] for x in pts], [x[2] for x in pts],
                           facecolor="none", edgecolor="k", hatch="///", lw=0)
    hp = np.linspace(lo, hi, 4000)
    a.plot(m.vss(hp) - np.sqrt(m.D * m.xi(hp)), hp, "k--", lw=1, label="Hopf (eq 6.21)")
    if line:
        lc, lp = zip(*sorted(line))
        a.plot(lc, lp, "k.-", lw=1.5, ms=3, label="homoclinic")
    for name, c, p0 in marks:
        a.plot([c], [p0], "k*", ms=9)
        a.annotate(name, (c, p0), textcoords="offset points", xytext=(4, 4))
    handles = [matplotlib.patches.Patch(color=cmap(i), label=kinds[i]) for i in range(5)]
    handles.append(matplotlib.patches.Patch(facecolor="w", edgecolor="k", hatch="///",
                                            label="limit cycles"))
    a.legend(handles=handles + a.get_legend_handles_labels()[0], fontsize=7, loc="lower left")
    a.set(xlabel="c", ylabel="phi0", xlim=(cs[0], cs[-1]), ylim=(lo, hi),
          title=f"a) fig 6.14 right / 6.18 a: limit cycles ({m.label})")
    for i, (name, c, p0, zz, pp, vv) in enumerate(orbits):
        col = f"C{i}"
        ax[1].plot(pp, vv, col, lw=1.5, label=f"{name}: c = {c:g}, phi0 = {p0:.4f}")
        ax[1].plot([p0], [m.vss(p0)], "k.", ms=5)
        ax[2].plot(zz, pp, col, lw=1.5, label=f"{name}: phi")
        ax[2].plot(zz, vv, col, lw=1, ls="--", label=f"{name}: v")
    pp = np.linspace(0.68, 0.84, 2000)
    ax[1].plot(pp, m.vss(pp), "m", lw=0.8, label="v_ss")
    ax[1].set(xlabel="phi", ylabel="v", ylim=(-0.02, 0.6), title="b) the closed orbits I-III")
    ax[1].legend(fontsize=7)
    ax[2].set(xlabel="z = x - c t (one period)", ylabel="phi, v",
              title="c) fig 6.18 c: profiles phi(z) (solid), v(z) (dashed)")
    ax[2].legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print(f"wrote {path}")
    return line, orbits
