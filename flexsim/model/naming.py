"""Names of the state entries of a model, from the one output vocabulary (:mod:`flexsim.io.vocabulary`).

Used by everything that labels a state vector: the output layer and flight logs
(:class:`flexsim.sim.outputs.OutputMaps`), the environments, and linear models
(:class:`flexsim.linear.linearize.LinearModel`). Order: :class:`flexsim.model.layout.StateLayout`
(position, Euler angles, q, xi, v, omega, s, eta, inflow), blocks absent in the model variant left out.
"""

from __future__ import annotations

from flexsim.io.vocabulary import check_names

__all__ = ["state_names"]


def state_names(model) -> tuple[str, ...]:
    """One vocabulary name per state entry of ``model`` (an :class:`~flexsim.model.aircraft_model.AircraftModel`):
    ``x_north_m``, ``phi_rad``, ``q_<component>_<k>_m``, ``xi_<component>_<k>_rad``, ``v_x_m_s``, ``omega_x_rad_s``,
    ``s_<component>_<k>_m_s``, ``eta_<component>_<k>_rad_s``, ``lambda_<component>_<strip>_<n>_m_s`` (strips numbered
    from 01 within each component, inflow states from 1).
    """
    lay, dofs = model.layout, model.structure.dofs
    names: list[str] = []
    if lay.rigid:
        names += ["x_north_m", "y_east_m", "z_down_m", "phi_rad", "theta_rad", "psi_rad"]
    elastic = lay.nq + lay.nxi > 0

    def per_component(table: dict[str, slice], prefix: str, unit: str) -> list[str]:
        return [f"{prefix}_{c}_{k + 1}_{unit}" for c in dofs.component_names
                for k in range(table[c].stop - table[c].start)]

    if elastic:
        names += per_component(dofs.bending, "q", "m") + per_component(dofs.torsion, "xi", "rad")
    if lay.rigid:
        names += ["v_x_m_s", "v_y_m_s", "v_z_m_s", "omega_x_rad_s", "omega_y_rad_s", "omega_z_rad_s"]
    if elastic:
        names += per_component(dofs.bending, "s", "m_s") + per_component(dofs.torsion, "eta", "rad_s")
    if lay.n_inflow:
        strips = model.aero.strips
        n_per = model.aero.options.n_inflow
        counter: dict[str, int] = {}
        for j, comp in enumerate(strips.component):
            counter[comp] = counter.get(comp, 0) + 1
            if strips.unsteady[j]:
                names += [f"lambda_{comp}_{counter[comp]:02d}_{n + 1}_m_s" for n in range(n_per)]
    if len(names) != lay.n_states:
        raise RuntimeError(f"state names: built {len(names)} names for {lay.n_states} states")
    return check_names("state", names)
