"""Generate flexsim/aircraft/data/maewing1.toml from the mAEWing1 NASTRAN beam-stick model (FEM v5.2).

Source: the Bulk Data files of "FEM v5.2 for Geri+WS4" (Virginia Tech / PAAW, W. Zhao, 2016), public repository
zhaowei0566/mAEWing1 (MIT licence), folder "Design/FEM/FEM v5.2/NASTRAN files", commit 7683349c7711a14607347f8fc0b40095774cf549,
copied unchanged into flexsim/aircraft/data/sources/ (GRID_mAEWing1.dat, gvt_accelerations.dat, WS3_spar_full.dat,
BEAM_mAEWing1_updated_asymmetric.dat, CONM2_mAEWing1_updated.dat, CAERO_mAEWing1_updated.dat, sol103_mAEWing1_FEMv5p2.bdf).
Units of the model: inch, pound-force, second; masses are weights in pound (PARAM WTMASS 0.002591 = 1/386 turns
them into lbf s^2/in), so 1 lb of CONM2, density or NSM is 0.45359237 kg. NASTRAN frame: x aft, y right, z up =
flexsim's "design" frame. The reduction (maewing1.md): a rigid centre body (fuselage beam, no airloads) carrying
every mass inboard of the wing-root ribs (|y| <= 7.65 in) as one lumped mass, and the motor as an engine;
rigid centre-body halves (right/left_htail) carrying the centre body's strips and the body flaps as elevator;
flexible wings from the root ribs (GRID 1010/2010) to the tips (GRID 1090/2090) along the straight spar line, with EI =
E I1 and GJ = G J of foam+cover and spar beams summed, element masses rho A + NSM as mass per span, the CONM2 point
masses (with the foam's CONM2 of zero mass: pure rotary inertias) as lumped masses at their grids. Run from the root:
    python tools/make_maewing1_toml.py > flexsim/aircraft/data/maewing1.toml
"""

import argparse
import math
import re
from pathlib import Path

import numpy as np

IN, LB, LBF = 0.0254, 0.45359237, 4.4482216152605  # [m], [kg], [N] per inch, pound (mass), pound-force
LBIN2 = LBF * IN**2  # 1 lbf in^2 in N m^2
FILES = ("sol103_mAEWing1_FEMv5p2.bdf", "GRID_mAEWing1.dat", "gvt_accelerations.dat", "WS3_spar_full.dat",
         "BEAM_mAEWing1_updated_asymmetric.dat", "CONM2_mAEWing1_updated.dat", "CAERO_mAEWing1_updated.dat")
ROOT_Y = 7.65  # |y| of the wing-root ribs (GRID 1010/2010) [in]
MAX_THRUST_N = 30.0  # not in the FEM: an assumed motor thrust, so that flexsim's trim can balance the drag


def number(text):
    """A NASTRAN real or integer ("1.1468-7", "5.098e-1", "0.", blank -> 0)."""
    t = text.strip()
    return float(re.sub(r"(?<=[0-9.])([+-]\d+)$", r"E\1", t)) if t else 0.0


def cards(folder):
    """Bulk Data cards of FILES as {name: [fields, ...]} (small-field format, continuation lines appended)."""
    out, last = {}, None
    for name in FILES:
        for line in (Path(folder) / name).read_text(encoding="latin-1").splitlines():
            line = line.expandtabs(8).rstrip()
            if not line or line.startswith("$") or "," in line[:8] or line.upper().startswith(("INIT", "SOL", "CEND", "BEGIN", "ENDDATA")):
                continue
            head = line[:8].strip()
            fields = [line[i:i + 8] for i in range(8, min(len(line), 72), 8)]
            fields += [""] * (8 - len(fields))
            if head == "" or head.startswith("+"):
                last.extend(fields)
            else:
                last = fields
                out.setdefault(head.upper(), []).append(last)
    return out


def frames(c):
    """CORD2R frames (defined in the basic frame) as {cid: (origin, 3x3 rotation with the axes as columns)}."""
    out = {0: (np.zeros(3), np.eye(3))}
    for f in c["CORD2R"]:
        a, b, p = (np.array([number(v) for v in f[k:k + 3]]) for k in (2, 5, 8))
        z = (b - a) / np.linalg.norm(b - a)
        x = (p - a) - ((p - a) @ z) * z
        x /= np.linalg.norm(x)
        out[int(f[0])] = (a, np.column_stack([x, np.cross(z, x), z]))
    return out


def model(folder):
    """Grids (basic, in), element masses and the point masses of the model."""
    c = cards(folder)
    cs = frames(c)
    grid = {}
    for f in c["GRID"]:
        o, r = cs[int(number(f[1]))]
        grid[int(f[0])] = o + r @ np.array([number(v) for v in f[2:5]])
    mat = {int(f[0]): dict(E=number(f[1]), G=number(f[2]), nu=number(f[3]), rho=number(f[4])) for f in c["MAT1"]}
    prop = {int(f[0]): dict(mid=int(f[1]), A=number(f[2]), I1=number(f[3]), I2=number(f[4]), J=number(f[6]), nsm=number(f[7]))
            for f in c["PBEAM"]}
    for f in c["PBARL"]:  # BAR of DIM1 x DIM2 (only its mass and a nominal stiffness are used: the keel is rigid here)
        b, h = number(f[8]), number(f[9])
        prop[int(f[0])] = dict(mid=int(f[1]), A=b * h, I1=b * h**3 / 12, I2=0.0, J=b * h * (b * b + h * h) / 12, nsm=number(f[10]))
    elems = []
    for f in c["CBEAM"] + c["CBAR"]:
        p = prop[int(f[1])]
        m = mat[p["mid"]]
        ga, gb = grid[int(f[2])], grid[int(f[3])]
        off = np.array([number(v) for v in f[10:13]]) if len(f) > 12 else np.zeros(3)  # CBEAM offset W1A-W3A
        g = m["G"] or m["E"] / (2 * (1 + m["nu"]))
        # polar inertia rho (I1 + I2) per length: in a CBEAM's lumped mass matrix (none for a CBAR: I2 = 0 above)
        elems.append(dict(a=ga, b=gb, off=off, mpl=m["rho"] * p["A"] + p["nsm"], ipl=m["rho"] * (p["I1"] + p["I2"]),
                          EI=m["E"] * p["I1"], GJ=g * p["J"]))
    points = []  # (mass [lb], position [in], inertia about own CG [lb in^2], basic axes, EID, GRID)
    for f in c["CONM2"]:
        o, r = cs[int(number(f[2]))]
        i11, i21, i22, i31, i32, i33 = (number(v) for v in f[8:14]) if len(f) > 13 else (0.0,) * 6
        tensor = r @ np.array([[i11, -i21, -i31], [-i21, i22, -i32], [-i31, -i32, i33]]) @ r.T
        points.append((number(f[3]), grid[int(f[1])] + r @ np.array([number(v) for v in f[4:7]]), tensor, int(f[0]), int(f[1])))
    for f in c["CMASS2"]:  # scalar rotary inertia on component 4 (Ixx) or 5 (Iyy)
        k = int(number(f[3])) - 4
        points.append((0.0, grid[int(f[2])], np.diag([1.0 * (k == 0), 1.0 * (k == 1), 0.0]) * number(f[1]), int(f[0]), int(f[2])))
    return grid, elems, points, c, cs


def halves(e):
    """An element's mass as two point masses at its (offset) ends, each with half its polar inertia about its axis."""
    length = np.linalg.norm(e["b"] - e["a"])
    d = (e["b"] - e["a"]) / length
    return [(0.5 * e["mpl"] * length, p + e["off"], 0.5 * e["ipl"] * length * np.outer(d, d)) for p in (e["a"], e["b"])]


def combine(items):
    """Total mass, CG and inertia tensor about the CG of (mass, position, own inertia) items."""
    m = sum(i[0] for i in items)
    cg = sum(i[0] * i[1] for i in items) / m if m > 0 else items[0][1]  # zero mass: a pure rotary inertia
    inertia = sum(i[2] + i[0] * ((i[1] - cg) @ (i[1] - cg) * np.eye(3) - np.outer(i[1] - cg, i[1] - cg)) for i in items)
    return m, cg, inertia


def planform(c):
    """Leading edge, trailing edge [in] at spanwise |y| [in] of the flat CAERO1 panels (right half; winglets left out)."""
    panels = []
    for f in c["CAERO1"]:
        x1, y1, z1, c12, x4, y4, z4, c43 = (number(v) for v in f[8:16])
        if y1 >= 0 and y4 >= 0 and z1 == z4 == 0 and y4 != y1:
            panels.append((min(y1, y4), max(y1, y4), (x1, c12) if y1 < y4 else (x4, c43), (x4, c43) if y1 < y4 else (x1, c12)))

    def edges(y):
        le, te = math.inf, -math.inf
        for ya, yb, (xa, ca), (xb, cb) in panels:
            if ya - 1e-9 <= y <= yb + 1e-9:
                t = (y - ya) / (yb - ya)
                x, ch = xa + t * (xb - xa), ca + t * (cb - ca)
                le, te = min(le, x), max(te, x + ch)
        return le, te
    breaks = np.unique([y for p in panels for y in p[:2]])
    return edges, breaks


def fmt(values, digits=6):
    return "[" + ", ".join(f"{v:.{digits}g}" for v in values) + "]"


def vlm_slopes(edges, breaks):
    """Mean sectional lift slope [1/rad] (chord-weighted) of the centre body (|y| < ROOT_Y) and of the wing, from
    flexsim's vortex lattice (flexsim.aero.vlm) of the whole flat CAERO1 planform, both halves, Mach 0."""
    from flexsim.aero.vlm import LiftingSurface, solve_vlm
    le, te = np.array([edges(y) for y in breaks]).T
    per = [max(4, int(round(b - a))) for a, b in zip(breaks[:-1], breaks[1:])]  # spanwise panels about 1 in wide
    half = LiftingSurface("wing", np.column_stack([le, breaks, 0 * breaks]) * IN, (te - le) * IN, n_chordwise=6,
                          n_spanwise=per, mirror=True)
    s = solve_vlm([half]).surfaces[0]
    weight = s.chord_m * s.width_m * (s.y_m > 0)
    inner = s.y_m < ROOT_Y * IN
    return tuple(float(np.sum((s.cl_alpha_per_rad * weight)[k]) / np.sum(weight[k])) for k in (inner, ~inner))


def datcom_slope(aspect, sweep):
    """Lift-curve slope of a wing [1/rad] (Helmbold-Diederich, USAF DATCOM 4.1.3.2; Mach 0, section slope 2 pi)."""
    return 2 * math.pi * aspect / (2 + math.sqrt(aspect**2 * (1 + math.tan(sweep) ** 2) + 4))


def wing_tables(elems, root, tip):
    """Stations [in] and section tables (lb/in, lbf in^2, lb in^2/in, in) of one wing from its elements."""
    a = (tip - root) / np.linalg.norm(tip - root)
    n = np.array([1.0, 0.0, 0.0]) - a[0] * a
    n /= np.linalg.norm(n)  # in-plane normal to the axis, aft
    side = np.sign(tip[1])
    mine = [e for e in elems if side * 0.5 * (e["a"] + e["b"])[1] > ROOT_Y + 1e-6]
    span = [sorted(((e["a"] - root) @ a, (e["b"] - root) @ a)) for e in mine]
    nodes = np.unique(np.round([s for ab in span for s in ab], 6))
    rows = []
    for lo, hi in zip(nodes[:-1], nodes[1:]):
        on = [e for e, (sa, sb) in zip(mine, span) if sa <= lo + 1e-6 and sb >= hi - 1e-6]
        m = sum(e["mpl"] for e in on)
        e_s = sum(e["mpl"] * (e["off"] @ n) for e in on) / m / abs(a[1])  # streamwise offset of the mass, + aft
        it = sum(e["ipl"] + e["mpl"] * ((e["off"] @ n) / abs(a[1])) ** 2 for e in on)
        rows.append((m, e_s, it, sum(e["EI"] for e in on), sum(e["GJ"] for e in on)))
    length = float(nodes[-1])
    st, vals = [0.0], [rows[0]]
    for k in range(1, len(rows)):  # a property jump at a node becomes two stations 0.5 mm apart
        if rows[k] != rows[k - 1]:
            st += [nodes[k] - 0.01, nodes[k] + 0.01]
            vals += [rows[k - 1], rows[k]]
    st.append(length)
    vals.append(rows[-1])
    return a, n, length, np.array(st), np.array(vals)


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--source", default=str(Path(__file__).resolve().parents[1] / "flexsim/aircraft/data/sources"),
                        help="folder holding the FEM v5.2 Bulk Data files [flexsim/aircraft/data/sources]")
    parser.add_argument("--totals", action="store_true", help="print the model's mass [kg], CG [m] and inertia [kg m^2] and stop")
    args = parser.parse_args()
    grid, elems, points, c, cs = model(args.source)
    m, cg, inertia = combine([item for e in elems for item in halves(e)] + [p[:3] for p in points])  # [lb], [in], [lb in^2]
    if args.totals:
        print(f"mass_kg = {m * LB:.6g}\ncg_m = {fmt(cg * IN)}\ninertia_kg_m2 = {fmt(np.diag(inertia) * LB * IN**2)}")
        raise SystemExit
    edges, breaks = planform(c)
    span = 2 * breaks[-1]
    cla = dict(zip(("htail", "wing"), vlm_slopes(edges, breaks)))
    # the two tip winglets (CAERO1 1101001-2102001, upper and lower panels) as one centreline fin of twice their chord
    # (same area, same x): flexsim has one fin; its axis at x = 27 in, the origin o at its root
    fin = sorted((number(f[10 + 4 * k]), number(f[8 + 4 * k]), 2 * number(f[11 + 4 * k])) for f in c["CAERO1"]
                 if number(f[9]) > 0 and number(f[10]) != number(f[14]) for k in (0, 1))  # (z, x_le, chord) [in]
    fin = np.array([fin[0]] + [fin[k] for k in range(1, len(fin)) if fin[k][0] > fin[k - 1][0] + 1e-9])
    x_fin, fin_span = 27.0, fin[-1, 0] - fin[0, 0]
    fin_aspect = 2 * fin_span**2 / np.trapezoid(fin[:, 2], fin[:, 0])  # one winglet: half the fin's area
    fin_cla = datcom_slope(fin_aspect, math.atan2(*(fin[-1, 1:] @ [1, 0.25] - fin[1, 1:] @ [1, 0.25], fin[-1, 0] - fin[1, 0])))
    tail, nose = np.array([x_fin, 0.0, 0.0]), grid[3001]
    out = []
    w = out.append
    w("# mAEWing1 (Geri + WS4) flying wing, NASTRAN beam-stick FEM v5.2 (Virginia Tech / PAAW, 2016) reduced to flexsim beams.")
    w("# Generated by tools/make_maewing1_toml.py from the FEM's Bulk Data in flexsim/aircraft/data/sources/; provenance, the")
    w("# reduction and its checks against the FEM's own NASTRAN results are in maewing1.md beside this file.")
    w('schema_version = 1\nname = "mAEWing1"')
    w(f'description = "mAEWing1 flying wing (span {span * IN:.3f} m, {m * LB:.3f} kg) from its public NASTRAN FEM v5.2; see maewing1.md"')
    w('\n[frame]\nkind = "design"   # the FEM\'s basic frame: x aft, y right, z up [m]')
    w(f"body_origin_m = {fmt(tail * IN)}   # on the centreline below the fin axis")
    w('\n[aero]\ncompressibility = "none"   # the FEM\'s doublet lattice is at Mach 0; flutter near Mach 0.1')
    keel = next(e for e in elems if np.allclose(e["a"], grid[3001]))
    w(f"\n[components.fuselage]   # rigid centre body: the nose (GRID 3001) to the fin axis, past the keel's tail (GRID 3007)")
    w(f"root_m = {fmt(tail * IN)}\neuler_deg = [0.0, 0.0, 0.0]\nlength_m = {(tail - nose)[0] * IN:.6g}\nrigid = true")
    w(f'section_inertia = "axisymmetric"\n[components.fuselage.sections]\nstation_m = [0.0, {(tail - nose)[0] * IN:.6g}]')
    w("mass_kg_per_m = [0.0, 0.0]\ntorsional_inertia_kg_m = [0.0, 0.0]")
    w(f"ei_nm2 = {fmt([keel['EI'] * LBIN2] * 2)}\ngj_nm2 = {fmt([keel['GJ'] * LBIN2] * 2)}")
    lumped = []
    for side, name, g_root, g_tip, cid_bf, cid_cs in ((1, "right", 2010, 2090, 201, 202), (-1, "left", 1010, 1090, 101, 102)):
        # centre-body half: rigid, carries the centre body's strips and the body flap (elevator)
        root, end = grid[3000], grid[g_root]
        a = (end - root) / np.linalg.norm(end - root)
        length = np.linalg.norm(end - root)
        cb = [e for e in elems if np.allclose(e["a"], root) and side * e["b"][1] > 0]
        psi = side * math.degrees(math.atan2(abs(a[1]), -a[0]))
        o, r = cs[cid_bf]
        h0, h1 = (o + r[:, 1] * side * y for y in (0.0, 12.45))  # hinge line (y axis of the body-flap frame), GRID 5021-5022
        for comp, g0, l_c, kind, hinge, tables in (("htail", root, length, "elevator", (h0, h1), None),
                                                    ("wing", grid[g_root], None, "aileron", None, wing_tables(elems, grid[g_root], grid[g_tip]))):
            if tables is None:
                st = np.array([0.0, 0.5 * l_c, l_c])
                rows = np.array([[0.0, 0.0, 0.0, sum(e["EI"] for e in cb), sum(e["GJ"] for e in cb)]] * 3)
                ax = a
            else:
                ax, _, l_c, st, rows = tables
                o2, r2 = cs[cid_cs]
                hinge = tuple(o2 + r2[:, 1] * side * y for y in (29.76, 44.51))  # outer flap hinge, GRID 8021-8022 span
            pts = g0[None, :] + st[:, None] * ax[None, :]
            le, te = np.array([edges(abs(p[1])) for p in pts]).T
            chord = te - le
            ea = (pts[:, 0] - le) / chord
            ys = sorted(abs(h[1]) for h in hinge)
            y_root = abs(g0[1])
            s0, s1 = max(0.0, (ys[0] - y_root) / abs(ax[1])), min(l_c, (ys[1] - y_root) / abs(ax[1]))
            y_mid = y_root + 0.5 * (s0 + s1) * abs(ax[1])
            t = (y_mid - abs(hinge[0][1])) / (abs(hinge[1][1]) - abs(hinge[0][1]))
            x_h = hinge[0][0] + t * (hinge[1][0] - hinge[0][0])
            le_m, te_m = edges(y_mid)
            key = f"{name}_{comp}"
            w(f"\n[components.{key}]\nroot_m = {fmt(g0 * IN)}\neuler_deg = [0.0, 0.0, {psi:.6g}]   # sweep {abs(psi) - 90:.4g} deg")
            w(f"length_m = {l_c * IN:.6g}")
            w("rigid = true" if comp == "htail" else "bending_modes = 10\ntorsion_modes = 6")
            w(f"[components.{key}.aero]\nstrips = {3 if comp == 'htail' else 12}")
            w(f"lift_slope = {cla[comp]:.6g}   # vortex lattice of the planform, mean")
            w(f'[components.{key}.control_surface]\nkind = "{kind}"   # {"body flap" if kind == "elevator" else "outer flap"}')
            w(f"hinge_fraction = {(x_h - le_m) / (te_m - le_m):.4g}\nstart_m = {s0 * IN:.6g}\nend_m = {s1 * IN:.6g}")
            w(f"[components.{key}.sections]\nstation_m = {fmt(st * IN)}\nmass_kg_per_m = {fmt(rows[:, 0] * LB / IN)}")
            w(f"cg_offset_m = {fmt(rows[:, 1] * IN)}\ntorsional_inertia_kg_m = {fmt(rows[:, 2] * LB * IN)}")
            w(f"ei_nm2 = {fmt(rows[:, 3] * LBIN2)}\ngj_nm2 = {fmt(rows[:, 4] * LBIN2)}")
            w(f"chord_m = {fmt(chord * IN)}\nea_fraction = {fmt(ea)}")
            if comp == "wing":
                on = {}
                for p in points:
                    if side * p[1][1] > ROOT_Y + 1e-6:  # with the foam's CONM2 of zero mass: pure rotary inertias
                        on.setdefault(p[4], []).append(p)
                for gid, group in sorted(on.items()):
                    mg, pos, tens = combine([p[:3] for p in group])
                    s_p = (pos - g0) @ ax
                    pos = pos - max(0.0, s_p - l_c) * ax  # the winglet's CG, 0.9 in outboard of the tip node: onto the tip
                    lumped.append((f"conm2_{'_'.join(str(p[3]) for p in group)}", key, mg, pos, tens))
    cb_items = [it for e in elems if abs(0.5 * (e["a"] + e["b"])[1]) <= ROOT_Y + 1e-6 for it in halves(e)]
    cb_items += [p[:3] for p in points if abs(p[1][1]) <= ROOT_Y + 1e-6 and p[3] != 303]
    w(f"\n[components.vtail]   # both winglets as one rigid fin: chord x 2, bottom to top; no rudder: trims in sideslip")
    w(f"root_m = {fmt(np.array([x_fin, 0.0, fin[0, 0]]) * IN)}\neuler_deg = [90.0, 90.0, 0.0]")
    w(f"length_m = {fin_span * IN:.6g}\nrigid = true")
    w(f"[components.vtail.aero]\nstrips = 4\nlift_slope = {fin_cla:.6g}   # DATCOM 4.1.3.2, one winglet's aspect ratio {fin_aspect:.3g}")
    w(f"[components.vtail.sections]\nstation_m = {fmt((fin[:, 0] - fin[0, 0]) * IN)}\nmass_kg_per_m = {fmt(np.zeros(len(fin)))}")
    w(f"torsional_inertia_kg_m = {fmt(np.zeros(len(fin)))}\nei_nm2 = {fmt([keel['EI'] * LBIN2] * len(fin))}")
    w(f"gj_nm2 = {fmt([keel['GJ'] * LBIN2] * len(fin))}\nchord_m = {fmt(fin[:, 2] * IN)}")
    w(f"ea_fraction = {fmt((x_fin - fin[:, 1]) / fin[:, 2])}")
    lumped.insert(0, ("centre_body", "fuselage", *combine(cb_items)))
    for name_, comp, mg, pos, tens in lumped:
        pos, tens = np.where(np.abs(pos) > 1e-6, pos, 0.0), np.where(np.abs(tens) > 1e-9 * np.abs(tens).max(), tens, 0.0)
        w(f'\n[[lumped_masses]]\nname = "{name_}"\ncomponent = "{comp}"\nposition_m = {fmt(pos * IN)}\nmass_kg = {mg * LB:.6g}')
        if np.abs(tens).max() > 0:
            w(f"inertia_kg_m2 = [{', '.join(fmt(row * LB * IN**2) for row in tens)}]")
    motor = next(p for p in points if p[3] == 303)
    w('\n[[engines]]\nname = "motor"   # CONM2 303\ncomponent = "fuselage"')
    w(f"position_m = {fmt(motor[1] * IN)}\nmass_kg = {motor[0] * LB:.6g}")
    w(f"max_thrust_n = {MAX_THRUST_N}   # assumed (not in the FEM)")
    print("\n".join(out))
