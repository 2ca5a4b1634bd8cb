"""The end constraint as data: the DOF map's numbering and condensation follow the declared
constraints (schema.CONSTRAINTS), for a constraint at another node and for a map of more than one
reduced co-ordinate too, against independent computations (the reduced layout written out, a dense
d'Alembert projection T^T (...) T with the constraint's Jacobian T)."""

import dataclasses

import numba
import numpy as np
import pytest

from crankgen.discrete import constraints, mesh
from crankgen.declaration import schema
from crankgen.engine import elements, records

MAPPED = mesh.MAPPED


def test_the_declared_constraints_give_the_papers_reduced_vector():
    """[psi_0, u_1, v_1, psi_1, ..., u_{n-1}, v_{n-1}, psi_{n-1}, s, psi_n]: the pin removes
    u_0, v_0; the guide's s takes the place of u_n and v_n goes."""
    for n in range(1, 6):
        m = mesh.Mesh(n)
        expected = [(0, mesh.PSI)] + [(node, c) for node in range(1, n) for c in range(3)] + [("s",), (n, mesh.PSI)]
        assert m.n_dofs == len(expected) == 3 * n
        for k, key in enumerate(expected):
            if key == ("s",):
                assert m.reduced_coordinates()[0] == k and m.reduced_coordinates() == (k,)
            else:
                assert m.reduced_index(*key) == k
        assert m.reduced_index(0, mesh.U) is None and m.reduced_index(n, mesh.V) is None
        assert all(m.reduced_index(node, mesh.CHI) is None for node in range(n + 1))     # no chi: linear u
        assert m.holders() == [(n - 1, (4, 5), (4,))]          # the second node's (u, v) of the last element
        assert [h[0] for h in m.holders(schema.CONSTRAINTS[0])] == [0]
        assert (m.element_dofs[:, [mesh.CHI, mesh.NODE_DOFS + mesh.CHI]] == m.dummy).all()


def test_the_exact_rods_nodes_carry_the_axial_slope():
    """[psi_0, chi_0, u_1, v_1, psi_1, chi_1, ..., s, psi_n, chi_n]: the exact rod's cubic u adds
    chi = u_x at every node, the pin and the guide eliminate the same (u, v)."""
    options = dict(schema.resolve_options("exact"))
    for n in range(1, 6):
        m = mesh.Mesh(n, components=mesh.components_of(options))
        assert m.components == ("u", "v", "psi", "chi")
        expected = ([(0, mesh.PSI), (0, mesh.CHI)] + [(node, c) for node in range(1, n) for c in range(4)]
                    + [("s",), (n, mesh.PSI), (n, mesh.CHI)])
        assert m.n_dofs == len(expected) == 4 * n + 1                    # 4 (n + 1) less the pin's two and v_n
        for k, key in enumerate(expected):
            if key == ("s",):
                assert m.reduced_coordinates() == (k,)
            else:
                assert m.reduced_index(*key) == k
        assert m.holders() == [(n - 1, (4, 5), (4,))]
    assert mesh.components_of(dict(schema.resolve_options("consistent"))) == ("u", "v", "psi")


def _as_lists(c):
    return [np.asarray(x).tolist() for x in c]


def test_the_compiled_condensation_is_the_meshs(monkeypatch):
    """The engine's condensation (records.condensation and the Work's map from element to holding)
    is the mesh's (Mesh.holders), at the last node, with a flexible rocker's tip (two reduced
    co-ordinates), and, the constraint moved to an interior node, on the elements either side of it."""
    from crankgen.engine.batch import body_data
    from crankgen.engine.records import MeshData

    def work_of(m):
        held, slots, reduced = records.condensation(m.n_all, m.holders(), len(m.mapped.reduced))
        data = MeshData(m.element_dofs, 5, m.length, None, None, None, None, None, m.n_rod, -1, -1, None,
                        *body_data(m), held, slots, reduced)
        return records.new_work(data, m.n_dofs), (held, slots, reduced)

    for n in range(1, 7):
        for m in (mesh.Mesh(n), mesh.Mesh(n, rocker_elements=2, rocker_length=0.5)):
            held = m.holders()
            w, arrays = work_of(m)
            assert _as_lists(arrays) == [[h[0] for h in held], [list(h[1]) for h in held], [list(h[2]) for h in held]]
            assert [int(i) for i in w.mapped] == [held_index(held, e) for e in range(m.n_all)]
            assert w.E.shape[0] == 3 + 4 * len(m.mapped.reduced) + len(m.mapped.reduced) ** 2
    inner = dataclasses.replace(MAPPED, node=2)
    monkeypatch.setattr(schema, "CONSTRAINTS", (schema.CONSTRAINTS[0], inner))
    for n in (3, 5):
        m = mesh.Mesh(n)
        held = m.holders(inner)
        assert held == [(1, (4, 5), (4,)), (2, (0, 1), (0,))]          # node 2 ends element 1, starts element 2
        s = m.reduced_coordinates(inner)[0]
        assert m.element_dofs[1, 4] == m.element_dofs[2, 0] == s       # one s, shared
        assert m.element_dofs[1, 5] == m.element_dofs[2, 1] == m.dummy
        assert m.n_dofs == 3 * (n + 1) - 2 - 1                          # the pin's two, v_2
        _, arrays = work_of(m)
        assert _as_lists(arrays) == [[1, 2], [[4, 5], [0, 1]], [[4], [0]]]


def held_index(held, e):
    return next((i for i, h in enumerate(held) if h[0] == e), -1)


def _random_map(rng, m, k, shape=()):
    rows = constraints.map_rows(m)
    return rng.standard_normal(shape + (len(rows), k)), rows


def _dense_projection(E, rows, r, K, C, M, slots, reduced):
    """The reduced terms written as d'Alembert's projection with the constraint's Jacobian T:
    element vector q = T p with p the element's own components and, in the places `reduced`, the
    reduced co-ordinates s; the eliminated components' columns of T are g_s."""
    n, m = len(r), len(reduced)
    tag = (lambda *i: "") if m == 1 else (lambda *i: "_" + "".join(map(str, i)))

    def jac(name):
        T = np.eye(n)
        T[:, list(slots)] = 0.0
        for j, sj in enumerate(reduced):
            T[list(slots), sj] = E[rows[name + tag(j)]]
        return T

    def only(name):                       # the map's derivative alone in the reduced columns
        D = np.zeros((n, n))
        for j, sj in enumerate(reduced):
            D[list(slots), sj] = E[rows[name + tag(j)]]
        return D

    T = jac("g_s")
    K_red = T.T @ (K @ T + C @ only("dqd_ds") + M @ only("dqdd_ds"))
    C_red = T.T @ (C @ T + M @ only("dqdd_dsd"))
    M_red = T.T @ M @ T
    for j, sj in enumerate(reduced):
        for i, si in enumerate(reduced):
            K_red[sj, si] += E[rows["g_ss" + tag(j, i)]] @ r[list(slots)]
    return T.T @ r, K_red, C_red, M_red


@pytest.mark.parametrize("m,slots", [(1, (3, 4)), (2, (3, 4, 5)), (2, (0, 1))])
def test_the_condensation_is_dalemberts_projection_for_any_number_of_reduced_coordinates(m, slots):
    """NumPy (constraints.project) and compiled (engine.elements.project) condensation against the
    dense projection, for the guide's one reduced co-ordinate and for two."""
    rng = np.random.default_rng(7 + m)
    n = schema.ELEMENT_DOFS
    reduced = slots[:m]
    E, rows = _random_map(rng, m, len(slots))
    r = rng.standard_normal(n)
    K, C, M = rng.standard_normal((3, n, n))
    expected = _dense_projection(E, rows, r, K, C, M, slots, reduced)
    monkey_rows = constraints.ROWS
    try:
        constraints.ROWS = rows                       # the map's rows for m co-ordinates
        got = constraints.project(E, r, K, C, M, slots, reduced)
    finally:
        constraints.ROWS = monkey_rows
    for a, b in zip(got, expected):
        np.testing.assert_allclose(a, b, rtol=1e-12, atol=1e-12)
    scratch = elements_scratch(len(slots), m)
    rc, Kc, Cc, Mc = r.copy(), K.copy(), C.copy(), M.copy()
    compiled_project(E, rc, Kc, Cc, Mc, np.array(slots), np.array(reduced), scratch)
    for a, b in zip((rc, Kc, Cc, Mc), expected):
        np.testing.assert_allclose(a, b, rtol=1e-12, atol=1e-12)


@numba.njit
def compiled_project(E, r, K, C, M, slots, reduced, w):
    elements.project(E, r, K, C, M, slots, reduced, w)


def elements_scratch(k, m):
    from collections import namedtuple
    Scratch = namedtuple("Scratch", ["px", "pr"])
    return Scratch(np.zeros((3, k)), np.zeros((3, m)))
