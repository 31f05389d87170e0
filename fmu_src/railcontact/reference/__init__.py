"""Independent discretised half-space solvers: the project's "exact theory".

Used by the tests and the accuracy report to check every closed form; never by the FMU's hot path.
"""
