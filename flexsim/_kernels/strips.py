"""Strip airloads: their data, kinematics, loads and apparent mass (paper eqs. 17-31), compiled.

Sources: Tuzcu & Nguyen (2014), eqs. (17)-(24) generalized forces, (25)-(31) strip airloads; Peters,
Karunamoorthy & Cao (1995), finite-state inflow, as written in ``docs/reference/aero-kinematics.md`` section 2.1
and the Peters-Johnson strip loads, sections 1.3-1.6; USAF DATCOM sec. 4.4.1, wing downwash at the tail
(:func:`flexsim.model.coupling.tail_downwash`); H. Glauert (1928), Prandtl-Glauert. The strips' data are built by
:class:`flexsim.model.coupling.AeroCoupling`. Strip axes d (chord, to the trailing edge), n (plunge, down),
p = d x n; SI units, radians.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from flexsim._kernels.downwash import downwash_velocity, has_downwash, tail_downwash  # noqa: F401 (re-exported)
from flexsim._kernels.layout import STRIP_COL_PTR, STRIP_COLS, _f1, _f2, _f3, _flag, _i1, kernel, packed, term_data
from flexsim._kernels.peters import inflow_derivative, inflow_lambda0


@term_data
@dataclasses.dataclass(frozen=True)
class StripData:
    """The strips' geometry, kinematic maps and airload coefficients (paper eqs. 17-31, built by
    :class:`flexsim.model.coupling.AeroCoupling`); n_s strips, strip axes d, n, p, component axes, V = [v, omega, s, eta]."""

    proj_n0: np.ndarray = packed(2, "n^T A at q = 0 (n_s, n_v): plunge velocity per unit V [-, m]")
    proj_d0: np.ndarray = packed(2, "d^T A at q = 0 (n_s, n_v): chordwise velocity per unit V")
    proj_n1: np.ndarray = packed(3, "the q part of n^T A in the omega columns (n_s, 3, nq) [-]")
    proj_d1: np.ndarray = packed(3, "the q part of d^T A in the omega columns (n_s, 3, nq) [-]")
    proj_p: np.ndarray = packed(2, "p^T B (n_s, n_v): pitch rate per unit V [1/m, -]")
    rel: np.ndarray = packed(2, "elastic pitch per unit [q, xi] (n_s, n_el) [rad/m, -]")
    incidence: np.ndarray = packed(1, "rigging incidence alpha_r (n_s,) [rad]")
    semichord: np.ndarray = packed(1, "b (n_s,) [m]")
    ab: np.ndarray = packed(1, "a b (n_s,): elastic axis behind mid-chord [m]")
    k0: np.ndarray = packed(1, "Cl_a0 / 2 pi (n_s,) [-]")
    pr_w: np.ndarray = packed(1, "pi b^2 w (n_s,): apparent mass per unit density [m^3]")
    width: np.ndarray = packed(1, "strip width w (n_s,) [m]")
    cd0: np.ndarray = packed(1, "section profile drag coefficient (n_s,) [-]")
    flap_sign: np.ndarray = packed(1, "sign of the control deflection on the strip (n_s,) [-]")
    paper_strips: np.ndarray = packed(1, "1 on strips resolved as the paper's eq. 28 (n_s,)")
    n_over_d_x: np.ndarray = packed(1, "n_x / d_x, body-x components of n and d (n_s,) [-]")
    flap_w: np.ndarray = packed(2, "flap camber coefficients f0, f1, f2 (n_s, 3) [-]")
    d: np.ndarray = packed(2, "chord direction d in component axes (n_s, 3)")
    n: np.ndarray = packed(2, "plunge direction n in component axes (n_s, 3)")
    strip_dcm: np.ndarray = packed(3, "component-to-body rotation of each strip (n_s, 3, 3)")
    strip_pos: np.ndarray = packed(2, "elastic-axis point in body axes at q = 0 (n_s, 3) [m]")
    apparent_pitch: np.ndarray = packed(2, "sum_j pi b^4 w / 8 (p^T B)^T (p^T B) (n_v, n_v) [m^4]")
    tilt_scale: np.ndarray = packed(1, "scale of the lift's tilt by the flow angle (n_s,) (Terms.force_resolution)")
    drag_scale: np.ndarray = packed(1, "scale of the drag (n_s,) (Terms.force_resolution, fin_drag_per_lift)")
    drag_per_lift: np.ndarray = packed(1, "drag per unit lift kappa (n_s,) (Terms.fin_drag_per_lift, eq. 30)")
    aero_dv: np.ndarray = packed(1, "body velocity offset the strips see (3,) [m/s] (Terms.aero_velocity_offset_m_s)")
    strip_mach: np.ndarray = packed(1, "[Mach of a frozen compressibility factor] (1,), nan: the flight's")
    flap_index: np.ndarray = packed(1, "index in u of each strip's control surface, 0: none (n_s,)", "ints")
    prandtl_glauert: int = packed(0, "1: Prandtl-Glauert factor on Cl_alpha (Glauert 1928)", "flag")
    paper: int = packed(0, "1: the paper's force resolution (eq. 28) on the paper_strips", "flag")
    has_aero_dv: int = packed(0, "1 when aero_dv is applied", "flag")

    @staticmethod
    def fields_of(model) -> dict:
        """The fields of a model (:class:`flexsim.model.aircraft_model.AircraftModel`): the arrays of its strip
        coupling (:class:`flexsim.model.coupling.AeroCoupling`, ``model.aero``), no strips without aerodynamics."""
        a, d = model.aero, model.structure.dofs
        if a is None:
            return dict(proj_n0=np.zeros((0, d.n_v)), proj_d0=np.zeros((0, d.n_v)), proj_p=np.zeros((0, d.n_v)),
                        rel=np.zeros((0, d.nq + d.nxi)), proj_n1=np.zeros((0, 3, d.nq)), proj_d1=np.zeros((0, 3, d.nq)),
                        strip_mach=[math.nan])
        s, mach = a.strips, a.compressibility_mach
        return dict(proj_n0=s.proj_n0, proj_d0=s.proj_d0, proj_n1=s.proj_n1, proj_d1=s.proj_d1, proj_p=a.proj_p,
                    rel=a.rel, incidence=s.incidence_rad, semichord=s.semichord_m, ab=a.ab, k0=a.k0, pr_w=a.pr_w,
                    width=s.width_m, cd0=s.cd0, flap_sign=s.flap_sign, paper_strips=a.paper_strips.astype(float),
                    n_over_d_x=a.n_over_d_x, flap_w=s.flap_w, d=s.d, n=s.n, strip_dcm=a.strip_dcm,
                    strip_pos=s.position_body_m, apparent_pitch=a.apparent_pitch, tilt_scale=a.tilt_scale,
                    drag_scale=a.drag_scale, drag_per_lift=a.drag_per_lift, aero_dv=a.velocity_offset_m_s,
                    strip_mach=[math.nan if mach is None else float(mach)], flap_index=s.flap_index,
                    prandtl_glauert=a.compressibility == "prandtl-glauert", paper=a.formulation == "paper",
                    has_aero_dv=a.terms.aero_velocity_offset_m_s is not None)


# the fields' indices (kernel constants, generated by term_data)
PROJ_N0 = StripData.index["proj_n0"]
PROJ_D0 = StripData.index["proj_d0"]
PROJ_N1 = StripData.index["proj_n1"]
PROJ_D1 = StripData.index["proj_d1"]
PROJ_P = StripData.index["proj_p"]
REL = StripData.index["rel"]
INCIDENCE = StripData.index["incidence"]
SEMICHORD = StripData.index["semichord"]
AB = StripData.index["ab"]
K0 = StripData.index["k0"]
PR_W = StripData.index["pr_w"]
WIDTH = StripData.index["width"]
CD0 = StripData.index["cd0"]
FLAP_SIGN = StripData.index["flap_sign"]
PAPER_STRIPS = StripData.index["paper_strips"]
N_OVER_D_X = StripData.index["n_over_d_x"]
FLAP_W = StripData.index["flap_w"]
D = StripData.index["d"]
N = StripData.index["n"]
STRIP_DCM = StripData.index["strip_dcm"]
STRIP_POS = StripData.index["strip_pos"]
APPARENT_PITCH = StripData.index["apparent_pitch"]
TILT_SCALE = StripData.index["tilt_scale"]
DRAG_SCALE = StripData.index["drag_scale"]
DRAG_PER_LIFT = StripData.index["drag_per_lift"]
AERO_DV = StripData.index["aero_dv"]
STRIP_MACH = StripData.index["strip_mach"]
FLAP_INDEX = StripData.index["flap_index"]
PRANDTL_GLAUERT = StripData.index["prandtl_glauert"]
PAPER = StripData.index["paper"]
HAS_AERO_DV = StripData.index["has_aero_dv"]

_MACH_CAP = 0.95


@kernel
def aero_velocity(F, I, vel):
    """The velocity V the strips see (n_v,): V with the body velocity offset dv (field ``aero_dv``, body axes
    [m/s]) added to v when the model has one (:attr:`flexsim.model.terms.Terms.aero_velocity_offset_m_s`), else V."""
    if not _flag(I, HAS_AERO_DV):
        return vel
    dv = _f1(F, I, AERO_DV)
    out = vel.copy()
    for a in range(3):
        out[a] += dv[a]
    return out


@kernel
def strip_mach(F, I, mach):
    """The Mach number of the strips' compressibility factor: the frozen one (field ``strip_mach``;
    :attr:`flexsim.model.terms.Terms.compressibility_mach`) when the model has one, else the flight's ``mach``."""
    frozen = _f1(F, I, STRIP_MACH)[0]
    return mach if math.isnan(frozen) else frozen


@kernel
def strip_kinematics(F, I, q, xi, vel, lam, u, wind_c, has_wind):
    """Strip velocities and Chebyshev downwash coefficients (:mod:`flexsim.model.coupling` docstring).

    u0 = -d^T A(q) V [m/s];  w_EA = n^T A(q) V + u0 (alpha_el + alpha_r) [m/s] (down, relative to the air:
    the strip air velocity ``wind_c`` (n_s, 3), component axes, enters when ``has_wind``);
    alpha_dot = p^T B V;  w0 = w_EA - a b alpha_dot + u0 beta f0;  w1 = b alpha_dot + u0 beta f1;
    w2 = u0 beta f2;  lambda0 = 1/2 b^T lambda (unsteady strips, Peters et al. 1995).

    Returns p_mat (n_s, n_v), d_mat (n_s, n_v), alpha_el, u0, w_ea, w34 = w0 + w1/2, wc = w34 - lambda0,
    w_moment = w0 - lambda0 - w2/2, alpha_chord (elastic pitch + rigging + flap camber angle), adot
    (arrays (n_s,) unless noted). V is the velocity the strips see (:func:`aero_velocity`).
    """
    vel = aero_velocity(F, I, vel)
    semichord = _f1(F, I, SEMICHORD)
    ab = _f1(F, I, AB)
    incidence = _f1(F, I, INCIDENCE)
    rel = _f2(F, I, REL)
    proj_p = _f2(F, I, PROJ_P)
    proj_n1 = _f3(F, I, PROJ_N1)
    proj_d1 = _f3(F, I, PROJ_D1)
    d = _f2(F, I, D)
    n = _f2(F, I, N)
    flap_sign = _f1(F, I, FLAP_SIGN)
    flap_index = _i1(I, FLAP_INDEX)
    flap_w = _f2(F, I, FLAP_W)
    col_ptr = _i1(I, STRIP_COL_PTR)
    cols = _i1(I, STRIP_COLS)
    n_s = semichord.shape[0]
    nq = q.shape[0]
    nxi = xi.shape[0]
    p_mat = _f2(F, I, PROJ_N0).copy()
    d_mat = _f2(F, I, PROJ_D0).copy()
    lam0 = inflow_lambda0(F, I, lam, n_s)
    alpha_el = np.empty(n_s)
    u0 = np.empty(n_s)
    w_ea = np.empty(n_s)
    w34 = np.empty(n_s)
    wc = np.empty(n_s)
    w_moment = np.empty(n_s)
    alpha_chord = np.empty(n_s)
    adot = np.empty(n_s)
    for j in range(n_s):
        for a in range(3):
            acc_n = 0.0
            acc_d = 0.0
            for k in range(nq):
                acc_n += proj_n1[j, a, k] * q[k]
                acc_d += proj_d1[j, a, k] * q[k]
            p_mat[j, 3 + a] += acc_n
            d_mat[j, 3 + a] += acc_d
        alpha = incidence[j]
        for k in range(nq):
            alpha += rel[j, k] * q[k]
        for k in range(nxi):
            alpha += rel[j, nq + k] * xi[k]
        uj = 0.0
        wn = 0.0
        ad = 0.0
        for t in range(col_ptr[j], col_ptr[j + 1]):  # the strip's non-zero columns (strip_columns)
            i = cols[t]
            uj -= d_mat[j, i] * vel[i]
            wn += p_mat[j, i] * vel[i]
            ad += proj_p[j, i] * vel[i]
        if has_wind:
            for a in range(3):
                uj += d[j, a] * wind_c[j, a]
                wn -= n[j, a] * wind_c[j, a]
        wea = wn + uj * alpha
        flap = flap_sign[j] * u[flap_index[j]] if flap_index[j] > 0 else 0.0
        ub = uj * flap
        w0 = wea - ab[j] * ad + ub * flap_w[j, 0]
        w1 = semichord[j] * ad + ub * flap_w[j, 1]
        w2 = ub * flap_w[j, 2]
        alpha_el[j] = alpha
        u0[j] = uj
        w_ea[j] = wea
        w34[j] = w0 + 0.5 * w1
        wc[j] = w34[j] - lam0[j]
        w_moment[j] = w0 - lam0[j] - 0.5 * w2
        alpha_chord[j] = alpha + flap * (flap_w[j, 0] + 0.5 * flap_w[j, 1])
        adot[j] = ad
    return p_mat, d_mat, alpha_el, u0, w_ea, w34, wc, w_moment, alpha_chord, adot


@kernel
def compressibility_factor(prandtl_glauert, mach):
    """beta with Cl_alpha(M) = Cl_alpha0 / beta: sqrt(1 - M^2), M capped at 0.95 (Prandtl-Glauert; H. Glauert,
    Proc. R. Soc. Lond. A 118, 113-119, 1928; the paper's "Numerical Model"), or 1 without the correction."""
    return math.sqrt(1.0 - min(mach, _MACH_CAP) ** 2) if prandtl_glauert else 1.0


@kernel
def circulatory(F, I, u0, wc, w_moment, alpha_chord, rho, mach):
    """Circulatory lift, moment about the EA, lift x flow angle, drag per unit span, flow angle.

    L = Cl_a rho b u0 (w0 + w1/2 - lambda0) [N/m];  M_EA = (Cl_a/2) rho b^2 u0 (w0 - lambda0 - w2/2) + a b L
    [N];  Cl_a = Cl_a0 / beta with beta = sqrt(1 - min(M, 0.95)^2) (Prandtl-Glauert, Glauert 1928) or 1
    (compressibility "none"). Flow angle relative to the component axes a0 = (w0 + w1/2 - lambda0)/u0 -
    alpha_chord (formed as products with the lift, without dividing by u0); drag = induced L alpha_e
    (1 - Cl_a0/2 pi) + rho u0^2 b cd0 (module docstring of :mod:`flexsim.model.coupling`). The flow-angle terms
    of the resolution are scaled per strip (:class:`flexsim.model.terms.Terms`): lift x flow angle by
    ``tilt_scale``, the drag by ``drag_scale``, plus ``drag_per_lift`` x L (the paper's fin drag law, eq. 30,
    d_v = kappa l_v); 1, 1 and 0 in the full model. beta at :func:`strip_mach`.
    """
    beta = compressibility_factor(_flag(I, PRANDTL_GLAUERT) != 0, strip_mach(F, I, mach))
    beta_i = 1.0 if _flag(I, PAPER) else beta  # induced angle of the compressible lift (physical formulation)
    b = _f1(F, I, SEMICHORD)
    k0 = _f1(F, I, K0)
    ab = _f1(F, I, AB)
    cd0 = _f1(F, I, CD0)
    tilt_scale = _f1(F, I, TILT_SCALE)
    drag_scale = _f1(F, I, DRAG_SCALE)
    drag_per_lift = _f1(F, I, DRAG_PER_LIFT)
    n_s = b.shape[0]
    lift = np.empty(n_s)
    moment = np.empty(n_s)
    lift_tilt = np.empty(n_s)
    drag = np.empty(n_s)
    flow_angle = np.empty(n_s)
    for j in range(n_s):
        two_pi_rho_b = 2.0 * np.pi * rho * b[j] * (k0[j] / beta)
        lift[j] = two_pi_rho_b * u0[j] * wc[j]
        moment[j] = 0.5 * two_pi_rho_b * b[j] * u0[j] * w_moment[j] + ab[j] * lift[j]
        flow = wc[j] - u0[j] * alpha_chord[j]  # u0 x flow angle [m/s]
        lift_tilt[j] = tilt_scale[j] * (two_pi_rho_b * wc[j] * flow)
        drag[j] = (drag_scale[j] * (two_pi_rho_b * wc[j] * wc[j] * (1.0 - k0[j]) / beta_i + rho * u0[j] * u0[j] * b[j] * cd0[j])
                   + drag_per_lift[j] * lift[j])
        flow_angle[j] = flow / max(u0[j], 1.0)
    return lift, moment, lift_tilt, drag, flow_angle


@kernel
def downwash_shift(F, I, vel, u0, wc, mach):
    """Change of the tail strips' normal velocity relative to the air in the wing's downwash, (n_s,) [m/s]:
    -epsilon V (n . z_b) (an air velocity epsilon V along body z at the tail; it shifts w_EA, w0 + w1/2 and the
    moment's downwash, not the inflow forcing or the apparent mass). Zero without a downwash gradient."""
    if not has_downwash(F, I):
        return np.zeros(u0.shape[0])
    vel = aero_velocity(F, I, vel)
    speed = math.sqrt(vel[0] * vel[0] + vel[1] * vel[1] + vel[2] * vel[2])
    beta = compressibility_factor(_flag(I, PRANDTL_GLAUERT) != 0, strip_mach(F, I, mach))
    return downwash_velocity(F, I, u0, wc, speed, beta)


@kernel
def _add_block(m, blk, cols, b0, nb):
    """m[c_t, c_s] += blk[t, s] for t, s < nb, c = cols[b0:b0 + nb]."""
    for t in range(nb):
        row = m[cols[b0 + t]]
        for s in range(nb):
            row[cols[b0 + s]] += blk[t, s]


@kernel
def aero_evaluate(F, I, q, xi, vel, lam, u, rho, mach, wind_c, has_wind):
    """Added mass M_a (n_v, n_v), explicit generalized aerodynamic force Q_a (n_v,) and the inflow terms.

    Eq. (28), force resolution "physical": f = L (-n - a0 d) + D (d - a0 n); "paper" on wing/stabilizer
    strips: f = -L n + L (n_x / d_x) d. Each strip's force and moment enter as width * G^T [f; M_EA p]
    (eqs. 17-24); the tail strips in the wing's downwash (:func:`downwash_shift`). Apparent mass (pi rho b^2,
    reference section 1.4): w_EA_dot = row0 V_dot + w_ea_x, with
    row0 = n^T A - alpha_el d^T A - a b p^T B and the explicit part w_ea_x (omega x q-derivative terms and
    u0 times the elastic pitch rate). M_a = sum_j rho pr_w (n^T A - a b p^T B)^T row0 + rho sum_j pr_w b^2/8
    (p^T B)^T (p^T B), the last sum constant per unit density (field ``apparent_pitch``, built by
    :class:`flexsim.model.coupling.AeroCoupling`).

    Returns m_a, q_a, row0 (n_s, n_v), w_ea_x (n_s,), u0 (n_s,).
    """
    p_mat, d_mat, alpha_el, u0, w_ea, w34, wc, w_moment, alpha_chord, adot = strip_kinematics(
        F, I, q, xi, vel, lam, u, wind_c, has_wind)
    shift = downwash_shift(F, I, vel, u0, wc, mach)  # the tail in the wing's downwash
    for j in range(shift.shape[0]):
        wc[j] += shift[j]
        w_moment[j] += shift[j]
    r_mat = _f2(F, I, PROJ_P)
    ab = _f1(F, I, AB)
    b = _f1(F, I, SEMICHORD)
    lift, moment, lift_tilt, drag, flow_angle = circulatory(F, I, u0, wc, w_moment, alpha_chord, rho, mach)
    w = _f1(F, I, WIDTH)
    rel = _f2(F, I, REL)
    pr_w0 = _f1(F, I, PR_W)
    paper = _f1(F, I, PAPER_STRIPS)
    n_over_d_x = _f1(F, I, N_OVER_D_X)
    proj_n1 = _f3(F, I, PROJ_N1)
    proj_d1 = _f3(F, I, PROJ_D1)
    is_paper = _flag(I, PAPER) != 0
    nq = q.shape[0]
    n_el = rel.shape[1]
    n_s = lift.shape[0]
    n_v = vel.shape[0]
    col_ptr = _i1(I, STRIP_COL_PTR)
    cols = _i1(I, STRIP_COLS)
    w_ea_x = np.empty(n_s)
    right = np.zeros((n_s, n_v))  # row0 (zero outside each strip's columns, as the fields it is made of)
    m_a = np.zeros((n_v, n_v))
    q_a = np.zeros(n_v)
    # M_a accumulates per run of consecutive strips with the same columns (a component's strips) on those
    # columns, in blk (nb x nb), added into m_a once per run (the columns of strip j: cols[lo:lo + nc])
    blk = np.zeros((n_v, n_v))
    nb = 0  # columns of the current run (0: none yet)
    b0 = 0  # its first entry in cols
    lc = np.empty(n_v)  # the strip's pr_w (n^T A - a b p^T B) and row0 on its columns
    rc = np.empty(n_v)
    for j in range(n_s):
        c_n = -lift[j] - drag[j] * flow_angle[j]  # eq. (28): f = L (-n - a0 d) + D (d - a0 n)
        c_d = drag[j] - lift_tilt[j]
        if is_paper and paper[j] != 0.0:  # eq. (28) with d = l alpha_i0: no body-x component
            c_n = -lift[j]
            c_d = lift[j] * n_over_d_x[j]
        pdot = 0.0
        ddot = 0.0
        for a in range(3):
            pn = 0.0
            pd = 0.0
            for k in range(nq):
                pn += proj_n1[j, a, k] * vel[6 + k]
                pd += proj_d1[j, a, k] * vel[6 + k]
            pdot += pn * vel[3 + a]
            ddot += pd * vel[3 + a]
        relv = 0.0
        for e in range(n_el):
            relv += rel[j, e] * vel[6 + e]
        wx = pdot - alpha_el[j] * ddot + u0[j] * relv
        prw = rho * pr_w0[j]
        w_ea_x[j] = wx
        g_n = w[j] * c_n - prw * wx
        g_d = w[j] * c_d
        g_r = w[j] * moment[j] + ab[j] * prw * wx
        # the strip's rows are zero outside its columns (strip_columns): M_a += left_j^T right_j and
        # Q_a += [p; d; r]_j^T [g_n, g_d, g_r] over those columns only
        lo = col_ptr[j]
        nc = col_ptr[j + 1] - lo
        for t in range(nc):
            i = cols[lo + t]
            lv = p_mat[j, i] - ab[j] * r_mat[j, i]
            rv = lv - alpha_el[j] * d_mat[j, i]
            right[j, i] = rv
            lc[t] = prw * lv
            rc[t] = rv
            q_a[i] += p_mat[j, i] * g_n + d_mat[j, i] * g_d + r_mat[j, i] * g_r
        same = nc == nb
        if same:
            for t in range(nc):
                if cols[lo + t] != cols[b0 + t]:
                    same = False
                    break
        if not same:
            _add_block(m_a, blk, cols, b0, nb)
            nb = nc
            b0 = lo
            for t in range(nc):
                for s in range(nc):
                    blk[t, s] = 0.0
        for t in range(nc):
            lt = lc[t]
            for s in range(nc):
                blk[t, s] += lt * rc[s]
    _add_block(m_a, blk, cols, b0, nb)
    # M_a = left^T right + rho sum_j pr_w b^2/8 (p^T B)^T (p^T B), the second term constant per unit density
    pitch = _f2(F, I, APPARENT_PITCH)
    for i in range(n_v):
        for k in range(n_v):
            m_a[i, k] += rho * pitch[i, k]
    return m_a, q_a, right, w_ea_x, u0


@kernel
def inflow_rate(F, I, row0, w_ea_x, u0, lam, vdot):
    """Finite-state inflow derivative lambda_dot (n_u N,) [m/s^2] of the strips (:func:`flexsim._kernels.peters.
    inflow_derivative` with the strips' semichords and pitch rows)."""
    return inflow_derivative(F, I, row0, w_ea_x, u0, lam, vdot, _f1(F, I, SEMICHORD), _f2(F, I, PROJ_P))
