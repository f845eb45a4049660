"""The common result every element-stiffness estimator returns."""

from __future__ import annotations

from dataclasses import asdict, dataclass


@dataclass(frozen=True)
class StiffnessResult:
    """Tip stiffness of one sensing element for a force normal to the contact face.

    Attributes:
        element: paper element number (None for a bare geometry).
        model: estimator name: closed-form, beam, fem2d or fem3d.
        stiffness_N_per_mm: K, tip force / tip deflection along +y (N/mm).
        face_strain_per_N: the face strain at the gauge grid's centre: the flat top
            face over the notch centre, at mid-width, under the bonded gauge's glue line
            and carrier when the element carries one (the bare face otherwise), per
            newton of tip force (1/N, magnitude; x 1e6 for microstrain/N). The same
            quantity at every level: fem2d and fem3d read it with the layer meshed, the
            closed form and the beam level carry their bare section's through the
            layer's transformed section
            (:func:`tactcad.mechanics.closed_form.face_strain_factor`). Not what the
            grid reads (its plane lies the layer's height above the face, and it
            averages over its area): that is ``grid_strain_per_N`` or the read-out's.
        error_estimate_rel: estimated relative error of K (e.g. Richardson
            estimate for FEM, fitted residual for corrected closed forms).
        wall_time_s: wall-clock time of the evaluation (s).
        grid_strain_per_N: the mean strain on the grid's plane (the layer's top) over
            the grid per newton (1/N, signed as every command prints it: negative where a
            tip force shortens the grid; :func:`tactcad.mechanics.readout_chain.
            grid_strain_per_N`'s ``"grid"``) of an element carrying a gauge: fem2d and
            fem3d read it with the layer meshed; at the closed form and the beam level the
            estimator gives None and :meth:`tactcad.api.Element.stiffness` the read-out's.
            None for a bare element.
    """

    element: int | None
    model: str
    stiffness_N_per_mm: float
    face_strain_per_N: float
    error_estimate_rel: float
    wall_time_s: float
    grid_strain_per_N: float | None = None

    def as_json(self) -> dict:
        return asdict(self)
