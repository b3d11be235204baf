"""Bodies and materials per physical group: a bar of two materials in series against its exact end displacement,
and a mesh of two bodies with the body field."""

import os

import numpy as np

from harness import test

# The bars of meshes/bimaterial_bar.geo and bimaterial_bar3d.geo: soft on [0, L1], stiff on [L1, L1 + L2].
BAR_L1, BAR_L2, BAR_E, BAR_T = 1.2, 0.8, {"soft": 100.0, "stiff": 300.0}, 2.0


def uniaxial_strain(E, t, model):
    """The axial strain of a bar (nu = 0) under the dead traction t: t / E (linear); svk: the root of
    P = F S = (1 + e) E (e + e^2 / 2) = t (Green-Lagrange strain e + e^2 / 2, first Piola-Kirchhoff stress P)."""
    if model == "linear":
        return t / E
    roots = np.roots([0.5 * E, 1.5 * E, E, -t])
    return min(r.real for r in roots if abs(r.imag) < 1e-12 and r.real > 0)


@test("bimaterial_bar")
def bimaterial_bar(runner, dim):
    """A bar of two materials in series (nu = 0) pulled at one end: every node's axial displacement is the series
    springs' exact value, linear and svk (uniform strain in each material), to 1e-10 of the end displacement."""
    geo, supports, traction = {"2d": ("meshes/bimaterial_bar.geo", "left:x,origin:y", "right:%g:0" % BAR_T),
                               "3d": ("meshes/bimaterial_bar3d.geo", "left:x,origin:yz,corner:z",
                                      "right:%g:0:0" % BAR_T)}[dim]
    E = ",".join("%s:%g" % kv for kv in BAR_E.items())
    # nu per group in 2D, one value in 3D: both forms of the option.
    nu = "soft:0,stiff:0" if dim == "2d" else "0"
    for model in ("linear", "svk"):
        r = runner.run(["-mesh_file", geo, "-material_model", model, "-material_E", E, "-material_nu", nu,
                        "-bc_dirichlet", supports, "-bc_traction", traction], "bimaterial bar %s %s" % (dim, model))
        runner.expect_equal("E per group in summary.json", r.get("material.E"), BAR_E)
        e1, e2 = (uniaxial_strain(BAR_E[g], BAR_T, model) for g in ("soft", "stiff"))
        nodes = r.nodes()
        x = nodes["x"]
        exact = np.where(x < BAR_L1, e1 * x, e1 * BAR_L1 + e2 * (x - BAR_L1))
        end = e1 * BAR_L1 + e2 * BAR_L2
        right = np.isclose(x, BAR_L1 + BAR_L2)
        runner.expect_close("%s: end displacement %.12g" % (model, end), nodes["u_x"][right],
                            np.full(right.sum(), end), 1e-10)
        runner.expect_close("%s: axial displacement" % model, nodes["u_x"], exact, 0, 1e-10 * end)
        for k in ("u_y", "u_z")[:2 if dim == "3d" else 1]:
            runner.expect_close("%s: %s" % (model, k), nodes[k], 0 * x, 0, 1e-10 * end)


@test("two_bodies")
def two_bodies(runner):
    """Two blocks of one mesh that share no node: two bodies, numbered by their smallest file cell index (the lower
    block's cells come first), written as the cell field 'body'; each body's displacement scales with 1 / its E."""
    args = ["-mesh_file", "meshes/two_blocks.geo", "-bc_dirichlet", "lower_bottom:xy,upper_bottom:xy",
            "-bc_traction", "lower_top:0:-1,upper_top:0.5:0"]
    a = runner.run(args + ["-material_E", "lower:100,upper:50"], "two bodies, upper E 50")
    b = runner.run(args + ["-material_E", "lower:100,upper:100"], "two bodies, upper E 100")
    runner.expect_equal("bodies in summary.json", a.get("mesh.bodies"), 2)
    import h5py

    with h5py.File(os.path.join(a.dir, "solution.h5"), "r") as f:
        body = f["mesh/body"][()].ravel()
        xyz = f["mesh/coordinates"][()]
        topo = f["mesh/topology"][()]
    # Mixed topology (triangles and quadrilaterals): a type id before each cell's nodes.
    centroids_y, i = [], 0
    while i < len(topo):
        n = {4: 3, 5: 4}[int(topo[i])]
        centroids_y.append(xyz[topo[i + 1:i + 1 + n], 1].mean())
        i += n + 1
    expected = (np.array(centroids_y) > 1.25).astype(int)
    runner.expect_equal("body of each cell (%d and %d cells)" % tuple(np.bincount(expected)), body.tolist(),
                        expected.tolist())
    with open(os.path.join(a.dir, "solution.xdmf")) as f:
        runner.expect_true("the XDMF names the body attribute", 'Attribute Name="body"' in f.read())
    na, nb = a.nodes(), b.nodes()
    upper = na["y"] > 1.25
    for k in ("u_x", "u_y"):
        scale = np.abs(nb[k]).max()
        runner.expect_close("lower body unchanged (%s)" % k, na[k][~upper], nb[k][~upper], 0, 1e-12 * scale)
        runner.expect_close("upper body doubles (%s)" % k, na[k][upper], 2 * nb[k][upper], 0, 1e-12 * scale)
