"""Tests of the two tables of issue 5 added to tablegen: ``nonsteady_transfer`` (Nielsen Ch. 7)
and ``velocity_friction`` (Nielsen Sec. 5.3).

Each shipped file in ``tables/`` is compared with the direct function it tabulates
(:func:`railcontact.nonsteady.nonsteady_amplitude_phase_normalised`,
:func:`railcontact.friction.velocity_friction_creep_force_normalised`) at seeded random
off-grid points, to the accuracy recorded in the file; plus independent limits (quasi-static
H = 1, Carter's closed form 1 - (1 - chi)^2 on the m = 1 and kappa = 0 planes) and the Coulomb
bound |T|/(mu_0 N) <= max(1, m).
"""

import shutil
import subprocess

import numpy as np
import pytest

from railcontact.tables import Table, default_table_path, tables_directory
from tablegen.spec import get_spec

NONSTEADY = tables_directory() / "nonsteady_transfer.nc"
FRICTION = tables_directory() / "velocity_friction.nc"


# --------------------------------------------------------------------------------------------
# nonsteady_transfer
# --------------------------------------------------------------------------------------------

def test_nonsteady_spec_grid_and_function_shape():
    spec = get_spec("nonsteady_transfer")
    axes, pts = spec.grid("coarse")
    assert [a.name for a in axes] == ["a0_over_wavelength", "stick_ratio"]
    assert axes[0].nodes[0] == 0.0 and axes[0].nodes[-1] == pytest.approx(1.0)
    assert axes[1].nodes[0] == pytest.approx(0.02) and axes[1].nodes[-1] == pytest.approx(1.0)
    out = spec.function(pts[:7])
    assert out.shape == (7, 2) and np.all(np.isfinite(out))


@pytest.mark.skipif(not NONSTEADY.exists(), reason="tables/nonsteady_transfer.nc not built")
def test_nonsteady_table_against_direct_function():
    from railcontact.nonsteady import nonsteady_amplitude_phase_normalised

    table = Table.from_file(default_table_path("nonsteady_transfer"))
    assert table.variables == ["amplitude_ratio", "phase"]
    acc = table.accuracy()
    rng = np.random.default_rng(505)
    n = 3000
    ratio = np.where(rng.random(n) < 0.5, np.exp(rng.uniform(np.log(1e-3), 0.0, n)),
                     rng.uniform(0.0, 1.0, n))            # half log-uniform, half uniform
    r = np.exp(rng.uniform(np.log(0.02), 0.0, n))
    amp, phase = nonsteady_amplitude_phase_normalised(ratio, r, poisson_ratio=0.28,
                                                      pseudo_width_ratio=20.0, model="carter")
    got = table.spline.evaluate(np.column_stack([ratio, r]))
    for k, (name, want) in enumerate((("amplitude_ratio", amp), ("phase", phase))):
        err = np.max(np.abs(got[:, k] - want))
        assert acc[name]["max_abs_error"] <= 1e-4
        assert err <= 1e-4 and err <= 2.0 * acc[name]["max_abs_error"], (name, err)
    # quasi-static limit a0/L -> 0: H -> 1 (Carter's slope), a node of the table
    r0 = np.linspace(0.02, 1.0, 50)
    zero = table.spline.evaluate(np.column_stack([np.zeros_like(r0), r0]))
    assert np.max(np.abs(zero[:, 0] - 1.0)) < 1e-12 and np.max(np.abs(zero[:, 1])) < 1e-12
    # no 2 pi wrap of the phase anywhere on the grid
    assert np.all(table.values["phase"] <= 1e-15) and np.all(table.values["phase"] > -np.pi / 2 - 0.1)
    with pytest.raises(ValueError, match="stick_ratio must be in"):
        table("phase", [[0.1, 0.01]])
    with pytest.raises(ValueError, match="a0_over_wavelength must be in"):
        table("phase", [[1.5, 0.5]])
    assert table.attrs["model"] == "carter"
    assert table.attrs["poisson_ratio"] == pytest.approx(0.28)


# --------------------------------------------------------------------------------------------
# velocity_friction
# --------------------------------------------------------------------------------------------

def test_velocity_friction_spec_grid():
    spec = get_spec("velocity_friction")
    axes, pts = spec.grid("default")
    assert [a.name for a in axes] == ["friction_ratio", "kappa_normalised", "creepage_ratio"]
    assert pts.shape == (13 * 13 * 30, 3) and spec.chunk_size == 30   # one curve per task
    assert 1.0 in axes[0].nodes and axes[1].nodes[0] == 0.0 and axes[2].nodes[0] == 0.0


@pytest.mark.skipif(not FRICTION.exists(), reason="tables/velocity_friction.nc not built")
def test_velocity_friction_table_against_direct_solver():
    from railcontact.friction import velocity_friction_creep_force_normalised

    table = Table.from_file(default_table_path("velocity_friction"))
    acc = table.accuracy()["force_ratio"]["max_abs_error"]
    assert 0.0 < acc <= 1e-3
    rng = np.random.default_rng(5316)
    n = 5                                            # each direct call builds a solver (slow)
    pts = np.column_stack([rng.uniform(0.2, 1.8, n), rng.uniform(0.0, 6.0, n),
                           rng.uniform(0.0, 3.0, n)])
    want = -velocity_friction_creep_force_normalised(pts[:, 2], pts[:, 0], pts[:, 1],
                                                     degree=128, tol=1e-10)
    got = table("force_ratio", pts)
    assert np.max(np.abs(got - want)) <= acc, (got, want)
    with pytest.raises(ValueError, match="creepage_ratio must be in"):
        table("force_ratio", [[0.5, 1.0, 3.5]])
    with pytest.raises(ValueError, match="kappa_normalised must be in"):
        table("force_ratio", [[0.5, 7.0, 0.5]])


@pytest.mark.skipif(not FRICTION.exists(), reason="tables/velocity_friction.nc not built")
def test_velocity_friction_table_carter_planes_and_coulomb_bound():
    """m = 1 and kappa = 0 are Carter (independent closed form); |T| <= max(1, m) mu_0 N."""
    table = Table.from_file(default_table_path("velocity_friction"))
    acc = table.accuracy()["force_ratio"]["max_abs_error"]
    rng = np.random.default_rng(99)
    chi = rng.uniform(0.0, 3.0, 4000)
    carter = 1.0 - (1.0 - np.minimum(chi, 1.0)) ** 2
    for m, kap in ((1.0, rng.uniform(0.0, 6.0, 4000)), (rng.uniform(0.2, 1.8, 4000), 0.0)):
        pts = np.column_stack(np.broadcast_arrays(m, kap, chi))
        assert np.max(np.abs(table("force_ratio", pts) - carter)) <= acc
    # dense random points in the whole box: 0 <= force_ratio <= max(1, m) (to the recorded
    # accuracy: the C2 spline rounds the full-sliding kink, which is not on a grid line)
    n = 200_000
    pts = np.column_stack([rng.uniform(0.2, 1.8, n), rng.uniform(0.0, 6.0, n),
                           rng.uniform(0.0, 3.0, n)])
    f = table("force_ratio", pts)
    assert f.min() >= -acc
    assert np.max(f - np.maximum(1.0, pts[:, 0])) <= acc


# --------------------------------------------------------------------------------------------
# Both files: a non-Python reader
# --------------------------------------------------------------------------------------------

@pytest.mark.skipif(shutil.which("ncdump") is None, reason="ncdump not installed")
@pytest.mark.parametrize("path", [NONSTEADY, FRICTION], ids=lambda p: p.stem)
def test_ncdump_reads_new_tables(path):
    if not path.exists():
        pytest.skip(f"{path.name} not built")
    out = subprocess.run(["ncdump", "-h", str(path)], capture_output=True, text=True,
                         check=True).stdout
    assert ":Conventions = \"CF-1.8\"" in out and "max_abs_error" in out
