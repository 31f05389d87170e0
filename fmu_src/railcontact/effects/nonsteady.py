"""Non-steady rolling (Nielsen Ch. 7): relaxed creepages with a relaxation length, a state."""

from __future__ import annotations

import math

from .. import nonsteady
from ..creep3d import creep_coefficients
from .base import Effect, EffectUnavailable

__all__ = ["NonSteady"]


class NonSteady(Effect):
    r"""Non-steady rolling (Nielsen Ch. 7) as a relaxation-length law with state.

    The creep forces are the steady ones at *relaxed creepages* ``xi_e`` that follow the input
    creepages through ``(sigma / V) d xi_e / dt + xi_e = xi`` with the relaxation length
    ``sigma = a0* (Lambda(r_a0) - 1)`` (:func:`railcontact.nonsteady.relaxation_length`: the
    first-order term of the thesis' transfer function (7.53)-(7.54), Carter (7.20) or Johnson
    (7.15) displacement model, ``pseudo_width_ratio`` b/a0). Since the force is a steady force
    at some creepage, ``|F| <= mu N`` holds by construction.

    In a step the relaxed creepages are advanced over the rolled distance ``V h`` (``h`` =
    :attr:`ContactPoint.step_size`, set by the slave; inputs held, sample and hold) with the
    exact exponential and the predictor-corrector for the state-dependent sigma,
    :func:`railcontact.nonsteady.relaxation_step` (unconditionally stable, no overshoot, second
    order, sub-steps where sigma changes fast; error bound
    :func:`railcontact.nonsteady.relaxation_step_error_bound`). sigma is
    evaluated at the relaxed state, from the stick ratio the creep effect reports for it:

    * line contact (Carter, the thesis' 2-D setting): ``r_a0 = max(0, 1 - |xi_e| / xi_c)``,
      ``xi_c = mu a0 / R`` (Eqs. (2.51), (2.54)); only the longitudinal creepage is relaxed
      (the 2-D theory has no lateral force; lateral creepage and spin pass through);
    * elliptic contact (Creep3D): the strip-theory extension of the 2-D result. The centre
      strip y = 0 has half-length a0 and ``r_a0 = 1 - min(z, 1)`` (Eq. (2.83), z the
      normalised creepage of the strip or modified strip theory, Kalker's coefficients for
      "she", "modified_strip" and "exact"; 1 for the linear theory); xi_x, xi_y and spin are
      relaxed with that one sigma (the same relaxed state feeds the strip theory, whose strips
      then all lag by the centre strip's sigma -- an approximation: the thesis treats 2-D only).

    Initialisation (the first evaluation, ``exit_initialization_mode``) is the steady state,
    ``xi_e = xi``. Without contact (N = 0) the contact is stress free, ``xi_e = 0`` (a contact
    that closes again builds its force up over sigma). ``V = 0`` holds the state; full sliding
    (``r_a0 = 0``, sigma = 0) has no memory, ``xi_e = xi``. Outputs: ``relaxation_length``
    (sigma at the relaxed state after the step), ``relaxed_creepage_longitudinal``,
    ``relaxed_creepage_lateral``, ``relaxed_spin``. The relaxed creepages are internal state
    (:meth:`get_state`).

    Velocity-dependent friction reads the relaxed creepage like any creep effect; sigma is then
    still that of Coulomb friction with mu = ``friction.friction_coefficient`` (Ch. 7 assumes
    Coulomb friction). The scene rejects nonsteady with corrugation or wear (their Ch. 4
    models are quasi-static).
    """

    name = "nonsteady"

    def __init__(self, scene, **_):
        super().__init__()
        opts = scene.effects["nonsteady"]
        if opts["source"] != "analytic":       # (scene_from_dict rejects it already)
            raise EffectUnavailable("effect nonsteady (table) not available in this build (the "
                                    "relaxation length is a closed form)")
        self.model = opts["model"]
        self.pseudo_width_ratio = opts["pseudo_width_ratio"]
        self._sigma = nonsteady.relaxation_length_function(scene.poisson_ratio,
                                                        self.pseudo_width_ratio, self.model)
        self._relaxation_step = nonsteady.relaxation_step
        self._line = scene.geometry["kind"] == "line"
        method = scene.effects["creep"]["method"]
        self._full_stick = method == "linear"
        if self._line:
            self._inv_radius = 1.0 / scene.geometry["radius"]
        else:
            self._coefficients = creep_coefficients
            self._method = "strip" if method == "strip" else "modified_strip"
            self._nu = scene.poisson_ratio
            self._w_sat_per_mu_p0 = math.pi ** 2 * (1.0 + self._nu) / scene.youngs_modulus
            self._shape = (None, None)             # (a0/b0, (C11, C22, C23)) of the last step
        #: Relaxed (xi_x, xi_y, phi) after the last step; None before the first evaluation.
        self.relaxed = None
        self._inputs = None

    def _relaxation_length_function(self, c):
        """``sigma(state)`` [m] for the contact of this step: :func:`relaxation_length_function`
        at the r_a0 the creep theory gives for the relaxed creepages ``state``."""
        mu, a0, sig = c.friction_coefficient, c.a0, self._sigma
        if self._line:
            xi_c = mu * a0 * self._inv_radius                       # Eq. (2.54)

            def sigma_of(state):
                if xi_c > 0.0:
                    f = abs(state[0]) / xi_c
                    return sig(a0, 1.0 - f) if f < 1.0 else 0.0     # Eq. (2.51)
                return sig(a0, 1.0) if state[0] == 0.0 else 0.0
            return sigma_of
        if self._full_stick:
            full = sig(a0, 1.0)
            return lambda state: full
        b0 = c.b0
        g = a0 / b0 if b0 > 0.0 else 1.0
        last = self._shape[0]
        # (the Hertz scaling keeps a0/b0 up to rounding: Kalker's coefficients are computed
        # again only when the shape really changes; their change over 1e-12 is far below it)
        if last is None or abs(g - last) > 1e-12 * last:
            coefs = self._coefficients(a0, b0, self._nu, self._method)
            self._shape = (g, tuple(float(v) for v in coefs))
        c11, c22, c23 = self._shape[1]
        c23 *= math.sqrt(a0 * b0)
        w_sat = self._w_sat_per_mu_p0 * mu * c.p0            # Eqs. (2.93)-(2.96), (2.99)

        def sigma_of(state, _hypot=math.hypot):
            w = _hypot(c11 * state[0], c22 * state[1] + c23 * state[2])
            if w_sat > 0.0:
                z = w / w_sat
                return sig(a0, 1.0 - z) if z < 1.0 else 0.0     # Eq. (2.83), y = 0
            return sig(a0, 1.0) if w == 0.0 else 0.0
        return sigma_of

    def step(self, c):
        self.calls += 1
        xi = (c.creepage_longitudinal, c.creepage_lateral, c.spin)
        self._inputs = xi
        if c.normal_force <= 0.0:                  # no contact: stress free, no length
            new = (0.0, xi[1], xi[2]) if self._line else (0.0, 0.0, 0.0)
            sigma = 0.0
        else:
            sigma_of = self._relaxation_length_function(c)
            old = self.relaxed
            if old is None:                        # initialisation: the steady state
                new = xi
            else:
                if self._line:
                    old = (old[0], xi[1], xi[2])
                new = self._relaxation_step(old, xi, c.rolling_speed * c.step_size, sigma_of)
            sigma = sigma_of(new)
        self.relaxed = new
        c.relaxation_length = sigma
        (c.relaxed_creepage_longitudinal, c.relaxed_creepage_lateral,
         c.relaxed_spin) = new
        c.creepage_longitudinal, c.creepage_lateral, c.spin = new

    def finish(self, c):
        """After the last effect: the creepage fields are the importer's inputs again.

        (If an effect in between raises, the fields keep the relaxed creepages; the FMU then
        reports the error and the instance is not stepped further.)"""
        if self._inputs is not None:
            c.creepage_longitudinal, c.creepage_lateral, c.spin = self._inputs

    def get_state(self):
        return {"calls": self.calls,
                "relaxed": None if self.relaxed is None else list(self.relaxed),
                "inputs": None if self._inputs is None else list(self._inputs)}

    def set_state(self, state):
        self.calls = int(state["calls"])
        self.relaxed = None if state["relaxed"] is None else tuple(state["relaxed"])
        self._inputs = None if state["inputs"] is None else tuple(state["inputs"])
