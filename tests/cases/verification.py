"""Verification tests: Hertz against Johnson's half-width and peak pressure, Lame and a column under its own weight
against their exact fields at the L2 rate h^2."""

import numpy as np

from harness import rate, test, yaml_options


def johnson(dim, R, P, E, nu):
    """Johnson's (1985, 4.2) contact half-width (2D, P per unit thickness) or radius (3D) a and peak pressure p0 of a
    cylinder or sphere of radius R pressed on a rigid flat by the load P: E* = E / (1 - nu^2); 2D a = sqrt(4 P R /
    (pi E*)), p0 = 2 P / (pi a); 3D a = (3 P R / (4 E*))^(1/3), p0 = 3 P / (2 pi a^2)."""
    E_star = E / (1 - nu * nu)
    if dim == 2:
        a = np.sqrt(4 * P * R / (np.pi * E_star))
        return a, 2 * P / (np.pi * a)
    a = (3 * P * R / (4 * E_star)) ** (1 / 3)
    return a, 3 * P / (2 * np.pi * a * a)


def area_on_plane(result, z):
    """The area of the cells' faces on the plane z = const, by hand from solution.h5 (a triangle of a tetrahedron, or a
    quadrilateral of a hexahedron, taken as the convex polygon of its vertices)."""
    xyz, cells, _ = result.solution()
    on = np.abs(xyz[:, 2] - z) < 1e-12
    area = 0.0
    for cell in cells:
        face = [v for v in cell if on[v]]
        if len(face) < 3:
            continue
        p = xyz[face][:, :2]
        p = p[np.argsort(np.arctan2(*(p - p.mean(axis=0)).T[::-1]))]
        area += 0.5 * abs(np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1]))
    return area


def hertz_refinement_levels(runner, case, factors, h_contact, bound, load, heap_check=True):
    """Runs options/CASE.yml on meshes/CASE.geo at each size factor, computes here the load P the model stands for
    with load(runner, result, what) and from it Johnson's a and p0 (johnson: R, E and nu of the case's files), checks
    the summary's comparison against them and the computed a within the contact element size h_contact x factor,
    prints the errors and checks that both errors of a and p0 decrease overall, ending at most bound on the finest
    mesh, and that the pressure profile's fitted a converges to Johnson's."""
    options = dict(yaml_options(runner.path("options/%s.yml" % case)))
    R = float(options["report_hertz"].split(",")[0])
    E, nu = float(options["material_E"]), float(options["material_nu"])
    rows = []
    for f in factors:
        r = runner.run(["-options_file", "options/%s.yml" % case, "-mesh_file", "meshes/%s.geo" % case,
                        "-mesh_size_factor", f], "%s factor %g" % (case, f), heap_check=heap_check)
        h = r.summary["hertz"]
        P = load(runner, r, "factor %g" % f)
        a, p0 = johnson(r.get("mesh.dim"), R, P, E, nu)
        # The program's own comparison uses the same formulas; summary.json holds 10 significant digits.
        runner.expect_close("factor %g: summary's Johnson a" % f, h["a"], a, 1e-9)
        runner.expect_close("factor %g: summary's Johnson p0" % f, h["p0"], p0, 1e-9)
        # The contact zone is resolved node by node: a_computed comes from the summed tributary lengths (2D) or areas
        # (3D) of the active nodes, so it cannot be closer to a than about the element size at the contact.
        h_c = h_contact * f
        runner.expect_close("factor %g: a within the contact element size %g" % (f, h_c), h["a_computed"], a, 0, h_c)
        # The fit of the nodal pressures' profile, p^2 = p0^2 (1 - r^2/a^2) over the active nodes within 0.8 of the
        # outermost one's radius, recomputed here from the node table (the contact centre is the origin). Its a does
        # not move by whole elements, but rests on few nodes on a coarse 3D mesh: within the contact element size too
        # (measured in 2D: 0.04 to 0.09 % at factors 2 to 0.25; in 3D: 7.5, 2.3, 0.17, 0.33 % at factors 4 to 1).
        nodes = r.nodes()
        active = nodes[nodes["active"] > 0]
        r2 = active["x"] ** 2 + (active["y"] ** 2 if case == "hertz3d" else 0)
        inner = r2 <= 0.64 * r2.max()
        slope, intercept = np.polyfit(r2[inner], active["pressure"][inner] ** 2, 1)
        a_fit = np.sqrt(-intercept / slope)
        runner.expect_close("factor %g: a of the pressure profile's fit" % f, h["a_fit"], a_fit, 1e-6)
        runner.expect_close("factor %g: the fit's a within the contact element size %g" % (f, h_c), a_fit, a, 0, h_c)
        rows.append((f, abs(h["a_computed"] - a) / a, abs(h["p0_computed"] - p0) / p0, abs(a_fit - a) / a,
                     r.get("contact.active_pairs"), r.get("iterations.active_set"), r.get("mesh.nodes")))
    print("  factor  nodes  active  iterations  a error %  p0 error %  fit a error %")
    for f, ea, ep, ef, act, its, n in rows:
        print("  %6g %6d %7d %11d %10.3f %11.3f %14.3f" % (f, n, act, its, 100 * ea, 100 * ep, 100 * ef))
    h = np.array([r[0] for r in rows])
    for col, name in ((1, "a"), (2, "p0")):
        e = np.array([r[col] for r in rows])
        # The error decreases overall: a positive log-log slope over the sequence and the finest mesh better than the
        # coarsest (successive values may cross: the contact zone grows by whole elements or rings of nodes).
        slope = np.polyfit(np.log(h), np.log(e), 1)[0]
        runner.expect_true("%s error decreases overall: log-log slope %.2f > 0, finest %.3f%% < coarsest %.3f%%" % (
            name, slope, 100 * e[-1], 100 * e[0]), slope > 0 and e[-1] < e[0])
        runner.expect_true("%s error on the finest mesh %.3f%% <= %g%%" % (name, 100 * e[-1], 100 * bound),
                           e[-1] <= bound)


# Hertz line contact (ARCHITECTURE.md, Johnson 1985 section 4.2): mesh size factors of meshes/hertz.geo and its
# element size at the contact point.
HERTZ_FACTORS = [4, 2, 1.4, 1]
HERTZ_H_CONTACT = 0.02


@test("hertz_refinement")
def hertz_refinement(runner):
    """Hertz cylinder on a flat: half-width and peak pressure converge to Johnson's values under mesh refinement."""

    def load(runner, r, what):
        # The traction of options/hertz.yml on the flat top, 2R wide (meshes/hertz.geo): P per unit thickness. The
        # rigid flat carries the whole load (round-off of a direct solve).
        options = dict(yaml_options(runner.path("options/hertz.yml")))
        P = -float(options["bc_traction"].split(":")[2]) * 2 * float(options["report_hertz"].split(",")[0])
        runner.expect_close("%s: contact force" % what, r.get("contact.contact_force"), [0, P], 1e-10, 1e-10 * P)
        runner.expect_equal("%s: symmetry fraction" % what, r.get("hertz.fraction"), 1.0)
        return P

    hertz_refinement_levels(runner, "hertz", HERTZ_FACTORS, HERTZ_H_CONTACT, 0.02, load)


# Hertz sphere on a flat (options/hertz3d.yml, an octant of a ball with two symmetry planes): mesh size factors of
# meshes/hertz3d.geo and its element size at the contact point.
HERTZ3D_FACTORS = [4, 2, 1.4, 1]
HERTZ3D_H_CONTACT = 0.04


@test("hertz3d_refinement")
def hertz3d_refinement(runner):
    """Hertz sphere on a flat: contact radius and peak pressure converge to Johnson's values under mesh refinement."""

    def load(runner, r, what):
        # Two symmetry planes: the model is a quarter of the hemisphere. It carries the pressure q times the area of
        # its faceted top z = 0 (computed here from the mesh), a little less than P / 4; Johnson's values are those of
        # the load P_model = 4 q area it stands for.
        q = float(dict(yaml_options(runner.path("options/hertz3d.yml")))["bc_pressure"].split(":")[1])
        P_model = 4 * q * area_on_plane(r, 0.0)
        runner.expect_equal("%s: symmetry fraction" % what, r.get("hertz.fraction"), 0.25)
        F = r.get("contact.contact_force")
        runner.expect_close("%s: the model carries P_model / 4" % what, F, [0, 0, P_model / 4], 0, 1e-10 * P_model)
        runner.expect_close("%s: contact force = applied load" % what, F, -np.array(r.get("contact.applied_force")),
                            0, 1e-10 * P_model)
        # summary.json holds 10 significant digits.
        runner.expect_close("%s: summary's P_model" % what, r.get("hertz.P_model"), P_model, 1e-9)
        # The faceted top falls short of the quarter disc by the segments its rim cuts off (10 % on the coarsest).
        runner.expect_close("%s: P_model close to P = q pi R^2" % what, P_model, q * np.pi * 10.0 ** 2, 0.12)
        return P_model

    # heap_check off: -malloc_debug validates the whole heap at every allocation, slow on the finer 3D meshes.
    hertz_refinement_levels(runner, "hertz3d", HERTZ3D_FACTORS, HERTZ3D_H_CONTACT, 0.03, load, heap_check=False)


@test("hertz_thickness")
def hertz_thickness(runner):
    """-report_hertz's P is per unit thickness in 2D: the Hertz case with -material_thickness 2 (the same traction,
    twice the force) has the same half-width and peak pressure, and its comparison is the same as with thickness 1
    (before, the doubled force was compared with P: -29 % on a and p0)."""
    ref = runner.run([], "hertz, thickness 1")
    thick = runner.run(["-material_thickness", "2"], "hertz, thickness 2")
    for key in ("hertz.fraction", "hertz.P_model", "hertz.a", "hertz.a_computed", "hertz.p0", "hertz.p0_computed"):
        runner.expect_close(key, thick.get(key), ref.get(key), 1e-9, 0)
    runner.expect_close("hertz.P_model is P", ref.get("hertz.P_model"), 10, 1e-3, 0)
    # The default case's own comparison far from Hertz's range (E = 5: a = 4.3 against R = 8) is not made, and not
    # an error either: the user gave no -report_hertz.
    soft = runner.run(["-material_E", "5"], "hertz, E = 5")
    runner.expect_true("E = 5: no Hertz comparison, a note instead",
                       "hertz" not in soft.summary and "not compared" in soft.output)


# Lame cylinder (options/lame_cylinder.yml): radii, internal pressure; size factors of meshes/lame*.geo.
LAME_A, LAME_B, LAME_P = 1.0, 2.0, 1.0
LAME_FACTORS = [0.5, 0.25, 0.125]

# Quadrature: Dunavant's 7-point rule of degree 5 on triangles (barycentric coordinates, weights summing to 1) and
# the 3 x 3 Gauss rule on quadrilaterals; both integrate the squared error of a smooth field well beyond O(h^2).
_A1, _B1, _A2, _B2 = 0.059715871789770, 0.470142064105115, 0.797426985353087, 0.101286507323456
TRI_POINTS = np.array([[1 / 3, 1 / 3, 1 / 3], [_A1, _B1, _B1], [_B1, _A1, _B1], [_B1, _B1, _A1], [_A2, _B2, _B2],
                       [_B2, _A2, _B2], [_B2, _B2, _A2]])
TRI_WEIGHTS = np.array([0.225] + [0.132394152788506] * 3 + [0.125939180544827] * 3)
_G, _GW = np.array([-np.sqrt(0.6), 0, np.sqrt(0.6)]), np.array([5 / 9, 8 / 9, 5 / 9])
QUAD_POINTS = np.array([(xi, eta) for xi in _G for eta in _G])
QUAD_WEIGHTS = np.array([wx * wy for wx in _GW for wy in _GW])


def lame_exact(x, E, nu):
    """Plane-strain displacement of the Lame cylinder: u_r = (1 + nu)/E ((1 - 2 nu) A r + B / r) with
    A = p a^2 / (b^2 - a^2), B = p a^2 b^2 / (b^2 - a^2) (sigma_rr = A - B/r^2, sigma_tt = A + B/r^2)."""
    A = LAME_P * LAME_A ** 2 / (LAME_B ** 2 - LAME_A ** 2)
    B = A * LAME_B ** 2
    r = np.hypot(x[:, 0], x[:, 1])
    ur = (1 + nu) / E * ((1 - 2 * nu) * A * r + B / r)
    return x * (ur / r)[:, None]


def l2_error(xyz, cells, u, exact):
    """||u_h - u||_L2 over the mesh, u_h interpolated with the P1/Q1 shape functions of each cell."""
    total = 0.0
    for c in cells:
        xe, ue = xyz[c], u[c]
        if len(c) == 3:
            N = TRI_POINTS
            detJ = np.full(len(N), abs(np.cross(xe[1] - xe[0], xe[2] - xe[0])))  # twice the area
            w = 0.5 * TRI_WEIGHTS
        else:
            xi, eta = QUAD_POINTS[:, 0], QUAD_POINTS[:, 1]
            N = 0.25 * np.column_stack([(1 - xi) * (1 - eta), (1 + xi) * (1 - eta), (1 + xi) * (1 + eta),
                                        (1 - xi) * (1 + eta)])
            dxi = 0.25 * np.column_stack([-(1 - eta), 1 - eta, 1 + eta, -(1 + eta)])
            deta = 0.25 * np.column_stack([-(1 - xi), -(1 + xi), 1 + xi, 1 - xi])
            Jx, Jy = dxi @ xe, deta @ xe
            detJ = np.abs(Jx[:, 0] * Jy[:, 1] - Jx[:, 1] * Jy[:, 0])
            w = QUAD_WEIGHTS
        d = N @ ue - exact(N @ xe)
        total += np.sum(w * detJ * np.sum(d * d, axis=1))
    return np.sqrt(total)


@test("lame_convergence")
def lame_convergence(runner, kind):
    """Lame cylinder under internal pressure: the L2 displacement error of P1 (tri) or Q1 (quad) falls as h^2."""
    mesh, cell_size = {"tri": ("meshes/lame.geo", 3), "quad": ("meshes/lame_quad.geo", 4)}[kind]
    errors, sizes = [], []
    for f in LAME_FACTORS:
        r = runner.run(["-options_file", "options/lame_cylinder.yml", "-mesh_file", mesh, "-mesh_size_factor", f],
                       "lame %s factor %g" % (kind, f))
        xyz, cells, u = r.solution()
        runner.expect_true("factor %g: %d cells, all with %d nodes" % (f, len(cells), cell_size),
                           all(len(c) == cell_size for c in cells))
        E, nu = r.get("material.E"), r.get("material.nu")
        errors.append(l2_error(xyz, cells, u, lambda x: lame_exact(x, E, nu)))
        sizes.append(f)
        print("  factor %g: %d nodes, L2 error %.4e" % (f, len(xyz), errors[-1]))
    rates = rate(np.array(sizes), np.array(errors))
    # Linear elements converge at O(h^2) in L2 for a smooth solution, and so does the polygonal approximation of
    # the arcs. Unstructured meshes do not refine exactly by the size factor, hence the +-0.2 band.
    for i, p in enumerate(rates):
        runner.expect_true("rate %g -> %g: %.3f in [1.8, 2.2]" % (sizes[i], sizes[i + 1], p), 1.8 <= p <= 2.2)


# Lame spherical shell (options/lame_sphere.yml): radii, internal pressure; size factors of meshes/lame3d*.geo (the
# hexahedra of lame3d_hex.geo are about half the size of the tetrahedra at the same factor).
LAME3D_A, LAME3D_B, LAME3D_P = 1.0, 2.0, 1.0
LAME3D_FACTORS = {"tet": [0.7, 0.5, 0.35, 0.25], "hex": [1.4, 1, 0.7]}

# Quadrature on tetrahedra: the 3 x 3 x 3 Gauss rule on the cube collapsed onto the tetrahedron (Duffy), degree 5;
# on hexahedra the 3 x 3 x 3 Gauss rule. Barycentric points and weights summing to the reference volume 1/6.
_U = 0.5 * (1 + _G)
_UW = 0.5 * _GW
_TET = [(u, v * (1 - u), w * (1 - u) * (1 - v), wu * wv * ww * (1 - u) ** 2 * (1 - v))
        for u, wu in zip(_U, _UW) for v, wv in zip(_U, _UW) for w, ww in zip(_U, _UW)]
TET_POINTS = np.array([[1 - l1 - l2 - l3, l1, l2, l3] for l1, l2, l3, _ in _TET])
TET_WEIGHTS = np.array([w for *_, w in _TET])
HEX_POINTS = np.array([(xi, eta, zeta) for xi in _G for eta in _G for zeta in _G])
HEX_WEIGHTS = np.array([wx * wy * wz for wx in _GW for wy in _GW for wz in _GW])
# VTK/XDMF vertex order of a hexahedron: the bottom face counter-clockwise, then the top face.
HEX_CORNERS = np.array([(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1), (-1, -1, 1), (1, -1, 1), (1, 1, 1),
                        (-1, 1, 1)])


def lame_sphere_exact(x, E, nu):
    """Displacement of the Lame sphere: u_r = p a^3 / (E (b^3 - a^3)) ((1 - 2 nu) r + (1 + nu) b^3 / (2 r^2))."""
    c = LAME3D_P * LAME3D_A ** 3 / (E * (LAME3D_B ** 3 - LAME3D_A ** 3))
    r = np.linalg.norm(x, axis=1)
    ur = c * ((1 - 2 * nu) * r + (1 + nu) * LAME3D_B ** 3 / (2 * r ** 2))
    return x * (ur / r)[:, None]


def l2_error_3d(xyz, cells, u, exact):
    """||u_h - u||_L2 over a mesh of tetrahedra, pyramids and hexahedra, u_h interpolated with the P1/Q1 shape
    functions; a pyramid is the hexahedron with its top four vertices collapsed onto its apex (its shape functions and
    its map are those of the collapsed hexahedron, whose Jacobian vanishes only at the apex, off the Gauss points)."""
    total = 0.0
    cells = [c if len(c) != 5 else np.concatenate([c, [c[4]] * 3]) for c in cells]
    for n in (4, 8):
        c = np.array([c for c in cells if len(c) == n], dtype=int)
        if not len(c):
            continue
        xe, ue = xyz[c], u[c]  # cells x nodes x 3
        if n == 4:
            N, w = TET_POINTS, TET_WEIGHTS
            J = np.stack([xe[:, 1] - xe[:, 0], xe[:, 2] - xe[:, 0], xe[:, 3] - xe[:, 0]], axis=1)
            detJ = np.abs(np.linalg.det(J))[:, None] * np.ones(len(w))
        else:
            s = HEX_CORNERS
            P = HEX_POINTS
            N = np.prod(1 + P[:, None, :] * s[None, :, :], axis=2) / 8  # points x nodes
            dN = np.stack([s[None, :, k] * np.prod(1 + np.delete(P[:, None, :] * s[None, :, :], k, axis=2), axis=2) / 8
                           for k in range(3)], axis=1)  # points x 3 x nodes
            J = np.einsum("qkn,cnd->cqkd", dN, xe)
            detJ = np.abs(np.linalg.det(J))
            w = HEX_WEIGHTS
        xq, uq = np.einsum("qn,cnd->cqd", N, xe), np.einsum("qn,cnd->cqd", N, ue)
        d = uq - exact(xq.reshape(-1, 3)).reshape(xq.shape)
        total += np.sum(w[None, :] * detJ * np.sum(d * d, axis=2))
    return np.sqrt(total)


@test("lame3d_convergence")
def lame3d_convergence(runner, kind):
    """Lame spherical shell under internal pressure: the L2 displacement error of P1 tetrahedra or Q1 hexahedra
    falls as h^2."""
    mesh, cell_size = {"tet": ("meshes/lame3d.geo", 4), "hex": ("meshes/lame3d_hex.geo", 8)}[kind]
    errors, sizes = [], []
    for f in LAME3D_FACTORS[kind]:
        r = runner.run(["-options_file", "options/lame_sphere.yml", "-mesh_file", mesh, "-mesh_size_factor", f],
                       "lame3d %s factor %g" % (kind, f), heap_check=False)
        xyz, cells, u = r.solution()
        runner.expect_true("factor %g: %d cells, all with %d nodes" % (f, len(cells), cell_size),
                           all(len(c) == cell_size for c in cells))
        E, nu = r.get("material.E"), r.get("material.nu")
        errors.append(l2_error_3d(xyz, cells, u, lambda x: lame_sphere_exact(x, E, nu)))
        # The mean cell size (volume / cells)^(1/3): gmsh's 3D meshes do not refine exactly by the size factor (the
        # cell count grows by 2.4 to 2.8 per factor 1.4), and the subdivided hexahedra even less so.
        sizes.append((np.pi / 6 * (LAME3D_B ** 3 - LAME3D_A ** 3) / len(cells)) ** (1 / 3))
        print("  factor %g: %d nodes, %d cells, h %.4f, L2 error %.4e" % (f, len(xyz), len(cells), sizes[-1],
                                                                          errors[-1]))
    rates = rate(np.array(sizes), np.array(errors))
    # As in 2D: O(h^2) for linear elements and for the faceted spheres; the +-0.2 band for unstructured meshes.
    for i, p in enumerate(rates):
        runner.expect_true("rate h %.4f -> %.4f: %.3f in [1.8, 2.2]" % (sizes[i], sizes[i + 1], p), 1.8 <= p <= 2.2)


# A column under its own weight on the conforming mesh of meshes/cube_mixed_conforming.geo: body force b per unit
# volume along -z, the bottom z = 0 pushed up by the traction b H (H = 1 its height), u_x = 0 on x = 0, u_y = 0 on
# y = 0 and u_z = 0 at the origin. Exact: sigma_zz = b (z - H), every other stress component zero, and the quadratic
# displacement u_x = -nu b x (z - H) / E, u_y = -nu b y (z - H) / E, u_z = b ((z - H)^2 - H^2 + nu (x^2 + y^2)) / (2 E).
COLUMN_B, COLUMN_H, COLUMN_VOLUME = 1.0, 1.0, 2.0
# gmsh 4.8 folds some tetrahedra near the pyramids at factor 0.25 (cells overlapping across a face, each with a
# positive volume: the volume of the cells exceeds the box's by 5.8e-5); the volume check below catches that.
COLUMN_FACTORS = [0.7, 0.5, 0.35]


def column_exact(x, E, nu):
    b, H = COLUMN_B, COLUMN_H
    s = x[:, 2] - H
    return np.column_stack([-nu * b * x[:, 0] * s / E, -nu * b * x[:, 1] * s / E,
                            b * (s * s - H * H + nu * (x[:, 0] ** 2 + x[:, 1] ** 2)) / (2 * E)])


@test("mixed_conforming_convergence")
def mixed_conforming_convergence(runner):
    """The column under its own weight on the conforming mesh of hexahedra, pyramids and tetrahedra
    (meshes/cube_mixed_conforming.geo) at size factors 0.7, 0.5, 0.35: the L2 displacement error falls as h^2."""
    errors, sizes = [], []
    for f in COLUMN_FACTORS:
        r = runner.run(["-mesh_file", "meshes/cube_mixed_conforming.geo", "-mesh_size_factor", f,
                        "-material_E", 1000, "-material_nu", 0.3, "-bc_dirichlet", "left:x,front:y,origin:z",
                        "-bc_body_force", "0,0,%g" % -COLUMN_B, "-bc_traction", "bottom:0:0:%g" % (COLUMN_B * COLUMN_H)],
                       "column factor %g" % f, heap_check=False)
        # The cells fill the box exactly once: the body force (b x their volume) balances the bottom traction (b H x
        # the bottom's area 2), both integrated exactly.
        runner.expect_close("factor %g: applied load = 0" % f, r.get("contact.applied_force"), [0, 0, 0], 0,
                            1e-12 * COLUMN_B * COLUMN_VOLUME)
        xyz, cells, u = r.solution()
        kinds = {n: sum(len(c) == n for c in cells) for n in (4, 5, 8)}
        runner.expect_true("factor %g: tetrahedra, pyramids and hexahedra %s" % (f, kinds), min(kinds.values()) > 0)
        E, nu = r.get("material.E"), r.get("material.nu")
        errors.append(l2_error_3d(xyz, cells, u, lambda x: column_exact(x, E, nu)))
        # The mean node spacing (volume / nodes)^(1/3): the halves refine alike (the hexahedra's divisions and the
        # tetrahedra's size both scale with the factor), but the cell counts of the kinds do not compare.
        sizes.append((COLUMN_VOLUME / len(xyz)) ** (1 / 3))
        print("  factor %g: %d nodes, cells %s, h %.4f, L2 error %.4e" % (f, len(xyz), kinds, sizes[-1], errors[-1]))
    rates = rate(np.array(sizes), np.array(errors))
    # O(h^2) for linear elements on a quadratic field; the +-0.2 band of the other 3D convergence tests.
    for i, p in enumerate(rates):
        runner.expect_true("rate h %.4f -> %.4f: %.3f in [1.8, 2.2]" % (sizes[i], sizes[i + 1], p), 1.8 <= p <= 2.2)
