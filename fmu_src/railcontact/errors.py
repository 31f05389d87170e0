"""Exceptions of the package (kept free of heavy imports, so that ``import railcontact`` can
export them without loading the compiled solvers)."""

__all__ = ["RollingConvergenceError"]


class RollingConvergenceError(RuntimeError):
    """An iterative contact solver did not reach its tolerance.

    Raised by the exact 3-D rolling solver (:func:`railcontact.reference.rolling3d.solve_rolling_3d`
    and ``method="exact"`` of :func:`railcontact.creep_force_3d` /
    :func:`railcontact.creep_solution_3d`) when the Gauss-Seidel iteration of the tangential
    problem, or the conjugate-gradient iteration of the normal problem, stops at its iteration
    limit above the tolerance. The message names the residual, the tolerance, the limit and
    the case. A RuntimeError: the input was valid, the numerical method failed; never
    returned as a silently unconverged answer.
    """
