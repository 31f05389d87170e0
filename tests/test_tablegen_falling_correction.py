"""The falling-friction correction table's builder (tablegen.falling_correction): resumable
chunks, and nodes added later along ln(a0/b0), tau or s costing only their own solves.

The exact solves (hours) are replaced by a cheap function of the node here; what is checked
is the bookkeeping: which chunks a run computes, that a resumed or extended build reuses
what is there, and that the written file holds the exact values minus the model's.
"""

import numpy as np
import pytest

netCDF4 = pytest.importorskip("netCDF4")
pytest.importorskip("xarray")

import tablegen.falling_correction as fc  # noqa: E402


def _small_nodes(log_aspect_ratio=(-1.0, -0.3, 0.4, 1.0), spin_coordinate=(0.0, 1.0, 2.0, 4.0),
                creepage_coordinate=(0.0, 0.3, 0.6, 1.0)):
    return {
        "log_aspect_ratio": np.array(log_aspect_ratio),
        "poisson_ratio": np.array([0.0, 0.5]),
        "creepage_coordinate": np.array(creepage_coordinate),
        "creepage_angle": np.linspace(-np.pi, np.pi, 5)[:-1],
        "spin_coordinate": np.array(spin_coordinate),
        "friction_ratio": np.array([0.3, 0.65, 1.0]),
        "friction_decay_number": np.array([0.0, 0.5, 1.125, 2.0]),
    }


def _exact(lg, nu, s, th, tau, m, kn):
    """A stand-in for the exact solve: smooth in the node, NaN at one (an unconverged
    node)."""
    if m == 0.3 and kn == 2.0 and tau == 4.0 and s == 0.3 and th == 0.0:
        return np.full(3, np.nan)
    if m == 0.65 and kn == 0.5 and tau == 2.0 and s in (0.3, 0.6) and th == 0.0:
        return np.full(3, np.nan)       # (two along s: a node added between is not tried)
    return np.array([0.01 * lg + 0.02 * s, 0.003 * tau * (1.0 - m), 0.001 * kn + 0.002 * nu])


def _model(lg, nu, s, th, tau, m, kn):
    return np.stack([0.001 * np.asarray(lg), 0.0 * np.asarray(nu), 0.0005 * np.asarray(kn)])


def _no_ladder(*args):
    raise AssertionError("a ladder solve was made")


def _ladder(lg, nu, s, th, tau, m, kn):
    """A stand-in for the ladder of grids: converges where the exact solve did not, but for
    one node, with values a little off the stand-in exact's."""
    if m == 0.65 and s == 0.6:
        return np.full(3, np.nan)
    return np.array([0.01 * lg + 0.02 * s + 1e-3, 0.003 * tau * (1.0 - m), 0.001 * kn])


@pytest.fixture
def builder(monkeypatch):
    monkeypatch.setattr(fc, "NODES", _small_nodes())
    monkeypatch.setattr(fc, "exact_point", _exact)
    monkeypatch.setattr(fc, "model_points", _model)
    monkeypatch.setattr(fc, "LADDER_TAU_MAX", -1.0)     # no ladder unless a test asks
    monkeypatch.setattr(fc, "ladder_point", _no_ladder)
    monkeypatch.setattr(fc, "SKIP_AFTER_UNCONVERGED_TAU", False)   # (unless a test asks)
    monkeypatch.setattr(fc, "FRICTION_RATIO_NODES_ADDED", {"smooth": (), "polach": ()})
    return monkeypatch


def test_build_resumes_and_writes_exact_minus_model(builder, tmp_path):
    chunks = 4 * 2 * 4          # (ln(a0/b0), nu, tau) blocks
    done, missing, path = fc.build(tmp_path / "w", workers=1, output=tmp_path / "t.nc",
                                   limit=5)
    assert (done, missing, path) == (5, chunks - 5, None)
    done, missing, path = fc.build(tmp_path / "w", workers=1, output=tmp_path / "t.nc")
    # the 27 missing chunks, then the model at the 4 tau nodes
    assert (done, missing, path) == (chunks - 5 + 4, 0, tmp_path / "t.nc")
    with netCDF4.Dataset(path) as ds:
        vals = np.stack([np.ma.filled(ds.variables[v][:].astype(float), np.nan)
                         for v in fc.VARIABLES])
        assert ds.n_unconverged == 4 * 2 * 3     # (3 nodes per ln(a0/b0) and nu)
        assert ds.grid_hash == fc._hash()
    n = fc.NODES
    # a node that is solved: (lg, nu, s, theta, tau, m, kn) indices (1, 1, 2, 3, 2, 1, 2)
    i = (1, 1, 2, 3, 2, 1, 2)
    p = [n[k][j] for k, j in zip(fc.AXES, i)]
    np.testing.assert_allclose(vals[(slice(None), *i)],
                               _exact(*p) - _model(*[np.array(v) for v in p]),
                               rtol=1e-6, atol=1e-8)
    # the known nodes are 0: Coulomb (mu_k/mu_0 = 1, kappa = 0) and s = 1
    assert np.all(vals[..., 2, :] == 0.0) and np.all(vals[..., 0] == 0.0)
    assert np.all(vals[:, :, :, 3] == 0.0)
    assert np.isnan(vals[0, :, :, 1, 2, 3, 0, 3]).all()     # the unconverged node


@pytest.mark.parametrize("axis, nodes", [
    ("log_aspect_ratio", (-1.0, -0.6, -0.3, 0.4, 1.0)),
    ("spin_coordinate", (0.0, 1.0, 1.5, 2.0, 4.0)),
    ("creepage_coordinate", (0.0, 0.15, 0.3, 0.6, 1.0)),
    ("creepage_coordinate", (0.0, 0.3, 0.45, 0.6, 1.0)),
])
def test_a_node_added_later_costs_only_its_own_chunks(builder, tmp_path, axis, nodes):
    fc.build(tmp_path / "w", workers=1, output=tmp_path / "t.nc")
    first = fc._hash()
    before = {p.name: p.stat().st_mtime_ns for p in (tmp_path / "w").rglob("exact_*.npy")}
    kw = {axis: nodes}
    builder.setattr(fc, "NODES", _small_nodes(**kw))
    assert fc._hash() == first                  # the same work directory
    done, missing, path = fc.build(tmp_path / "w", workers=1, output=tmp_path / "t2.nc")
    after = {p.name: p.stat().st_mtime_ns for p in (tmp_path / "w").rglob("exact_*.npy")}
    # every chunk of before is kept as it was; the new ones are the new node's rows:
    # (nu x tau x s) for ln(a0/b0), (ln(a0/b0) x nu x s) for tau, (ln(a0/b0) x nu x tau)
    # for s, each a row of (theta, m, kappa) nodes
    assert {k: after[k] for k in before} == before
    assert len(after) - len(before) == 2 * 4 * 4
    # jobs: the blocks with a new row (a new ln(a0/b0) or tau node's 2 x 4, every block
    # for a new s node), then the model at every tau node (its file is named by the
    # ln(a0/b0) and s nodes too) or at the new tau node only
    n_tau = fc.NODES["spin_coordinate"].size
    jobs = 4 * 2 * 4 if axis == "creepage_coordinate" else 2 * 4
    model = 1 if axis == "spin_coordinate" else n_tau
    assert (done, missing) == (jobs + model, 0)
    with netCDF4.Dataset(path) as ds:
        assert ds.dimensions[axis].size == 5
        vals = np.stack([np.ma.filled(ds.variables[v][:].astype(float), np.nan)
                         for v in fc.VARIABLES])
    # the new node's values are the stand-in's there (a solved node of it)
    n = fc.NODES
    new = [j for j, v in enumerate(n[axis]) if v in nodes and v not in _small_nodes()[axis]][0]
    i = [1, 1, 1, 3, 1, 1, 2]
    i[fc.AXES.index(axis)] = new
    p = [n[k][j] for k, j in zip(fc.AXES, i)]
    np.testing.assert_allclose(vals[(slice(None), *i)],
                               _exact(*p) - _model(*[np.array(v) for v in p]),
                               rtol=1e-6, atol=1e-8)


def test_a_node_between_two_unconverged_ones_along_s_is_not_tried(builder, tmp_path):
    """A row of s added between two solved rows: where both neighbours did not converge, the
    node is stored unconverged without a solve (the stand-in would converge there), and
    filled like the others; every other node of the row is solved."""
    fc.build(tmp_path / "w", workers=1, output=tmp_path / "t.nc")
    builder.setattr(fc, "NODES", _small_nodes(creepage_coordinate=(0.0, 0.3, 0.45, 0.6, 1.0)))
    fc.build(tmp_path / "w", workers=1, output=tmp_path / "t2.nc")
    workdir = next((tmp_path / "w").iterdir())
    n = fc.NODES
    i_tau = list(n["spin_coordinate"]).index(2.0)
    for i_g in range(4):
        for i_nu in range(2):
            row = np.load(fc._chunk(workdir, i_g, i_nu, i_tau, 2))     # s = 0.45
            # theta 0 is the third angle of linspace(-pi, pi, 5)[:-1]; (m, kn) (0.65, 0.5)
            assert np.isnan(row[:, 2, 1, 1]).all()
            assert np.isfinite(np.delete(row[0].reshape(-1), np.ravel_multi_index(
                (2, 1, 1), row.shape[1:]))).all()
            assert _exact(n["log_aspect_ratio"][i_g], n["poisson_ratio"][i_nu], 0.45, 0.0,
                          2.0, 0.65, 0.5)[0] == pytest.approx(
                              0.01 * n["log_aspect_ratio"][i_g] + 0.02 * 0.45)
    with netCDF4.Dataset(tmp_path / "t2.nc") as ds:
        assert ds.n_unconverged == 4 * 2 * 4     # the 3 before and the one not tried


def test_recover_rebuilds_the_chunks_from_a_file_without_a_solve(builder, tmp_path):
    """On a machine without the work directory: the chunks come back from the file (its
    correction plus the model at the nodes), and the build from them writes the same table
    without one exact solve; the file's unconverged nodes stay unconverged."""
    fc.build(tmp_path / "w", workers=1, output=tmp_path / "t.nc")

    def no_solve(*args):
        raise AssertionError("an exact solve was made")

    builder.setattr(fc, "exact_point", no_solve)
    n_written, workdir = fc.recover(tmp_path / "t.nc", tmp_path / "w2")
    assert n_written == 4 * 2 * 4 * 4           # every (ln(a0/b0), nu, tau, s) row
    for p in (tmp_path / "w").rglob("exact_*.npy"):
        np.testing.assert_allclose(np.load(workdir / p.name), np.load(p), rtol=1e-6,
                                   atol=1e-9)
    done, missing, path = fc.build(tmp_path / "w2", workers=1, output=tmp_path / "t2.nc")
    assert missing == 0 and done == 4          # the model at the 4 tau nodes only
    with netCDF4.Dataset(tmp_path / "t.nc") as a, netCDF4.Dataset(path) as b:
        assert b.n_unconverged == a.n_unconverged == 4 * 2 * 3
        for v in fc.VARIABLES:
            np.testing.assert_allclose(np.ma.filled(b.variables[v][:], np.nan),
                                       np.ma.filled(a.variables[v][:], np.nan), rtol=1e-6,
                                       atol=1e-9)
    # a second recover keeps what is there
    assert fc.recover(tmp_path / "t.nc", tmp_path / "w2")[0] == 0


def test_recover_refuses_a_file_of_another_model_or_other_nodes(builder, tmp_path):
    fc.build(tmp_path / "w", workers=1, output=tmp_path / "t.nc")
    builder.setattr(fc, "_model_hash", lambda: "0123456789ab")
    with pytest.raises(ValueError, match="source: the file's model .* is not the current"):
        fc.recover(tmp_path / "t.nc", tmp_path / "w2")
    builder.undo()
    builder.setattr(fc, "NODES", _small_nodes(spin_coordinate=(0.0, 1.0, 4.0)))
    with pytest.raises(ValueError, match="nodes of spin_coordinate .* are not all nodes"):
        fc.recover(tmp_path / "t.nc", tmp_path / "w2")


def _read(path):
    with netCDF4.Dataset(path) as ds:
        vals = np.stack([np.ma.filled(ds.variables[v][:].astype(float), np.nan)
                         for v in fc.VARIABLES])
        return vals, ds.variables["ladder_node"][:].astype(bool), dict(ds.__dict__)


def test_the_ladder_estimates_the_unconverged_nodes_up_to_its_tau(builder, tmp_path):
    """The ladder is tried at the unconverged nodes of tau <= LADDER_TAU_MAX only (tau 2 here:
    the two nodes of (m, kn) (0.65, 0.5) along s; the node at tau 4 is left); its value where
    it converges (s = 0.3) is stored as the exact one and flagged, where it does not (s = 0.6)
    the node stays unconverged; a second build makes no ladder solve."""
    builder.setattr(fc, "LADDER_TAU_MAX", 2.0)
    builder.setattr(fc, "ladder_point", _ladder)
    done, missing, path = fc.build(tmp_path / "w", workers=1, output=tmp_path / "t.nc")
    # 32 blocks of exact solves, the 8 (ln(a0/b0), nu) blocks at tau 2 with the ladder, the
    # model at the 4 tau nodes
    assert (done, missing) == (32 + 8 + 4, 0)
    vals, ladder, attrs = _read(path)
    assert attrs["n_ladder"] == int(ladder.sum()) == 4 * 2
    assert attrs["n_unconverged"] == 4 * 2 * 2        # tau 4, and s = 0.6 at tau 2
    assert attrs["ladder_tau_max"] == 2.0
    n = fc.NODES
    i = (2, 1, 1, 2, 2, 1, 1)                 # s 0.3, theta 0, tau 2, m 0.65, kn 0.5
    assert ladder[i] and np.isnan(vals[(0, *i[:2], 2, *i[3:])])
    p = [n[k][j] for k, j in zip(fc.AXES, i)]
    np.testing.assert_allclose(vals[(slice(None), *i)],
                               _ladder(*p) - _model(*[np.array(v) for v in p]),
                               rtol=1e-6, atol=1e-8)
    assert np.isnan(vals[0, :, :, 1, 2, 3, 0, 3]).all()     # tau 4: not tried
    builder.setattr(fc, "ladder_point", _no_ladder)
    assert fc.build(tmp_path / "w", workers=1, output=tmp_path / "t2.nc")[:2] == (0, 0)


def test_recover_brings_back_the_ladder_nodes_as_the_ladder_s(builder, tmp_path):
    """The ladder's nodes come back into the ladder's files (the exact chunks keep them
    unconverged), so that the build from the recovered chunks makes no solve of either kind
    and writes the same table and flags."""
    builder.setattr(fc, "LADDER_TAU_MAX", 2.0)
    builder.setattr(fc, "ladder_point", _ladder)
    fc.build(tmp_path / "w", workers=1, output=tmp_path / "t.nc")

    def no_solve(*args):
        raise AssertionError("an exact solve was made")

    builder.setattr(fc, "exact_point", no_solve)
    builder.setattr(fc, "ladder_point", _no_ladder)
    fc.recover(tmp_path / "t.nc", tmp_path / "w2")
    for p in (tmp_path / "w").rglob("*.npy"):
        if p.name.startswith(("exact_", "ladder")):
            np.testing.assert_allclose(np.load(next((tmp_path / "w2").iterdir()) / p.name),
                                       np.load(p), rtol=1e-6, atol=1e-9)
    done, missing, path = fc.build(tmp_path / "w2", workers=1, output=tmp_path / "t2.nc")
    assert (done, missing) == (4, 0)
    (a, la, aa), (b, lb, ab) = _read(tmp_path / "t.nc"), _read(path)
    np.testing.assert_array_equal(la, lb)
    np.testing.assert_allclose(b, a, rtol=1e-6, atol=1e-9)
    assert (ab["n_ladder"], ab["n_unconverged"]) == (aa["n_ladder"], aa["n_unconverged"])


def test_ladder_point_agrees_with_the_default_grid_where_that_converges():
    """The real ladder (6 grids, extrapolated in 1/mx) against method="exact"'s default grid
    at a converged node of a strong law with spin (a0/b0 1.50, nu 0.5, s 0.1, theta -60 deg,
    tau -1.625, mu_k/mu_0 0.65, kappa number 2): within 0.5 % of mu_0 N, T_x within 0.2 %
    (measured 0.07 / 0.37 / 0.03 % for T_x, T_y, M_z; over 30 nodes of the falling laws
    max 0.16 / 0.16 / 0.35 %)."""
    node = (np.log(5.0) / 4, 0.5, 0.1, -np.pi / 3, -1.625, 0.65, 2.0)
    lad = fc.ladder_point(*node)
    ex = fc.exact_point(*node)
    assert np.isfinite(ex).all()
    np.testing.assert_allclose(lad, ex, atol=5e-3)
    np.testing.assert_allclose(lad[0], ex[0], atol=2e-3)


def _theta_nodes(n):
    nodes = _small_nodes()
    nodes["creepage_angle"] = np.linspace(-np.pi, np.pi, n + 1)[:-1]
    return nodes


def _counted(fun, log):
    """``fun``, each call's arguments appended to the file ``log`` (the build's workers are
    processes)."""
    def counted(*args):
        with open(log, "a") as f:
            f.write(" ".join(repr(float(a)) for a in args) + "\n")
        return fun(*args)
    return counted


def _calls(log):
    return [tuple(float(v) for v in line.split()) for line in open(log)] if log.exists() else []


def test_a_theta_node_added_later_costs_only_its_own_solves(builder, tmp_path):
    """Theta nodes every 45 instead of 90 degrees: ``recover`` from the file of the 4 nodes
    writes their rows with the 4 new nodes pending, and the build solves those only (half the
    solves of a build from scratch) and writes the same table, flags and counts as that
    build (the ladder's nodes too)."""
    builder.setattr(fc, "LADDER_TAU_MAX", 2.0)
    builder.setattr(fc, "ladder_point", _ladder)
    fc.build(tmp_path / "w", workers=1, output=tmp_path / "t.nc")
    builder.setattr(fc, "NODES", _theta_nodes(8))
    builder.setattr(fc, "exact_point", _no_ladder)
    n_written, workdir = fc.recover(tmp_path / "t.nc", tmp_path / "w2")
    assert n_written == 4 * 2 * 4 * 4
    assert len(list(workdir.glob("pending_exact_*.npy"))) == n_written
    builder.setattr(fc, "exact_point", _counted(_exact, tmp_path / "extended"))
    builder.setattr(fc, "ladder_point", _counted(_ladder, tmp_path / "ladder"))
    fc.build(tmp_path / "w2", workers=1, output=tmp_path / "t2.nc")
    extended = _calls(tmp_path / "extended")
    assert not list(workdir.glob("pending_*"))
    # the new thetas' unknown nodes: 4 thetas x (2 m x 3 kn) x s 0.3 and 0.6 (s = 0 takes
    # theta 0's values, s = 1 is known) x 4 ln(a0/b0) x 2 nu x 4 tau
    assert len(extended) == 4 * 6 * 2 * 4 * 2 * 4
    assert {round(a[3], 12) for a in extended} == {round(v, 12) for v in
                                                  np.pi * np.array([-0.75, -0.25, 0.25, 0.75])}
    assert _calls(tmp_path / "ladder") == []       # (no new node failed)
    builder.setattr(fc, "exact_point", _counted(_exact, tmp_path / "scratch"))
    fc.build(tmp_path / "w3", workers=1, output=tmp_path / "t3.nc")
    # (and at s = 0 the one theta of every row, which the extension took from the file)
    assert len(_calls(tmp_path / "scratch")) == 2 * len(extended) + 4 * 2 * 4 * 6
    (a, la, aa), (b, lb, ab) = _read(tmp_path / "t2.nc"), _read(tmp_path / "t3.nc")
    assert a.shape[4] == 8
    np.testing.assert_array_equal(la, lb)
    np.testing.assert_allclose(a, b, rtol=1e-6, atol=1e-9)
    assert (aa["n_ladder"], aa["n_unconverged"]) == (ab["n_ladder"], ab["n_unconverged"])


def test_a_theta_node_between_two_unconverged_ones_is_left_to_the_ladder(builder, tmp_path):
    """A new theta node whose old neighbours both did not converge is not solved (stored
    unconverged, as along s); the ladder tries it (tau 2 here), and only it."""
    def exact(lg, nu, s, th, tau, m, kn):
        if (m, kn, tau, s) == (0.3, 2.0, 2.0, 0.3) and (np.isclose(th, 0.0)
                                                        or np.isclose(th, np.pi / 2)):
            return np.full(3, np.nan)
        return _exact(lg, nu, s, th, tau, m, kn)

    builder.setattr(fc, "exact_point", exact)
    builder.setattr(fc, "LADDER_TAU_MAX", 2.0)
    builder.setattr(fc, "ladder_point", _ladder)
    fc.build(tmp_path / "w", workers=1, output=tmp_path / "t.nc")
    builder.setattr(fc, "NODES", _theta_nodes(8))
    workdir = fc.recover(tmp_path / "t.nc", tmp_path / "w2")[1]
    builder.setattr(fc, "exact_point", _counted(exact, tmp_path / "solved"))
    builder.setattr(fc, "ladder_point", _counted(_ladder, tmp_path / "ladder"))
    fc.build(tmp_path / "w2", workers=1, output=tmp_path / "t2.nc")
    solved, ladder_calls = _calls(tmp_path / "solved"), _calls(tmp_path / "ladder")
    between = [a for a in solved if (a[5], a[6], a[4], a[2]) == (0.3, 2.0, 2.0, 0.3)
               and np.isclose(a[3], np.pi / 4)]
    assert between == []
    assert len(solved) == 4 * 6 * 2 * 4 * 2 * 4 - 4 * 2
    assert {(round(a[3], 12), a[2], a[4], a[5], a[6]) for a in ladder_calls} == {
        (round(np.pi / 4, 12), 0.3, 2.0, 0.3, 2.0)}
    assert len(ladder_calls) == 4 * 2
    vals, ladder, _ = _read(tmp_path / "t2.nc")
    i = (0, 0, 1, 5, 2, 0, 3)               # s 0.3, theta pi/4, tau 2, m 0.3, kn 2
    assert ladder[i]
    p = [fc.NODES[k][j] for k, j in zip(fc.AXES, i)]
    np.testing.assert_allclose(vals[(slice(None), *i)],
                               _ladder(*p) - _model(*[np.array(v) for v in p]),
                               rtol=1e-6, atol=1e-8)
    assert np.isnan(np.load(fc._chunk(workdir, 0, 0, 2, 1))[0, 5, 0, 3])


def _exact_theta(lg, nu, s, th, tau, m, kn):
    """The stand-in, varying along theta too."""
    return _exact(lg, nu, s, th, tau, m, kn) + np.array(
        [0.004 * np.cos(th), 0.002 * np.sin(2.0 * th), 0.001 * np.sin(th)]) * (1.0 - m)


def test_a_partial_build_ships_what_is_done_and_the_table_before_elsewhere(builder, tmp_path):
    """Theta nodes every 45 instead of 90 degrees, 3 of the 32 blocks solved: the partial
    file (``partial_from``) holds the solves there, the 90-degree table elsewhere (its
    periodic spline along theta at the new nodes, flagged ``source_node``); recovered from
    it, the build solves the rest only and writes the table a build from scratch writes."""
    from scipy.interpolate import CubicSpline

    builder.setattr(fc, "exact_point", _exact_theta)
    fc.build(tmp_path / "w", workers=1, output=tmp_path / "t.nc")
    before = _read(tmp_path / "t.nc")[0]
    builder.setattr(fc, "NODES", _theta_nodes(8))
    fc.recover(tmp_path / "t.nc", tmp_path / "w2")
    fc.build(tmp_path / "w2", workers=1, limit=3)
    done, n_source, path = fc.build(tmp_path / "w2", workers=1, output=tmp_path / "p.nc",
                                    partial_from=tmp_path / "t.nc")
    assert path == tmp_path / "p.nc"
    vals, _, attrs = _read(path)
    with netCDF4.Dataset(path) as ds:
        source = ds.variables["source_node"][:].astype(bool)
    # the new thetas' unknown nodes (2 m x 3 kn) at s 0, 0.3 and 0.6 of the 29 blocks not
    # solved (blocks run tau first: the 3 solved are tau 0's (g, nu) (0, 0), (0, 1), (1, 0))
    assert n_source == attrs["n_source_nodes"] == source.sum() == 29 * 3 * 4 * 6
    assert not source[:, :, :, 1::2].any() or not source[:, :, :, ::2].any()
    assert not source[0, :, :, :, 0].any() and not source[1, 0, :, :, 0].any()
    n = fc.NODES
    i = (0, 1, 1, 1, 0, 1, 2)           # solved: s 0.3, theta -3 pi / 4, tau 0, m 0.65, kn 1.125
    p = [n[k][j] for k, j in zip(fc.AXES, i)]
    np.testing.assert_allclose(vals[(slice(None), *i)],
                               _exact_theta(*p) - _model(*[np.array(v) for v in p]),
                               rtol=1e-6, atol=1e-8)
    assert not source[i]
    # a node not computed: the 90-degree table's periodic spline along theta there, and
    # that table at its own nodes
    th4 = np.linspace(-np.pi, np.pi, 5)
    row = before[:, 2, 1, 2, :, 3, 0, 1]          # (var, theta): s 0.6, tau 4, m 0.3, kn 0.5
    spline = CubicSpline(th4, np.concatenate([row, row[:, :1]], axis=1), axis=1,
                         bc_type="periodic")
    assert source[2, 1, 2, 1::2, 3, 0, 1].all()
    np.testing.assert_allclose(vals[:, 2, 1, 2, 1::2, 3, 0, 1], spline(n["creepage_angle"][1::2]),
                               rtol=1e-5, atol=1e-8)
    np.testing.assert_allclose(vals[:, 2, 1, 2, ::2, 3, 0, 1], row, rtol=1e-6, atol=1e-9)
    assert abs(vals[0, 2, 1, 2, 3, 3, 0, 1] - (_exact_theta(*[n[k][j] for k, j in zip(
        fc.AXES, (2, 1, 2, 3, 3, 0, 1))]) - _model(*[np.array(n[k][j]) for k, j in zip(
            fc.AXES, (2, 1, 2, 3, 3, 0, 1))]))[0]) > 2e-5    # (the spline is not the truth)
    # recovered from the partial file: its computed nodes kept, the others solved
    builder.setattr(fc, "exact_point", _counted(_exact_theta, tmp_path / "rest"))
    fc.recover(path, tmp_path / "w3")
    fc.build(tmp_path / "w3", workers=1, output=tmp_path / "t3.nc")
    assert len(_calls(tmp_path / "rest")) == 29 * 2 * 4 * 6    # (s = 0 takes theta -pi's)
    builder.setattr(fc, "exact_point", _exact_theta)
    fc.build(tmp_path / "w4", workers=1, output=tmp_path / "t4.nc")
    (a, la, aa), (b, lb, ab) = _read(tmp_path / "t3.nc"), _read(tmp_path / "t4.nc")
    np.testing.assert_allclose(a, b, rtol=1e-6, atol=1e-9)
    with netCDF4.Dataset(tmp_path / "t3.nc") as ds:
        assert "source_node" not in ds.variables and ds.n_source_nodes == 0


@pytest.fixture
def polach(monkeypatch):
    """The builder set to Polach's law family, restored after the test."""
    monkeypatch.setattr(fc, "LAW_FAMILY", fc.LAW_FAMILY)
    monkeypatch.setitem(fc.NODES, "creepage_angle", fc.NODES["creepage_angle"])
    monkeypatch.setitem(fc.NODES, "creepage_coordinate", fc.NODES["creepage_coordinate"])
    monkeypatch.setitem(fc.NODES, "friction_ratio", fc.NODES["friction_ratio"])
    fc.set_law_family("polach")
    return monkeypatch


def _exact_polach(lg, nu, s, th, tau, m, kn):
    """A stand-in for Polach's exact solve: the smooth stand-in's plus a part along theta
    (unconverged where the smooth one is, and at one node of its own)."""
    if m == 0.3 and kn == 1.125 and tau == 1.0 and s == 0.6 and th == 0.0:
        return np.full(3, np.nan)
    return _exact_theta(lg, nu, s, th, tau, m, kn) + np.array(
        [0.003 * np.cos(th) + 0.002, 0.001 * np.sin(th), 0.0]) * (1.0 - m) * kn


def test_polach_family_is_its_own_build_written_on_the_smooth_table(builder, tmp_path):
    """--law polach: another work directory (the smooth law's hash unchanged, so its chunks
    stay), its own file and attributes, its own theta nodes (here 90 degrees apart against
    the smooth table's 45); written on the smooth law's table (``base``, on_base): at its
    solved nodes the family's exact minus model, between them along theta the base plus the
    difference's periodic spline, and where not solved yet (a partial build: 3 of the 32
    blocks) the base itself, flagged ``source_node``. An unknown family is a ValueError."""
    from scipy.interpolate import CubicSpline

    builder.setattr(fc, "THETA_NODES", {"smooth": 8, "polach": 4})
    builder.setattr(fc, "CREEPAGE_NODES_ADDED", {"smooth": (), "polach": ()})
    builder.setattr(fc, "LAW_FAMILY", fc.LAW_FAMILY)
    builder.setattr(fc, "NODES", _theta_nodes(8))
    builder.setattr(fc, "exact_point", _exact_theta)
    fc.build(tmp_path / "ws", workers=1, output=tmp_path / "smooth.nc")
    base = _read(tmp_path / "smooth.nc")[0]
    smooth_hash = fc._hash()
    fc.set_law_family("polach")
    assert fc._hash() != smooth_hash and fc.NODES["creepage_angle"].size == 4
    assert fc.table_name() == "falling_correction_polach"
    builder.setattr(fc, "exact_point", _exact_polach)
    assert fc.build(tmp_path / "w", workers=1, limit=3)[1] == 32 - 3
    assert (tmp_path / "w" / f"falling_correction-{fc._hash()}").is_dir()
    builder.chdir(tmp_path)
    done, n_source, path = fc.build(tmp_path / "w", workers=1, partial_from=tmp_path / "smooth.nc")
    assert path == tmp_path / "tables-build" / "falling_correction_polach.nc"
    vals, _, attrs = _read(path)
    with netCDF4.Dataset(path) as ds:
        source = ds.variables["source_node"][:].astype(bool)
        assert ds.variables["creepage_angle"].size == 8        # the base's theta nodes
    assert attrs["law_family"] == "polach" and "Polach" in attrs["title"]
    assert attrs["base_table"] == "smooth.nc" and n_source == source.sum() > 0
    n = fc.NODES
    th8 = np.linspace(-np.pi, np.pi, 9)[:-1]
    # solved (tau 0's block (g, nu) = (0, 1)): at a Polach node exact minus model; between
    # two, the base plus the periodic spline of the difference
    i = (0, 1, 1, 2, 0, 1, 2)         # s 0.3, theta 0 (the Polach node 2, the base's 4)
    p = [n[k][j] for k, j in zip(fc.AXES, i)]
    want = _exact_polach(*p) - _model(*[np.array(v) for v in p])
    np.testing.assert_allclose(vals[:, 0, 1, 1, 4, 0, 1, 2], want, rtol=1e-6, atol=1e-8)
    d = []
    for th in n["creepage_angle"]:
        q = list(p)
        q[3] = th
        d.append(_exact_polach(*q) - _model(*[np.array(v) for v in q])
                 - base[:, 0, 1, 1, list(th8).index(th), 0, 1, 2])
    d = np.array(d).T
    spline = CubicSpline(np.append(n["creepage_angle"], np.pi),
                         np.concatenate([d, d[:, :1]], axis=1), axis=1, bc_type="periodic")
    np.testing.assert_allclose(vals[:, 0, 1, 1, 1::2, 0, 1, 2],
                               base[:, 0, 1, 1, 1::2, 0, 1, 2] + spline(th8[1::2]),
                               rtol=1e-5, atol=1e-7)
    assert not source[0, 1, 1, :, 0].any()
    # not solved (tau 4): the base's values, flagged
    np.testing.assert_allclose(vals[:, :, :, :, :, 3], base[:, :, :, :, :, 3], rtol=1e-6,
                               atol=1e-9)
    assert source[:, :, :3, :, 3, :2, 1:].all() and not source[..., 2, :].any()  # (not known)
    # the whole build: nothing left from the base, and the family's exact at its nodes
    fc.build(tmp_path / "w", workers=1, output=tmp_path / "full.nc",
             base=tmp_path / "smooth.nc")
    full, _, attrs = _read(tmp_path / "full.nc")
    assert attrs["n_source_nodes"] == 0
    i = (2, 0, 2, 1, 3, 0, 3)           # s 0.6, theta -pi/2, tau 4, m 0.3, kn 2
    p = [n[k][j] for k, j in zip(fc.AXES, i)]
    np.testing.assert_allclose(full[:, 2, 0, 2, 2, 3, 0, 3],
                               _exact_polach(*p) - _model(*[np.array(v) for v in p]),
                               rtol=1e-6, atol=1e-8)
    with pytest.raises(ValueError, match="law family must be one of .*'smooth', 'polach'"):
        fc.set_law_family("coulomb")
    with pytest.raises(ValueError, match="recover takes the smooth law's table; got law "
                                         "family 'polach'"):
        fc.recover(tmp_path / "full.nc", tmp_path / "w5")


def _exact_curved(lg, nu, s, th, tau, m, kn):
    """The stand-in, curved along s (a cubic there)."""
    return _exact(lg, nu, s, th, tau, m, kn) + np.array(
        [0.05 * s ** 2, -0.03 * s ** 3, 0.01 * s ** 2 * (1.0 - m)])


def _exact_curved_polach(lg, nu, s, th, tau, m, kn):
    return _exact_curved(lg, nu, s, th, tau, m, kn) + np.array(
        [0.004 * (1.0 - m) * kn * s, 0.002 * np.cos(th) * s, 0.0])


def test_a_family_s_node_the_smooth_table_lacks_takes_its_spline_there(builder, tmp_path):
    """Polach's table has an s node the smooth law's has not (CREEPAGE_NODES_ADDED; here
    0.45 between 0.3 and 0.6): set_law_family adds it (and takes it away for the smooth law),
    the work directory's hash stays, and on_base takes the smooth table there as its spline
    along s (with four s nodes, the cubic through them: checked against numpy's polyfit).
    Where Polach's rows are solved (a partial build: 3 of 32 blocks) the file holds Polach's
    exact minus the model at every s node, the new one too; where not yet, the smooth
    table's cubic, flagged ``source_node``."""
    builder.setattr(fc, "THETA_NODES", {"smooth": 4, "polach": 4})
    builder.setattr(fc, "CREEPAGE_NODES_ADDED", {"smooth": (), "polach": (0.45,)})
    builder.setattr(fc, "LAW_FAMILY", fc.LAW_FAMILY)
    builder.setattr(fc, "exact_point", _exact_curved)
    fc.build(tmp_path / "ws", workers=1, output=tmp_path / "smooth.nc")
    base = _read(tmp_path / "smooth.nc")[0]
    s_base = fc.NODES["creepage_coordinate"].copy()
    fc.set_law_family("polach")
    assert fc.NODES["creepage_coordinate"].tolist() == [0.0, 0.3, 0.45, 0.6, 1.0]
    hash_polach = fc._hash()
    builder.setattr(fc, "exact_point", _exact_curved_polach)
    fc.build(tmp_path / "w", workers=1, limit=3)
    done, n_source, path = fc.build(tmp_path / "w", workers=1, output=tmp_path / "p.nc",
                                    partial_from=tmp_path / "smooth.nc")
    vals = _read(path)[0]
    with netCDF4.Dataset(path) as ds:
        source = ds.variables["source_node"][:].astype(bool)
        assert ds.variables["creepage_coordinate"][:].tolist() == [0.0, 0.3, 0.45, 0.6, 1.0]
    n = fc.NODES
    # solved (tau 0, (g, nu) = (0, 0)): Polach's exact minus the model at s = 0.45
    i = (0, 0, 2, 1, 0, 1, 2)
    p = [n[k][j] for k, j in zip(fc.AXES, i)]
    np.testing.assert_allclose(vals[(slice(None),) + i],
                               _exact_curved_polach(*p) - _model(*[np.array(v) for v in p]),
                               rtol=1e-6, atol=1e-8)
    assert not source[i]
    # not solved (tau 4, (g, nu) = (2, 1), m 0.65, kn 1.125): the smooth table's cubic in s
    at = (slice(None), 2, 1, slice(None), 0, 3, 1, 2)
    want = [np.polyval(np.polyfit(s_base, base[at][v], 3), 0.45) for v in range(3)]
    np.testing.assert_allclose(vals[at][:, 2], want, rtol=1e-6, atol=1e-8)
    np.testing.assert_allclose(vals[at][:, [0, 1, 3, 4]], base[at], rtol=1e-6, atol=1e-9)
    assert source[at[1:]][:4].all() and not source[at[1:]][4]      # (s = 1: known, 0)
    fc.set_law_family("smooth")
    assert fc.NODES["creepage_coordinate"].tolist() == s_base.tolist()
    fc.set_law_family("polach")
    assert fc._hash() == hash_polach


def test_a_family_node_the_ladder_has_not_reached_is_filled_not_the_base_s(builder, tmp_path):
    """Polach's table written while its ladder is under way: a node its exact solve did not
    converge on and the ladder has not reached yet (here Polach's own, tau 1, m 0.3, kn 1.125,
    s 0.6, theta 0; the smooth table converged there) is not flagged ``source_node`` and is
    not the smooth table's value: the base plus the difference filled from its neighbours
    along theta (the reader's fill); once the ladder has reached it, the ladder's value minus
    the model, flagged ``ladder_node``."""
    builder.setattr(fc, "THETA_NODES", {"smooth": 4, "polach": 4})
    builder.setattr(fc, "CREEPAGE_NODES_ADDED", {"smooth": (), "polach": ()})
    builder.setattr(fc, "LAW_FAMILY", fc.LAW_FAMILY)
    builder.setattr(fc, "exact_point", _exact_theta)
    fc.build(tmp_path / "ws", workers=1, output=tmp_path / "smooth.nc")
    base = _read(tmp_path / "smooth.nc")[0]
    fc.set_law_family("polach")
    builder.setattr(fc, "exact_point", _exact_polach)
    builder.setattr(fc, "LADDER_TAU_MAX", 2.0)
    builder.setattr(fc, "ladder_point", _ladder)
    assert fc.build(tmp_path / "w", workers=1, limit=32)[2] is None     # (no ladder yet)
    fc.build(tmp_path / "w", workers=1, output=tmp_path / "p.nc",
             partial_from=tmp_path / "smooth.nc")
    vals, ladder, _ = _read(tmp_path / "p.nc")
    with netCDF4.Dataset(tmp_path / "p.nc") as ds:
        source = ds.variables["source_node"][:].astype(bool) if "source_node" in \
            ds.variables else np.zeros(ladder.shape, dtype=bool)
    n = fc.NODES
    i = (1, 0, 2, 2, 1, 0, 2)           # (g, nu, s 0.6, theta 0, tau 1, m 0.3, kn 1.125)
    assert not source[i] and not ladder[i] and np.isfinite(base[(slice(None),) + i]).all()

    def d_at(i_theta):
        j = list(i)
        j[3] = i_theta
        p = [n[k][q] for k, q in zip(fc.AXES, j)]
        return (_exact_polach(*p) - _model(*[np.array(v) for v in p])
                - base[(slice(None),) + tuple(j)])

    want = base[(slice(None),) + i] + 0.5 * (d_at(1) + d_at(3))
    np.testing.assert_allclose(vals[(slice(None),) + i], want, rtol=1e-6, atol=1e-8)
    assert np.abs(want - base[(slice(None),) + i]).max() > 1e-4      # (not the base's)
    fc.build(tmp_path / "w", workers=1, output=tmp_path / "full.nc", base=tmp_path / "smooth.nc")
    vals, ladder, _ = _read(tmp_path / "full.nc")
    p = [n[k][q] for k, q in zip(fc.AXES, i)]
    np.testing.assert_allclose(vals[(slice(None),) + i],
                               _ladder(*p) - _model(*[np.array(v) for v in p]),
                               rtol=1e-6, atol=1e-8)
    assert ladder[i] and ladder.sum() > 1


def test_polach_family_solves_polach_s_law_in_the_slip(polach):
    """The Polach family's node is Polach's law ``mu_0 ((1 - A) exp(-B w) + A)`` with A the
    node's mu_k/mu_0 and B V its kappa (the same slope at zero slip as the smooth law's node):
    the exact solve equals creep_solution_3d with PolachFriction at another rolling speed
    (30 m/s, B scaled: the law in the slip is the same), and the model equals the package's
    numpy function with that law; both differ from the smooth law's by more than 1 % of
    mu_0 N here (the shapes differ)."""
    from railcontact import creep_solution_3d
    from railcontact.creep3d import load_exact_table
    from railcontact.falling_table import falling_friction_table
    from railcontact.friction import PolachFriction

    node = (0.0, 0.25, 0.2, 0.5, 1.5, 0.3, 1.125)
    got = fc.exact_point(*node)
    model = fc.model_points(*(np.array([v]) for v in node))[:, 0]
    a, mu0, mu_k, kappa = fc._case(*node)
    law = PolachFriction(mu0, mu_k / mu0, kappa / 30.0)
    ex = creep_solution_3d(*a[:8], law, method="exact", rolling_speed=30.0)
    scale = mu0 * a[3]
    np.testing.assert_allclose(got[:2], [ex.tx / scale, ex.ty / scale], rtol=1e-9, atol=1e-12)
    table = load_exact_table()

    def values(mu):
        sol = table.creep_solution_3d(*a[:8], float(mu))
        return sol.tx, sol.ty, sol.spin_moment, sol.stick_area_fraction, 0.0

    tx, ty = falling_friction_table(values, *(np.asarray(v) for v in a[:6]),
                                    lambda s: law(30.0 * s), np.asarray(mu0),
                                    material=(a[6], a[7]))[:2]
    np.testing.assert_allclose(model[:2], [tx / scale, ty / scale], rtol=1e-9, atol=1e-12)
    fc.set_law_family("smooth")
    assert np.hypot(*(fc.exact_point(*node) - got)[:2]) > 0.01
    assert np.hypot(*(fc.model_points(*(np.array([v]) for v in node))[:2, 0]
                      - model[:2])) > 0.01


def test_a_node_unconverged_at_the_tau_below_is_not_tried(builder, tmp_path):
    """SKIP_AFTER_UNCONVERGED_TAU: a node whose solve did not converge at the tau node below
    (its row there solved) is not attempted (NaN, for the ladder), as a node between two
    unconverged ones along s: here the stand-in's unconverged node at tau 2 (m 0.65, kn 0.5,
    s 0.3 and 0.6, theta 0) is not solved again at tau 4, and nothing else is skipped."""
    builder.setattr(fc, "SKIP_AFTER_UNCONVERGED_TAU", True)
    builder.setattr(fc, "exact_point", _counted(_exact, tmp_path / "calls"))
    fc.build(tmp_path / "w", workers=1, output=tmp_path / "t.nc")
    calls = set(_calls(tmp_path / "calls"))
    vals = _read(tmp_path / "t.nc")[0]
    n = fc.NODES
    for i_s in (1, 2):
        node = (n["log_aspect_ratio"][0], 0.0, n["creepage_coordinate"][i_s], 0.0, 4.0, 0.65,
                0.5)
        assert node not in calls and (node[:4] + (2.0,) + node[5:]) in calls
        i_t = int(np.flatnonzero(n["creepage_angle"] == 0.0)[0])
        assert np.isnan(vals[0, 0, 0, i_s, i_t, 3, 1, 1])
    # every other node of the grid was tried once: (g, nu, tau) x the unknown nodes of a
    # block (s 0: one theta; s 0.3, 0.6: every theta; m 0.3, 0.65; kn 0.5, 1.125, 2) less the
    # 2 x 8 (g, nu) skipped at tau 4
    per_block = (1 + 2 * 4) * 2 * 3
    assert len(calls) == 4 * 2 * 4 * per_block - 2 * 8


def test_a_pending_node_unconverged_at_the_tau_below_is_not_tried(builder, tmp_path):
    """SKIP_AFTER_UNCONVERGED_TAU for the nodes added to the rows (pending after ``recover``)
    too: a new theta node (pi/4) that did not converge at tau 2 is not solved at tau 4, and
    every other new node is solved once."""
    def exact(lg, nu, s, th, tau, m, kn):
        if (m, kn, s) == (0.3, 2.0, 0.3) and tau >= 2.0 and np.isclose(th, np.pi / 4):
            return np.full(3, np.nan)
        return _exact(lg, nu, s, th, tau, m, kn)

    builder.setattr(fc, "SKIP_AFTER_UNCONVERGED_TAU", True)
    builder.setattr(fc, "exact_point", exact)
    fc.build(tmp_path / "w", workers=1, output=tmp_path / "t.nc")
    builder.setattr(fc, "NODES", _theta_nodes(8))
    fc.recover(tmp_path / "t.nc", tmp_path / "w2")
    builder.setattr(fc, "exact_point", _counted(exact, tmp_path / "calls"))
    fc.build(tmp_path / "w2", workers=1, output=tmp_path / "t2.nc")
    calls = _calls(tmp_path / "calls")
    at = [a for a in calls if (a[5], a[6], a[2]) == (0.3, 2.0, 0.3)
          and np.isclose(a[3], np.pi / 4)]
    assert {a[4] for a in at} == {0.0, 1.0, 2.0}            # (not 4.0)
    # the new thetas' unknown nodes, as in the theta test, less the 4 x 2 (g, nu) at tau 4
    assert len(calls) == 4 * 6 * 2 * 4 * 2 * 4 - 4 * 2
    vals = _read(tmp_path / "t2.nc")[0]
    assert np.isnan(vals[0, 0, 0, 1, 5, 3, 0, 3]) and np.isnan(vals[0, 0, 0, 1, 5, 2, 0, 3])


def _exact_curved_m(lg, nu, s, th, tau, m, kn):
    """The stand-in, curved along mu_k/mu_0."""
    return _exact(lg, nu, s, th, tau, m, kn) + np.array(
        [0.04 * (1.0 - m) ** 2, 0.02 * m * (1.0 - m) * kn, 0.0])


def _exact_curved_m_polach(lg, nu, s, th, tau, m, kn):
    return _exact_curved_m(lg, nu, s, th, tau, m, kn) + np.array(
        [0.003 * (1.0 - m) * kn, 0.002 * np.cos(th) * (1.0 - m), 0.0])


def test_a_family_m_node_the_smooth_table_lacks_takes_its_line_there(builder, tmp_path):
    """Polach's table has a mu_k/mu_0 node the smooth law's has not
    (FRICTION_RATIO_NODES_ADDED; here 0.45 between 0.3 and 0.65): set_law_family adds it
    (and takes it away for the smooth law, whose hash stays). Where Polach's rows are solved
    (a partial build: 3 of 32 blocks) the file holds Polach's exact minus the model at the
    new node; where not yet, the smooth table's straight line between 0.3 and 0.65 there (the
    reader is linear along mu_k/mu_0: checked with numpy's interp), flagged ``source_node``."""
    builder.setattr(fc, "THETA_NODES", {"smooth": 4, "polach": 4})
    builder.setattr(fc, "CREEPAGE_NODES_ADDED", {"smooth": (), "polach": ()})
    builder.setattr(fc, "FRICTION_RATIO_NODES_ADDED", {"smooth": (), "polach": (0.45,)})
    builder.setattr(fc, "LAW_FAMILY", fc.LAW_FAMILY)
    builder.setattr(fc, "exact_point", _exact_curved_m)
    fc.build(tmp_path / "ws", workers=1, output=tmp_path / "smooth.nc")
    base = _read(tmp_path / "smooth.nc")[0]
    smooth_hash = fc._hash()
    fc.set_law_family("polach")
    assert fc.NODES["friction_ratio"].tolist() == [0.3, 0.45, 0.65, 1.0]
    builder.setattr(fc, "exact_point", _exact_curved_m_polach)
    fc.build(tmp_path / "w", workers=1, limit=3)
    path = fc.build(tmp_path / "w", workers=1, output=tmp_path / "p.nc",
                    partial_from=tmp_path / "smooth.nc")[2]
    vals = _read(path)[0]
    with netCDF4.Dataset(path) as ds:
        source = ds.variables["source_node"][:].astype(bool)
        assert ds.variables["friction_ratio"][:].tolist() == [0.3, 0.45, 0.65, 1.0]
    n = fc.NODES
    # solved (tau 0, (g, nu) = (0, 0)): Polach's exact minus the model at m = 0.45
    i = (0, 0, 1, 2, 0, 1, 2)
    p = [n[k][j] for k, j in zip(fc.AXES, i)]
    np.testing.assert_allclose(vals[(slice(None),) + i],
                               _exact_curved_m_polach(*p) - _model(*[np.array(v) for v in p]),
                               rtol=1e-6, atol=1e-8)
    assert not source[i]
    # not solved (tau 4, (g, nu) = (2, 1), s 0.6, kn 1.125): the smooth table's line
    at = (slice(None), 2, 1, 2, 1, 3, slice(None), 2)
    want = [np.interp(0.45, [0.3, 0.65, 1.0], base[at][v]) for v in range(3)]
    np.testing.assert_allclose(vals[at][:, 1], want, rtol=1e-6, atol=1e-8)
    np.testing.assert_allclose(vals[at][:, [0, 2, 3]], base[at], rtol=1e-6, atol=1e-9)
    assert abs(vals[at][1, 1] - (_exact_curved_m_polach(*[n[k][j] for k, j in zip(
        fc.AXES, (2, 1, 2, 1, 3, 1, 2))]) - _model(*[np.array(n[k][j]) for k, j in zip(
            fc.AXES, (2, 1, 2, 1, 3, 1, 2))]))[1]) > 5e-4    # (the line is not the truth)
    assert source[at[1:]][:3].all() and not source[at[1:]][3]      # (m = 1: known, 0)
    fc.set_law_family("smooth")
    assert fc.NODES["friction_ratio"].tolist() == [0.3, 0.65, 1.0]
    assert fc._hash() == smooth_hash
