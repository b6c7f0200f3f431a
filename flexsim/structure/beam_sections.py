"""A strain-based beam from an aircraft component's section tables (e.g. the bundled Pazy wing).

The aircraft format's section tables (:class:`flexsim.aircraft.sections.SectionTable`) are linear between
stations; :class:`~flexsim.structure.strain_beam.BeamProperties` is uniform by element over equal elements. Each
element gets the integral of the tables over its span (piecewise 3-point Gauss-Legendre between the stations inside
it, exact for the products of two linear pieces):

* mass per length: the element's mass over its length (total mass kept exactly);
* mass-centre offset: mass-weighted, sign changed (the tables: aft of the elastic axis; the beam: ahead, along
  ``e2``);
* inertias about the mass centre from the tables' inertias about the elastic axis by the parallel-axis theorem:
  torsion ``I_EA − m x_cg²``, flapwise rotary ``flap_inertia_kg_m`` (its axis, along the chord, passes through the
  offset mass centre), chordwise rotary ``I_EA − I_flap − m x_cg²`` (perpendicular-axis theorem, as the tables'
  docstring states);
* stiffnesses: the compliance average ``(∫ 1/EI dx / l)⁻¹`` (elements in series: the element's end rotation under
  a moment equals that of the tables).

Units SI. Source of the convention: docs/aircraft-format.md (section tables) and the strain-based beam of Su &
Cesnik (2011), :mod:`flexsim.structure.strain_beam`.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from flexsim.aircraft.sections import SectionTable
from flexsim.structure.strain_beam import BeamProperties

__all__ = ["beam_from_sections", "element_means"]


def _element_integrals(station: NDArray, values: dict[str, NDArray], edges: NDArray) -> dict[str, NDArray]:
    """``∫ f dx`` over each element ``[edges[i], edges[i+1]]`` for each expression in ``values`` (callables)."""
    xg, wg = np.polynomial.legendre.leggauss(3)
    out = {name: np.zeros(edges.size - 1) for name in values}
    for i in range(edges.size - 1):
        lo, hi = edges[i], edges[i + 1]
        cuts = np.unique(np.concatenate([[lo, hi], station[(station > lo) & (station < hi)]]))
        for a, b in zip(cuts[:-1], cuts[1:]):
            x = 0.5 * (a + b) + 0.5 * (b - a) * xg
            for name, f in values.items():
                out[name][i] += 0.5 * (b - a) * np.sum(wg * f(x))
    return out


def beam_from_sections(sections: SectionTable, n_elements: int, **beam_options) -> BeamProperties:
    """Equal-element :class:`BeamProperties` from ``sections`` (module docstring), clamped at station 0.

    Parameters
    ----------
    sections : SectionTable
        The component's tables; ``ei_chord_nm2`` must be given (the beam bends in both planes); ``ea_n`` and
        ``flap_inertia_kg_m`` are used when given (None: inextensible; no flapwise rotary inertia).
    n_elements : int
        Number of equal elements, 1-1000.
    **beam_options
        Other :class:`BeamProperties` fields (``root_position_m``, ``root_rotation``, ``gauss_points``).

    Returns
    -------
    BeamProperties
    """
    if not isinstance(sections, SectionTable):
        raise TypeError(f"sections is a {type(sections).__name__}: must be a SectionTable (aircraft component)")
    if sections.ei_chord_nm2 is None:
        raise ValueError("sections.ei_chord_nm2 is not given: the geometrically exact beam needs the chordwise "
                         "bending stiffness [N m^2]")
    if isinstance(n_elements, bool) or not isinstance(n_elements, (int, np.integer)) or not 1 <= n_elements <= 1000:
        raise ValueError(f"n_elements = {n_elements!r}: must be an integer in 1-1000")
    s = sections
    x = np.asarray(s.station_m, dtype=float)
    length = float(x[-1])
    edges = np.linspace(0.0, length, int(n_elements) + 1)

    def lin(arr):
        return lambda z: np.interp(z, x, np.asarray(arr, dtype=float))

    m, cg, it = lin(s.mass_kg_per_m), lin(s.cg_offset_m), lin(s.torsional_inertia_kg_m)
    flap = lin(s.flap_inertia_kg_m if s.flap_inertia_kg_m is not None else np.zeros_like(x))
    exprs = {"m": m, "mx": lambda z: m(z) * cg(z), "it": it, "flap": flap,
             "cgj": lambda z: 1.0 / lin(s.gj_nm2)(z), "cei": lambda z: 1.0 / lin(s.ei_nm2)(z),
             "cch": lambda z: 1.0 / lin(s.ei_chord_nm2)(z)}
    if s.ea_n is not None:
        exprs["cea"] = lambda z: 1.0 / lin(s.ea_n)(z)
    ints = _element_integrals(x, exprs, edges)
    le = np.diff(edges)
    mass = ints["m"] / le
    x_cg = ints["mx"] / ints["m"]  # aft of the elastic axis [m]
    i_ea, i_flap = ints["it"] / le, ints["flap"] / le
    torsion = i_ea - mass * x_cg**2
    chord = i_ea - i_flap - mass * x_cg**2
    return BeamProperties(
        length_m=length, n_elements=int(n_elements), gj_nm2=le / ints["cgj"], ei_flap_nm2=le / ints["cei"],
        ei_chord_nm2=le / ints["cch"], ea_n=(le / ints["cea"]) if "cea" in ints else None,
        mass_kg_per_m=mass, cg_offset_m=-x_cg, torsion_inertia_kg_m=torsion, flap_inertia_kg_m=i_flap,
        chord_inertia_kg_m=np.maximum(chord, 0.0), **beam_options)


def element_means(station_m, values, n_elements: int) -> NDArray:
    """Mean over each of ``n_elements`` equal elements of a table linear between stations.

    Parameters
    ----------
    station_m : array_like, shape (k,)
        Stations, strictly increasing from 0 to the beam's length [m].
    values : array_like, shape (k,)
        Values at the stations (any unit).
    n_elements : int

    Returns
    -------
    ndarray, shape (n_elements,)
        ``∫ f dx / l`` per element (exact for the piecewise-linear table), in the unit of ``values``.
    """
    x, v = np.asarray(station_m, dtype=float), np.asarray(values, dtype=float)
    if x.ndim != 1 or x.size < 2 or v.shape != x.shape or x[0] != 0.0 or np.any(np.diff(x) <= 0):
        raise ValueError(f"station_m ({x.size} values) and values ({v.size}): stations must increase strictly "
                         "from 0, one value each")
    if isinstance(n_elements, bool) or not isinstance(n_elements, (int, np.integer)) or not 1 <= n_elements <= 1000:
        raise ValueError(f"n_elements = {n_elements!r}: must be an integer in 1-1000")
    edges = np.linspace(0.0, x[-1], int(n_elements) + 1)
    return _element_integrals(x, {"f": lambda z: np.interp(z, x, v)}, edges)["f"] / np.diff(edges)
