"""Contact between deformable bodies (-contact_pairs, mortar.hpp): the contact patch test on non-matching meshes."""

import numpy as np

from harness import displacement, test


@test("patch2d")
def patch2d(runner, kind):
    """Two blocks stacked, non-matching meshes on their interface (meshes/patch2d.geo: tri or quad), a uniform
    pressure q on the top: every slave node active with the pressure q (to 1e-10), the exact linear field, the contact
    forces of the two sides equal and opposite. Run with the default solver and with the iterative path."""
    q = 2.0
    mesh = {"tri": "meshes/patch2d.msh", "quad": "meshes/patch2d_quad.msh"}[kind]
    base = ["-options_file", "options/patch2d.yml", "-mesh_file", mesh]
    for solver, tol in (("auto", 1e-10), ("iterative", 1e-8)):
        r = runner.run(base + ["-contact_solver", solver], "patch %s %s" % (kind, solver))
        nodes = r.nodes()
        # The slave side: the upper block's bottom edge (y = 1, pressure reported); the master nodes carry none.
        on_interface = nodes[nodes["y"] == 1.0]
        slave = on_interface[np.isfinite(on_interface["gap"])]
        n = len(slave)
        runner.expect_true("%s: slave nodes found (%d) beside the master's (%d)" % (solver, n, len(on_interface) - n),
                           n >= 5 and len(on_interface) - n >= 3)
        runner.expect_equal("%s: active pairs" % solver, r.get("contact.active_pairs"), n)
        runner.expect_equal("%s: active slave nodes" % solver, int(slave["active"].sum()), n)
        runner.expect_close("%s: contact pressure = q at every slave node" % solver, slave["pressure"],
                            np.full(n, q), tol)
        W = 2.0
        runner.expect_close("%s: slave side force" % solver, r.get("contact.contact_force"), [0, q * W], tol,
                            tol * q * W)
        runner.expect_close("%s: master side force" % solver, r.get("contact.master_contact_force"), [0, -q * W], tol,
                            tol * q * W)
        runner.expect_close("%s: force balance" % solver, r.get("contact.force_balance"), 0, 0, tol)
        # Plane strain, sigma_yy = -q, sigma_xx = 0, u_x = 0 on the left edges, u_y = 0 at y = 0: one linear field
        # through both bodies, the interface closed.
        E, nu = r.get("material.E"), r.get("material.nu")
        exact = np.column_stack([nu * (1 + nu) * q / E * nodes["x"], -(1 - nu * nu) * q / E * nodes["y"]])
        runner.expect_close("%s: displacement = exact linear field" % solver, displacement(nodes), exact, 0,
                            tol * np.abs(exact).max())
