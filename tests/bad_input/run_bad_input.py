#!/usr/bin/python3
"""Runs one case of the catalogue of bad inputs: the signorini executable under mpiexec, expected to fail cleanly.

A case passes when the run
  - exits non-zero (a run that hangs is left to CTest's TIMEOUT: no wall-clock limit here),
  - prints exactly one line starting with "signorini: error:", on stderr, holding every expected substring (the
    offending input and what was expected),
  - prints no PETSc error message or stack trace and leaves no process behind,
  - leaves no half-written output: nothing in its work directory that was not there before the run (no -output_dir,
    nor a parent of it that the run made), and where the case starts from an earlier good run in that directory,
    every file of that run byte for byte and with its modification time.
The signal cases interrupt a long run instead, once it reports the first active-set iteration of its third load step
(the first two steps are written to DIR/incomplete by then), and expect a non-zero exit and no summary.json.

    run_bad_input.py --exe build/signorini --np 2 material_E_zero
    run_bad_input.py --exe build/signorini --np 1 --all
    run_bad_input.py --list

Exit status 0 when every check passed, 1 when one failed, 2 on a usage error, 77 when every case was skipped (the
cases that need strace, where it is missing).
"""
import argparse
import hashlib
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
ERROR_PREFIX = "signorini: error:"
# A block that -malloc_dump lists at PetscFinalize: PETSc memory the failed run did not free.
LEAKED_MEMORY = re.compile(r"^\[\s*\d+\]\s*\d+ bytes \S+\(\) at ", re.MULTILINE)
FORBIDDEN = ("PETSC ERROR", "Caught signal", "Segmentation", "AddressSanitizer", "runtime error:", "terminate called",
             "HDF5-DIAG")

# The built-in Hertz case and the clamped beam, as good runs that a bad option then spoils.
HERTZ = []
BEAM = ["-options_file", "{root}/options/beam_on_floor.yml"]
# The beam without its clamp and with no obstacle: nothing holds it.
# The unit cube of hexahedra on a rigid plane (3D).
CUBE = ["-options_file", "{root}/options/cube_on_plane.yml"]
# Two blocks stacked (the contact patch test), the upper one held by contact with the lower one alone.
PATCH = ["-options_file", "{root}/options/patch2d.yml"]
SLIDING = ["-options_file", "{root}/options/sliding_block.yml"]
# A bar of two physical surfaces (soft, stiff; all: both) in one body, held and pulled: materials per group.
BAR = ["-mesh_file", "{root}/meshes/bimaterial_bar.geo", "-bc_dirichlet", "left:x,origin:y", "-bc_traction",
       "right:2:0"]
LOOSE_BEAM = ["-mesh_file", "{root}/meshes/beam.msh", "-material_E", "1000", "-material_nu", "0.3",
              "-bc_pressure", "top:0.2"]


def mesh(name):
    return ["-mesh_file", "{meshes}/" + name]


# name: (arguments, expected substrings of the error line, options). Options: previous = arguments of a good run
# made first into the same -output_dir, which the bad run must leave untouched; signal = interrupt the run with it.
# {work} is the case's work directory, which the bad run must leave as it found it.
CASES = {
    # Mesh files.
    "mesh_missing": (mesh("does_not_exist.msh"), ["does_not_exist.msh", "cannot open", "expected"], {}),
    "mesh_empty": (mesh("empty.msh"), ["empty.msh", "is empty", "expected"], {}),
    "mesh_not_gmsh": (mesh("not_gmsh.msh"), ["not_gmsh.msh", "$MeshFormat", "expected"], {}),
    "mesh_truncated": (mesh("truncated.msh"), ["truncated.msh", "cannot read", "expected"], {}),
    "mesh_geo_syntax": (mesh("syntax_error.geo"), ["syntax_error.geo", "syntax error", "expected"], {}),
    "mesh_is_directory": (["-mesh_file", "{meshes}"], ["meshes'", "a directory", "expected"], {}),
    # The parallel mesh file (-mesh_save, a .h5 -mesh_file).
    "mesh_h5_missing": (mesh("does_not_exist.h5"), ["does_not_exist.h5", "cannot open", "written by -mesh_save"], {}),
    "mesh_h5_not_hdf5": (mesh("not_hdf5.h5"), ["-mesh_file", "not_hdf5.h5", "no HDF5 file",
                                               "expected a mesh written by -mesh_save"], {}),
    "mesh_h5_not_signorini": (mesh("not_signorini.h5"), ["-mesh_file", "not_signorini.h5", "no signorini mesh",
                                                         "expected a mesh written by -mesh_save"], {}),
    "mesh_h5_old_format": (mesh("old_format.h5"), ["-mesh_file", "old_format.h5", "'signorini mesh 1'",
                                                   "write it again with -mesh_save",
                                                   "expected a mesh written by -mesh_save"], {}),
    # A cell's vertex out of range in signorini's blocks (damaged.h5: tet_only.msh saved, one entry overwritten): every
    # rank stops with the first rank's finding.
    "mesh_h5_damaged": (mesh("damaged.h5"), ["-mesh_file", "damaged.h5", "is damaged", "is not one of its 4 vertices",
                                             "expected a mesh written by -mesh_save"], {}),
    "mesh_h5_metis": (mesh("not_signorini.h5") + ["-mesh_partitioner", "metis"],
                      ["-mesh_partitioner metis", "not_signorini.h5", "expected ptscotch or simple"], {}),
    "mesh_save_unwritable": (["-mesh_save", "{file}/mesh.h5"], ["-mesh_save", "a_file/mesh.h5", "cannot create",
                                                               "expected a writable .h5 path"], {}),
    "mesh_save_not_h5": (["-mesh_save", "{work}/mesh.msh"], ["-mesh_save", "mesh.msh", "ending in .h5"], {}),
    # A mesh that fails to read: no file, and no temporary one, beside the -mesh_save path.
    "mesh_save_bad_mesh": (mesh("empty.msh") + ["-mesh_save", "{work}/saved.h5"], ["empty.msh", "is empty"], {}),
    "mesh_without_groups": (mesh("no_groups.msh") + ["-bc_dirichlet", "left:x:y"],
                            ["'left'", "not in the mesh", "no physical groups"], {}),
    "mesh_lines_only": (mesh("lines_only.msh"), ["lines_only.msh", "no triangles or quadrilaterals", "expected"], {}),
    "mesh_prism": (mesh("prism.msh"), ["prism.msh", "Prism", "expected linear tetrahedra"], {}),
    "mesh_duplicate_nodes": (mesh("duplicate_nodes.msh"),
                             ["duplicate_nodes.msh", "duplicate node tag 3", "expected unique"], {}),
    "mesh_inverted_element": (mesh("inverted.msh"), ["inverted.msh", "inverted element", "element 2", "expected"],
                              {}),
    "mesh_zero_area_element": (mesh("zero_area.msh"), ["zero_area.msh", "element 3 has zero area", "expected"], {}),
    "mesh_inverted_tetrahedron": (mesh("inverted_tet.msh"),
                                  ["inverted_tet.msh", "inverted element", "element 2", "expected"], {}),
    # The surfaces of meshes/cube_tet.geo (gmsh -2): triangles in 3D space without the tetrahedra.
    "mesh_surface_3d": (mesh("surface_3d.msh"), ["surface_3d.msh", "no volume cells", "surface mesh cannot be the body",
                                                 "expected tetrahedra, pyramids or hexahedra"], {}),
    "mesh_bowtie_quad": (mesh("bowtie.msh"), ["bowtie.msh", "element 1 is not convex", "expected"], {}),
    # Two positive tetrahedra on the same side of the face they share (gmsh 4.8 makes such folds next to pyramids).
    "mesh_folded_cells": (mesh("folded_tet.msh"), ["folded_tet.msh", "elements 1 and 2 overlap", "folded mesh",
                                                   "expected"], {}),
    "mesh_curve_not_edges": (mesh("curve_not_edge.msh") + ["-bc_traction", "diagonal:0:1"],
                             ["'diagonal'", "not an edge", "expected"], {}),
    # Two tetrahedra sharing a face; the physical surface's triangle (1, 2, 5) cuts through them.
    "mesh_surface_not_faces": (mesh("surface_not_face.msh") + ["-bc_traction", "patch:0:0:1"],
                               ["surface_not_face.msh", "'patch'", "not a face of any cell", "expected"], {}),
    "mesh_geo_gmsh_crash": (mesh("gmsh_crash.geo"), ["gmsh_crash.geo", "gmsh crashed", "Mesh.Algorithm = 8",
                                                     "expected", "another Mesh.Algorithm"], {}),
    "mesh_geo_too_many_cells": (["-options_file", "{root}/options/hertz.yml", "-mesh_file", "{root}/meshes/hertz.geo",
                                 "-mesh_size_factor", "1e-3"], ["hertz.geo", "would have about", "-mesh_max_cells",
                                                                "expected a coarser mesh"], {}),
    "mesh_geo_over_max_cells": (["-options_file", "{root}/options/hertz.yml", "-mesh_file", "{root}/meshes/hertz.geo",
                                 "-mesh_max_cells", "1000"], ["hertz.geo", "more than -mesh_max_cells 1e+03"], {}),
    "mesh_max_cells_fraction": (["-options_file", "{root}/options/hertz.yml", "-mesh_file", "{root}/meshes/hertz.geo",
                                 "-mesh_max_cells", "100000.5"],
                                ["-mesh_max_cells 100000.5 is not a whole number",
                                 "expected a whole number in [1, 1e+12]"], {}),
    "mesh_max_cells_zero": (["-mesh_max_cells", "0"], ["-mesh_max_cells 0", "[1, 1e+12]"], {}),
    "mesh_size_factor_zero": (["-mesh_size_factor", "0"], ["-mesh_size_factor 0", "[0.001, 1000]"], {}),
    "mesh_partitioner_bogus": (["-mesh_partitioner", "bogus"], ["-mesh_partitioner", "'bogus'", "expected metis"], {}),
    # Material.
    "material_E_zero": (["-material_E", "0"], ["-material_E 0", "expected", "(0, inf)"], {}),
    "material_E_negative": (["-material_E", "-200"], ["-material_E -200", "expected", "(0, inf)"], {}),
    "material_E_nan": (["-material_E", "nan"], ["-material_E nan", "expected a finite"], {}),
    "material_E_not_a_number": (["-material_E", "abc"], ["-material_E abc", "expected a finite real number"], {}),
    "material_E_empty": (["-material_E", ""], ["-material_E", "without a value", "expected a number"], {}),
    "material_E_hex": (["-material_E", "0x10"], ["-material_E 0x10", "decimal or scientific notation"], {}),
    "material_E_tiny": (["-material_E", "1e-300"], ["-material_E 1e-300", "stiffness scale", "[1e-06, 1e+24]"], {}),
    "material_thickness_tiny": (["-material_thickness", "1e-300"],
                                ["-material_thickness 1e-300", "stiffness scale", "[1e-06, 1e+24]"], {}),
    "material_nu_half": (["-material_nu", "0.5"], ["-material_nu 0.5", "expected", "(-1, 0.5)"], {}),
    "material_nu_minus_one": (["-material_nu", "-1"], ["-material_nu -1", "expected", "(-1, 0.5)"], {}),
    "material_nu_inf": (["-material_nu", "inf"], ["-material_nu inf", "expected"], {}),
    "material_plane_on_3d": (CUBE + ["-material_plane", "stress"], ["-material_plane", "mesh is 3D", "expected"],
                             {}),
    "material_thickness_on_3d": (CUBE + ["-material_thickness", "2"],
                                 ["-material_thickness", "mesh is 3D", "expected"], {}),
    "material_thickness_zero": (["-material_thickness", "0"], ["-material_thickness 0", "expected", "(0, inf)"], {}),
    "material_thickness_minus_inf": (["-material_thickness", "-inf"], ["-material_thickness -inf", "expected"], {}),
    "material_model_unknown": (["-material_model", "neo"], ["-material_model", "neo", "linear svk"], {}),
    "material_model_empty": (["-material_model", ""], ["-material_model", "without a value", "linear or svk"], {}),
    # Materials per physical group of cells (-material_E GROUP:E,..., -material_nu GROUP:NU,...).
    "material_group_uncovered": (BAR + ["-material_E", "soft:100"],
                                 ["-material_E soft:100", "cell 127 (gmsh element 136", "'stiff', 'all'",
                                  "in none of the option's groups", "cover every cell exactly once"], {}),
    "material_group_overlap": (BAR + ["-material_nu", "all:0.2,soft:0.1"],
                               ["-material_nu all:0.2,soft:0.1", "cell 1 (gmsh element 10", "is in 2 ('soft', 'all')",
                                "cover every cell exactly once"], {}),
    "material_group_unknown": (BAR + ["-material_E", "steel:100,stiff:300"],
                               ["-material_E steel:100,stiff:300", "'steel' is not in the mesh",
                                "physical surfaces: soft, stiff, all"], {}),
    "material_group_wrong_dimension": (BAR + ["-material_E", "left:100,stiff:300"],
                                       ["-material_E left:100,stiff:300", "'left' has dimension 1",
                                        "physical surfaces (dimension 2"], {}),
    "material_group_malformed": (BAR + ["-material_E", "soft:100:2,stiff:300"],
                                 ["-material_E soft:100:2,stiff:300", "'soft:100:2' is malformed",
                                  "GROUP:E items"], {}),
    "material_group_nu_out_of_range": (BAR + ["-material_nu", "soft:0.5,stiff:0"],
                                       ["-material_nu soft:0.5,stiff:0", "'soft:0.5' is out of range", "GROUP:NU",
                                        "(-1, 0.5)"], {}),
    "material_group_E_scale": (BAR + ["-material_E", "soft:1e-300,stiff:1"],
                               ["-material_E soft:1e-300", "stiffness scale", "[1e-06, 1e+24]"], {}),
    "material_group_twice": (BAR + ["-material_E", "soft:1,soft:2"],
                             ["-material_E soft:1,soft:2", "'soft' is given twice", "each group once"], {}),
    "material_model_group_malformed": (BAR + ["-material_model", "soft:neo,stiff:linear"],
                                       ["-material_model soft:neo,stiff:linear", "'soft:neo' is malformed",
                                        "GROUP:MODEL items", "linear or svk"], {}),
    "material_model_group_twice": (BAR + ["-material_model", "soft:svk,soft:linear"],
                                   ["-material_model soft:svk,soft:linear", "'soft' is given twice",
                                    "each group once"], {}),
    "material_model_group_uncovered": (BAR + ["-material_model", "soft:svk"],
                                       ["-material_model soft:svk", "cell 127 (gmsh element 136",
                                        "in none of the option's groups", "cover every cell exactly once"], {}),
    "material_thickness_group_uncovered": (BAR + ["-material_thickness", "soft:2"],
                                           ["-material_thickness soft:2", "cell 127 (gmsh element 136",
                                            "in none of the option's groups", "cover every cell exactly once"], {}),
    "material_thickness_group_negative": (BAR + ["-material_thickness", "soft:-1,stiff:1"],
                                          ["-material_thickness soft:-1,stiff:1", "'soft:-1' is out of range",
                                           "GROUP:T"], {}),
    "material_thickness_group_scale": (BAR + ["-material_E", "soft:1e-5,stiff:1", "-material_thickness",
                                              "soft:0.01,stiff:1"],
                                       ["-material_E soft:1e-5 with -material_thickness soft:0.01", "stiffness scale",
                                        "[1e-06, 1e+24]"], {}),
    # Obstacles.
    "obstacle_segments_on_3d": (CUBE + ["-obstacle_segments", "-1,0,3,0"],
                                ["-obstacle_segments", "2D shape", "mesh is 3D", "expected -obstacle_planes"], {}),
    "obstacle_planes_on_2d": (["-obstacle_planes", "0,0,-8,0,0,1"],
                              ["-obstacle_planes", "3D shape", "mesh is 2D", "expected -obstacle_segments"], {}),
    "obstacle_arcs_on_3d": (CUBE + ["-obstacle_arcs", "0,0,20,200,340,8"],
                            ["-obstacle_arcs", "2D shape", "mesh is 3D", "expected -obstacle_planes"], {}),
    "obstacle_discs_on_3d": (CUBE + ["-obstacle_discs", "0,-20,1"],
                             ["-obstacle_discs", "2D shape", "mesh is 3D", "expected -obstacle_planes"], {}),
    "obstacle_spheres_on_2d": (["-obstacle_spheres", "0,0,-20,12"],
                               ["-obstacle_spheres", "3D shape", "mesh is 2D", "expected -obstacle_segments"], {}),
    "obstacle_cylinders_on_2d": (["-obstacle_cylinders", "0,0,-20,0,0,1,12"],
                                 ["-obstacle_cylinders", "3D shape", "mesh is 2D", "expected -obstacle_segments"], {}),
    "bc_body_force_two_values_on_3d": (CUBE + ["-bc_body_force", "1,2"],
                                       ["-bc_body_force", "2 value(s)", "expected 3", "BX,BY,BZ"], {}),
    "bc_point_force_two_values_on_3d": (CUBE + ["-bc_point_force", "top:1:2"],
                                        ["-bc_point_force 'top:1:2'", "2 value(s)", "expected 3"], {}),
    "obstacle_sphere_radius_zero": (CUBE + ["-obstacle_spheres", "0,0,-1,0"],
                                    ["-obstacle_spheres item 1", "radius 0"], {}),
    "bc_traction_two_values_on_3d": (CUBE + ["-bc_traction", "top:0:-1"],
                                     ["-bc_traction", "2 value(s)", "expected 3"], {}),
    # Meshed obstacles (-obstacle_mesh): each error names the file and the element, node or group at fault.
    "obstacle_mesh_missing": (CUBE + ["-obstacle_mesh", "{meshes}/no_such_punch.msh"],
                              ["no_such_punch.msh", "cannot open obstacle mesh file", "expected a readable"], {}),
    "obstacle_mesh_inconsistent": (CUBE + ["-obstacle_mesh", "{meshes}/obstacle_inconsistent.msh"],
                                   ["obstacle_inconsistent.msh", "element 7 and element 8", "same direction",
                                    "expected consistently oriented facets"], {}),
    "obstacle_mesh_nonmanifold": (CUBE + ["-obstacle_mesh", "{meshes}/obstacle_nonmanifold.msh"],
                                  ["obstacle_nonmanifold.msh", "edge (nodes 1, 2) is shared by 3 elements",
                                   "element 11, element 12, element 13", "expected a manifold surface"], {}),
    "obstacle_mesh_zero_area": (CUBE + ["-obstacle_mesh", "{meshes}/obstacle_zero_area.msh"],
                                ["obstacle_zero_area.msh", "element 21 has zero area", "expected"], {}),
    "obstacle_mesh_polyline_inconsistent": (["-obstacle_mesh", "{meshes}/obstacle_polyline_inconsistent.msh"],
                                            ["obstacle_polyline_inconsistent.msh", "element 4 and element 5 both end "
                                             "at node 2", "expected consistently oriented lines"], {}),
    "obstacle_mesh_unknown_group": (CUBE + ["-obstacle_mesh", "{root}/meshes/flat_obstacle.msh:roof"],
                                    ["flat_obstacle.msh", "no physical group 'roof'", "expected one of: 'floor' (2D)"],
                                    {}),
    "obstacle_mesh_group_of_other_dimension": (CUBE + ["-obstacle_mesh", "{root}/meshes/cube.msh:body"],
                                               ["cube.msh", "group 'body' is 3D", "expected a 2D group"], {}),
    "obstacle_mesh_surface_for_2d": (["-obstacle_mesh", "{root}/meshes/flat_obstacle.msh"],
                                     ["flat_obstacle.msh", "has only 28 element(s) of dimension 2",
                                      "expected 2-node line elements (the obstacle of a 2D body)"], {}),
    "obstacle_mesh_volume_only": (CUBE + ["-obstacle_mesh", "{meshes}/tet_only.msh"],
                                  ["tet_only.msh", "has only 1 element(s) of dimension 3",
                                   "expected 3-node triangles or 4-node quadrilaterals"], {}),
    "obstacle_mesh_empty_group": (CUBE + ["-obstacle_mesh", "{root}/meshes/flat_obstacle.msh:"],
                                  ["-obstacle_mesh item", "empty group name", "expected FILE or FILE:GROUP"], {}),
    "obstacle_segment_zero_length": (["-obstacle_segments", "1,-8,1,-8"],
                                     ["-obstacle_segments item 1", "zero length"], {}),
    "obstacle_segments_count": (["-obstacle_segments", "-12,-8,12"],
                                ["-obstacle_segments", "3 number(s)", "expected a multiple of 4"], {}),
    "obstacle_segments_nan": (["-obstacle_segments", "-12,-8,nan,-8"],
                              ["-obstacle_segments -12,-8,nan,-8", "value 3 'nan'", "expected a finite"], {}),
    "obstacle_segments_empty": (["-obstacle_segments", ""], ["-obstacle_segments", "without a value", "no obstacle"],
                                {}),
    "obstacle_segments_hex": (["-obstacle_segments", "-12,-8,0xc,-8"], ["-obstacle_segments", "value 3 '0xc'"], {}),
    "obstacle_segments_not_a_number": (["-obstacle_segments", "-12,-8,x,-8"],
                                       ["-obstacle_segments -12,-8,x,-8", "'x'", "expected a finite real number"],
                                       {}),
    "obstacle_disc_radius_zero": (["-obstacle_segments", "-12,-8,12,-8", "-obstacle_discs", "0,-20,0"],
                                  ["-obstacle_discs item 1", "radius", "expected > 0"], {}),
    "obstacle_disc_radius_negative": (["-obstacle_discs", "0,-20,-1"],
                                      ["-obstacle_discs item 1", "radius -1", "expected > 0"], {}),
    "obstacle_arc_no_segments": (["-obstacle_arcs", "0,0,20,200,340,0"],
                                 ["-obstacle_arcs item 1", "has 0 segments", "expected a whole number in [1, 1e+06]"],
                                 {}),
    "obstacle_arc_too_many_segments": (["-obstacle_arcs", "0,0,20,200,340,1000000000"],
                                       ["-obstacle_arcs item 1", "has 1e+09 segments", "[1, 1e+06]"], {}),
    "obstacle_arc_count": (["-obstacle_arcs", "0,0,20,200,340"],
                           ["-obstacle_arcs", "5 number(s)", "expected a multiple of 6"], {}),
    "obstacle_arc_angle_huge": (["-obstacle_arcs", "1,-5,5,60,1e300,10"],
                                ["-obstacle_arcs item 1", "angles 60, 1e+300",
                                 "expected THETA0 and THETA1 in [-720, 720]"], {}),
    "obstacle_arc_more_than_a_turn": (["-obstacle_arcs", "1,-5,5,60,420.5,10"],
                                      ["-obstacle_arcs item 1", "sweeps 360.5 degrees",
                                       "expected 0 < |THETA1 - THETA0| <= 360"], {}),
    "obstacle_arc_equal_angles": (["-obstacle_arcs", "0,0,20,200,200,8"],
                                  ["-obstacle_arcs item 1", "sweeps 0 degrees", "expected 0 <"], {}),
    # A full turn in two segments would lay them on each other.
    "obstacle_arc_half_turn_segments": (["-obstacle_arcs", "0,-20,12,450,90,2"],
                                        ["-obstacle_arcs item 1", "2 segment(s) for a sweep of -360 degrees",
                                         "less than 180 degrees"], {}),
    "obstacle_arc_radius_nan": (["-obstacle_arcs", "0,0,nan,200,340,8"],
                                ["-obstacle_arcs", "value 3 'nan'", "expected a finite"], {}),
    # Boundary conditions and loads.
    "bc_traction_one_value": (["-bc_traction", "top:1"], ["-bc_traction 'top:1'", "1 value(s)", "expected 2"], {}),
    "bc_traction_not_numbers": (["-bc_traction", "top:a:b"], ["-bc_traction 'top:a:b'", "'a'", "expected a finite"],
                                {}),
    "bc_dirichlet_component_z": (["-bc_dirichlet", "top:z"], ["-bc_dirichlet 'top:z'", "'z'", "expected x or y"], {}),
    "bc_dirichlet_no_component": (["-bc_dirichlet", "top_centre"], ["-bc_dirichlet 'top_centre'", "expected GROUP"],
                                  {}),
    "bc_pressure_nan": (["-bc_pressure", "top:nan"], ["-bc_pressure 'top:nan'", "'nan'", "expected a finite"], {}),
    "bc_body_force_three_values": (["-bc_body_force", "1,2,3"], ["-bc_body_force", "3 value(s)", "expected 2"], {}),
    "bc_body_force_not_a_number": (["-bc_body_force", "1,x"], ["-bc_body_force 1,x", "'x'", "expected a finite real"],
                                   {}),
    "bc_dirichlet_empty": (["-bc_dirichlet", ""], ["-bc_dirichlet", "without a value", "GROUP:COMPONENT"], {}),
    "bc_traction_empty_item": (["-bc_traction", "top:0:-0.625,"], ["-bc_traction top:0:-0.625,", "empty item 2"], {}),
    "bc_traction_hex": (["-bc_traction", "top:0:-0x1"], ["-bc_traction 'top:0:-0x1'", "'-0x1'", "expected a finite"],
                        {}),
    "bc_traction_huge": (["-bc_traction", "top:0:-1e308"],
                         ["-bc_traction group 'top' value -1e+308", "out of scale", "|value| <= 2e+08"], {}),
    "bc_point_force_huge": (["-bc_point_force", "contact_point:0:1e200"],
                            ["-bc_point_force group 'contact_point' value 1e+200", "out of scale"], {}),
    "bc_dirichlet_huge": (["-bc_dirichlet", "top_centre:x=1e300"],
                          ["-bc_dirichlet group 'top_centre' value 1e+300", "body diagonal"], {}),
    # Ramps @T0:T1 of the load steps' pseudo-time: the option, the item, what is wrong and the syntax.
    "bc_ramp_reversed": (["-bc_pressure", "top:1@0.5:0.2"],
                         ["-bc_pressure 'top:1@0.5:0.2'", "ramp '@0.5:0.2'", "does not start before it ends",
                          "expected one suffix @T0:T1 with numbers 0 <= T0 < T1 <= 1"], {}),
    "bc_ramp_not_numbers": (["-bc_traction", "top:0:-0.625@a:1"],
                            ["-bc_traction 'top:0:-0.625@a:1'", "ramp '@a:1'", "not two numbers", "expected one suffix"],
                            {}),
    "bc_ramp_outside": (["-bc_body_force", "0,-1@0:1.5"],
                        ["-bc_body_force '0,-1@0:1.5'", "ramp '@0:1.5'", "outside [0, 1]", "expected one suffix"], {}),
    "bc_ramp_twice": (["-bc_dirichlet", "top_centre:x=0.01@0:0.5@0.5:1,contact_point:x"],
                      ["-bc_dirichlet 'top_centre:x=0.01@0:0.5@0.5:1'", "two ramps", "expected one suffix"], {}),
    "bc_dirichlet_two_ramps": (["-options_file", "{root}/options/block_on_floor.yml", "-bc_dirichlet",
                                "left:x=0.01@0:0.5,bottom:x=0.01@0.5:1"],
                               ["component x of node 1 (in file order)", "0.01@0:0.5 by item 'left:x=0.01@0:0.5'",
                                "0.01@0.5:1 by item 'bottom:x=0.01@0.5:1'", "the same value with the same ramp"], {}),
    # A group's error starts with the option and the item that named it.
    "bc_unknown_group": (["-bc_traction", "lid:0:-1"],
                         ["-bc_traction lid:0:-1: physical group 'lid'", "not in the mesh",
                          "expected one of the mesh's groups:", "top_centre"], {}),
    "bc_traction_on_surface": (["-bc_traction", "body:0:-1"], ["-bc_traction body:0:-1: physical group 'body'",
                                                               "dimension 2", "expected a physical curve"], {}),
    "bc_traction_on_point": (["-bc_traction", "top_centre:0:-1"],
                             ["-bc_traction top_centre:0:-1: physical group 'top_centre'", "dimension 0",
                              "expected a physical curve"], {}),
    "bc_pressure_unknown_group": (["-bc_pressure", "lid:1"], ["-bc_pressure lid:1: physical group 'lid'",
                                                              "not in the mesh", "top_centre"], {}),
    "bc_point_force_unknown_group": (["-bc_point_force", "nope:0:1"],
                                     ["-bc_point_force nope:0:1: physical group 'nope'", "not in the mesh",
                                      "expected one of the mesh's groups:"], {}),
    "bc_dirichlet_unknown_group": (["-bc_dirichlet", "top_centre:x,nope:x"],
                                   ["-bc_dirichlet nope:x: physical group 'nope'", "not in the mesh",
                                    "expected one of the mesh's groups:"], {}),
    # Two different values on one node component: the message names the node, the component, both values and items.
    "bc_dirichlet_two_values": (["-bc_dirichlet", "top_centre:x=0.01,contact_point:x,top_centre:x=0.02"],
                                ["-bc_dirichlet prescribes two values to component x of node 1 (in file order)",
                                 "0.01 by item 'top_centre:x=0.01'", "0.02 by item 'top_centre:x=0.02'",
                                 "expected one value per node component"], {}),
    "bc_dirichlet_corner_two_values": (["-options_file", "{root}/options/block_on_floor.yml", "-bc_dirichlet",
                                        "left:x,bottom:x=0.001"],
                                       ["component x of node 1 (in file order)", "0 by item 'left:x'",
                                        "0.001 by item 'bottom:x=0.001'"], {}),
    # Two squares sharing an edge, a cell group each: on 2 ranks the shared nodes 2 and 5 are on the partition's
    # interface, and each rank holds one of the two items' cells.
    "bc_dirichlet_two_values_on_interface": (mesh("two_squares.msh") + ["-bc_dirichlet", "a:xy=0,b:x=0.001"],
                                             ["component x of node 2 (in file order)", "0 by item 'a:xy=0'",
                                              "0.001 by item 'b:x=0.001'"], {}),
    "contact_unknown_group": (["-contact_groups", "bottom"], ["-contact_groups bottom: physical group 'bottom'",
                                                              "not in the mesh"], {}),
    "contact_option_without_obstacle": (["-options_file", "{root}/options/lame_cylinder.yml", "-contact_gap_tol",
                                         "1e-3"], ["-contact_gap_tol is given", "no obstacle"], {}),
    # Friction (-contact_friction).
    "friction_negative": (SLIDING + ["-contact_friction", "-0.1"], ["-contact_friction -0.1", "[0, 1000]"], {}),
    "friction_not_a_number": (SLIDING + ["-contact_friction", "high"], ["-contact_friction high", "real number"], {}),
    "friction_pair_coefficient": (PATCH + ["-contact_pairs", "upper_bottom:lower_top:rough"],
                                  ["-contact_pairs: item 'upper_bottom:lower_top:rough'", "'rough'",
                                   "SLAVE:MASTER:MU"], {}),
    "friction_pair_unknown": (PATCH + ["-contact_pairs", "upper_bottom:floor:0.3"],
                              ["-contact_pairs upper_bottom:floor", "'floor'"], {}),
    "friction_pair_negative": (PATCH + ["-contact_pairs", "upper_bottom:lower_top:-0.2"],
                               ["-contact_pairs: item 'upper_bottom:lower_top:-0.2'", "'-0.2'", ">= 0"], {}),
    "friction_with_cholesky": (SLIDING + ["-options_file", "{root}/options/solver/mumps_cholesky.yml"],
                               ["nonsymmetric", "cholesky", "options/solver/mumps_lu.yml"], {}),
    "friction_with_cg": (SLIDING + ["-options_file", "{root}/options/solver/fieldsplit_gamg.yml", "-contact_ksp_type",
                                    "cg"],
                         ["nonsymmetric", "-contact_ksp_type cg", "options/solver/mumps_lu.yml",
                          "options/solver/fieldsplit_gamg.yml"], {}),
    "obstacle_friction_unknown_kind": (SLIDING + ["-obstacle_friction", "walls:0.3"],
                                       ["-obstacle_friction: item 'walls:0.3'", "KIND:MU", "segments, arcs"], {}),
    "obstacle_friction_kind_not_in_run": (SLIDING + ["-obstacle_friction", "spheres:0.3"],
                                          ["-obstacle_friction: item 'spheres:0.3'", "none of",
                                           "run's kinds (segments)"], {}),
    "obstacle_friction_negative": (SLIDING + ["-obstacle_friction", "segments:-1"],
                                   ["-obstacle_friction: item 'segments:-1'", "[0, 1000]"], {}),
    "obstacle_friction_twice": (SLIDING + ["-obstacle_friction", "segments:0.1,segments:0.2"],
                                ["-obstacle_friction: kind segments is given twice"], {}),
    # MUMPS out of working memory (ICNTL(23) below its need): one message, whether PETSc's interface factors (the
    # plain form) or the kept factorisation calls MUMPS itself.
    "mumps_working_memory_refactored": (CUBE + ["-contact_reuse_factorization", "0",
                                                "-contact_mat_mumps_icntl_23", "1"],
                                        ["MUMPS needs more working memory", "INFOG(1) = -19",
                                         "-contact_solver iterative"], {}),
    "mumps_working_memory_kept": (CUBE + ["-contact_kept_solver", "mumps", "-contact_mat_mumps_icntl_23", "1"],
                                  ["MUMPS needs more working memory", "INFOG(1) = -19", "-contact_solver iterative"],
                                  {}),
    "multiplier_split_without_friction": (CUBE + ["-contact_solver", "iterative", "-contact_fieldsplit_lambda_pc_type",
                                                  "fieldsplit"],
                                          ["-contact_fieldsplit_lambda_pc_type fieldsplit", "without friction"], {}),
    # The kept factorisation with friction needs a constant stiffness: svk refactors at every change.
    "friction_kept_with_svk": (SLIDING + ["-material_model", "svk", "-contact_reuse_factorization", "true"],
                               ["-contact_reuse_factorization with", "-material_model svk",
                                "expected -contact_reuse_factorization 0"], {}),
    # Pairs of bodies (-contact_pairs).
    "contact_pairs_malformed": (PATCH + ["-contact_pairs", "upper_bottom"],
                                ["-contact_pairs: item 'upper_bottom'", "SLAVE:MASTER"], {}),
    "contact_pairs_same_group": (PATCH + ["-contact_pairs", "lower_top:lower_top"],
                                 ["-contact_pairs lower_top:lower_top", "same group on both sides",
                                  "two different bodies"], {}),
    "contact_pairs_unknown_group": (PATCH + ["-contact_pairs", "upper_bottom:floor"],
                                    ["-contact_pairs upper_bottom:floor", "'floor'"], {}),
    "contact_pairs_surface_group": (PATCH + ["-contact_pairs", "upper:lower_top"],
                                    ["-contact_pairs upper:lower_top", "'upper'"], {}),
    "contact_pairs_same_body": (PATCH + ["-contact_pairs", "upper_bottom:upper_top"],
                                ["-contact_pairs upper_bottom:upper_top", "'upper_bottom' and 'upper_top'",
                                 "both on body 1", "two different bodies"], {}),
    # Two squares sharing an edge (one body), the shared edge a group: inside the body.
    "contact_pairs_interior_group": (mesh("interior_curve.msh") + ["-contact_pairs", "middle:top"],
                                     ["-contact_pairs middle:top", "'middle'", "inside a body",
                                      "on the boundary of a body"], {}),
    "contact_pairs_overlapping_bodies": (PATCH + ["-mesh_file", "{meshes}/patch2d_overlap.msh"],
                                         ["-contact_pairs upper_bottom:lower_top", "start inside each other",
                                          "slave node", "0.1 deep", "at most 0.001 body diagonals"], {}),
    "contact_pairs_out_of_reach": (PATCH + ["-mesh_file", "{meshes}/patch2d_apart.msh"],
                                   ["-contact_pairs upper_bottom:lower_top", "within the search radius",
                                    "-contact_search_radius"], {}),
    "contact_groups_with_pairs_only": (PATCH + ["-contact_groups", "upper_bottom"],
                                       ["-contact_groups is given", "no obstacle", "-contact_pairs"], {}),
    "contact_group_interior": (["-contact_groups", "body"], ["-contact_groups body", "node(s) inside the body",
                                                             "on the boundary"], {}),
    "contact_groups_empty": (["-contact_groups", ""], ["-contact_groups", "without a value", "no candidate nodes"], {}),
    "contact_groups_empty_item": (["-contact_groups", ","], ["-contact_groups , has an empty item 1"], {}),
    # Solver options.
    "contact_max_it_zero": (["-contact_max_it", "0"], ["-contact_max_it 0", "expected an integer in [1, 10000]"], {}),
    "contact_max_it_huge": (["-contact_max_it", "10001"], ["-contact_max_it 10001", "[1, 10000]"], {}),
    "contact_gap_tol_huge": (["-contact_gap_tol", "1e300"],
                             ["-contact_gap_tol 1e300", "[0, 0.001] x body diagonal", "body diagonal 17.8885"], {}),
    "contact_gap_tol_empty": (["-contact_gap_tol", ""], ["-contact_gap_tol", "without a value", "x body diagonal"],
                              {}),
    "contact_touch_tol_huge": (["-contact_touch_tol", "0.1"], ["-contact_touch_tol 0.1", "x body diagonal"], {}),
    "contact_alpha_tol_huge": (["-contact_alpha_tol", "0.5"], ["-contact_alpha_tol 0.5", "[0, 0.01]"], {}),
    "contact_search_radius_zero": (["-contact_search_radius", "0"],
                                   ["-contact_search_radius 0", "(0, 100000] x body diagonal"], {}),
    "contact_search_radius_huge": (["-contact_search_radius", "1e300"],
                                   ["-contact_search_radius 1e300", "(0, 100000] x body diagonal"], {}),
    "contact_activation_fraction_one": (["-contact_activation_fraction", "1"],
                                        ["-contact_activation_fraction 1", "[0, 1)"], {}),
    "contact_activation_gap_factor_below_one": (["-contact_activation_gap_factor", "0.5"],
                                                ["-contact_activation_gap_factor 0.5", "0 (off)", "[1, 1e+06]"], {}),
    "contact_activation_gap_factor_negative": (["-contact_activation_gap_factor", "-1"],
                                               ["-contact_activation_gap_factor -1", "[0, 1e+06]"], {}),
    "contact_complementarity_c_tiny": (["-contact_complementarity_c", "1e-10"],
                                       ["-contact_complementarity_c 1e-10", "x E x thickness", "E x thickness 200"],
                                       {}),
    "contact_monitor_not_a_bool": (["-contact_monitor", "maybe"], ["-contact_monitor maybe", "expected true or false"],
                                   {}),
    "contact_ksp_type_unknown": (["-contact_ksp_type", "bogus"],
                                 ["-contact_ksp_type bogus is not a KSP type", "expected a KSP type, one of", "gmres"],
                                 {}),
    # The solver's PETSc options, checked before any solve (PETSc took some without a word, or refused them only at
    # the solve without naming them).
    "contact_ksp_type_empty": (["-contact_ksp_type"], ["-contact_ksp_type is given without a value",
                                                       "expected a KSP type, one of", "gmres"], {}),
    "contact_pc_type_empty": (["-contact_pc_type"], ["-contact_pc_type is given without a value",
                                                     "expected a PC type, one of", "cholesky"], {}),
    "contact_sub_pc_type_empty": (["-options_file", "{root}/options/solver/fieldsplit_gamg.yml",
                                   "-contact_fieldsplit_u_pc_type"],
                                  ["-contact_fieldsplit_u_pc_type is given without a value", "expected a PC type"], {}),
    "contact_ksp_rtol_negative": (["-contact_ksp_rtol", "-1"], ["-contact_ksp_rtol -1 is out of range",
                                                                "expected a number in [0, 1)"], {}),
    "contact_ksp_rtol_one_iterative": (["-options_file", "{root}/options/solver/fieldsplit_gamg.yml",
                                        "-contact_ksp_rtol", "1"], ["-contact_ksp_rtol 1 is out of range", "[0, 1)"],
                                       {}),
    "contact_ksp_atol_negative": (["-options_file", "{root}/options/solver/fieldsplit_gamg.yml", "-contact_ksp_atol",
                                   "-1"], ["-contact_ksp_atol -1 is out of range", "expected a number in [0, inf]"],
                                  {}),
    "contact_ksp_max_it_zero": (["-options_file", "{root}/options/solver/fieldsplit_gamg.yml", "-contact_ksp_max_it",
                                 "0"], ["-contact_ksp_max_it 0 is out of range", "expected an integer >= 1"], {}),
    # A solver option that nothing reads (an ICNTL beyond MUMPS's): refused after the solve, before any output.
    "unused_solver_option_new_dir": (["-contact_mat_mumps_icntl_99", "1", "-output_dir", "{work}/new/out"],
                                     ["option -contact_mat_mumps_icntl_99 1 (on the command line) is set but never read"], {}),
    # Options that the chosen solver never reads: refused when it is set up, before any solve (they used to be
    # refused only after the whole solve and its printed summary).
    "contact_ksp_rtol_direct": (["-contact_ksp_rtol", "1e-3", "-output_dir", "{work}/out"],
                                ["-contact_ksp_rtol 1e-3 does not apply to the kept MUMPS factorisation",
                                 "makes no Krylov iterations", "-contact_ksp_type other than preonly"], {}),
    "contact_ksp_max_it_direct": (["-contact_ksp_max_it", "5"],
                                  ["-contact_ksp_max_it 5 does not apply to the kept MUMPS factorisation",
                                   "-contact_ksp_type other than preonly"], {}),
    "contact_ksp_rtol_refactorising": (BEAM + ["-contact_reuse_factorization", "false", "-contact_ksp_rtol", "1e-8"],
                                       ["-contact_ksp_rtol 1e-8 does not apply to a direct solve "
                                        "(-contact_ksp_type preonly, -contact_pc_type cholesky)"], {}),
    "contact_fieldsplit_option_direct": (BEAM + ["-options_file", "{root}/options/solver/mumps_lu.yml",
                                                 "-contact_fieldsplit_u_pc_type", "gamg"],
                                         ["-contact_fieldsplit_u_pc_type gamg does not apply", "-contact_pc_type lu"],
                                         {}),
    "load_steps_zero": (["-load_steps", "0"], ["-load_steps 0", "expected an integer in [1, 10000]"], {}),
    "load_steps_overflow": (["-load_steps", "99999999999999999999"],
                            ["-load_steps 99999999999999999999", "expected an integer in [1, 10000]"], {}),
    "load_steps_huge": (["-load_steps", "1000000000"], ["-load_steps 1000000000", "[1, 10000]"], {}),
    "load_max_cuts_huge": (["-load_max_cuts", "31"], ["-load_max_cuts 31", "[0, 30]"], {}),
    "newton_max_it_huge": (["-newton_max_it", "1001"], ["-newton_max_it 1001", "[1, 1000]"], {}),
    "newton_rtol_huge": (["-newton_rtol", "0.1"], ["-newton_rtol 0.1", "(0, 0.0001]"], {}),
    "newton_atol_huge": (["-newton_atol", "1"], ["-newton_atol 1", "[0, 1e-06]"], {}),
    "output_dir_empty": (["-output_dir", ""], ["-output_dir", "without a value", "a directory path"], {}),
    "mesh_file_empty": (["-mesh_file", ""], ["-mesh_file", "without a value", ".msh, .geo or .h5"], {}),
    "report_hertz_empty": (["-report_hertz", ""], ["-report_hertz", "without a value", "R,P"], {}),
    "report_hertz_other_load": (["-report_hertz", "8,1e6"], ["-report_hertz 8", "is 10", "not P, P/2 or P/4"], {}),
    "report_hertz_not_hertz": (["-options_file", "{root}/options/block_on_floor.yml", "-report_hertz", "8,10"],
                               ["-report_hertz 8", "is 4", "not P, P/2 or P/4", "Hertz case"], {}),
    "report_hertz_tiny_radius": (["-report_hertz", "1e-9,10"], ["-report_hertz 1e-09", "not small against R"], {}),
    "solver_path_unknown": (["-contact_solver", "fast"], ["-contact_solver", "fast", "auto direct iterative"], {}),
    "memory_budget_not_size": (["-contact_memory_budget", "lots"],
                               ["-contact_memory_budget lots", "expected a memory size"], {}),
    "active_set_rtol_out_of_range": (["-contact_active_set_rtol", "0.5"],
                                     ["-contact_active_set_rtol 0.5", "out of range", "[0, 0.1]"], {}),
    "augmentation_weight_out_of_range": (["-contact_augmentation_weight", "200"],
                                         ["-contact_augmentation_weight 200", "expected a number in [0, 100]"], {}),
    "augmentation_weight_negative": (["-contact_augmentation_weight", "-0.5"],
                                     ["-contact_augmentation_weight -0.5", "expected a number in [0, 100]"], {}),
    "memory_budget_negative": (["-contact_memory_budget", "-1G"],
                               ["-contact_memory_budget -1G", "expected a memory size"], {}),
    "reuse_max_it_linear": (["-contact_reuse_max_it", "3"],
                            ["-contact_reuse_max_it 3", "nonlinear material", "-material_model svk"], {}),
    "reuse_max_it_refactorising": (["-material_model", "svk", "-contact_reuse_factorization", "false",
                                    "-contact_reuse_max_it", "3"],
                                   ["-contact_reuse_max_it 3", "kept factorisation"], {}),
    "reuse_max_it_huge": (["-material_model", "svk", "-contact_reuse_max_it", "1001"],
                          ["-contact_reuse_max_it 1001", "[0, 1000]"], {}),
    "lagged_search_linear": (["-newton_lagged_search", "true"],
                             ["-newton_lagged_search", "-material_model svk", "kept factorisation"], {}),
    "lagged_search_refactorising": (["-material_model", "svk", "-contact_reuse_factorization", "false",
                                     "-newton_lagged_search"],
                                    ["-newton_lagged_search", "kept factorisation"], {}),
    # Options that do not apply to the run are errors that say what they apply to (never for their defaults).
    "newton_linesearch_linear": (BEAM + ["-newton_linesearch"],
                                 ["-newton_linesearch true applies to -material_model svk only"], {}),
    "newton_lagged_search_false_linear": (BEAM + ["-newton_lagged_search", "false"],
                                          ["-newton_lagged_search false", "applies to -material_model svk only"], {}),
    "mortar_tangent_linear": (["-options_file", "{root}/options/cylinders_2d.yml", "-newton_mortar_tangent", "frozen"],
                              ["-newton_mortar_tangent frozen applies to -material_model svk only"], {}),
    "mortar_tangent_no_pairs": (BEAM + ["-material_model", "svk", "-newton_mortar_tangent", "consistent"],
                                ["-newton_mortar_tangent consistent", "pairs of bodies", "-contact_pairs"], {}),
    "mortar_tangent_friction": (["-options_file", "{root}/options/slide2d.yml", "-contact_friction", "0.2",
                                 "-newton_mortar_tangent", "consistent"],
                                ["-newton_mortar_tangent consistent", "friction", "expected -newton_mortar_tangent "
                                 "frozen"], {}),
    "mortar_tangent_unknown": (["-options_file", "{root}/options/slide2d.yml", "-newton_mortar_tangent", "exact"],
                               ["exact", "-newton_mortar_tangent", "consistent frozen"], {}),
    "mortar_tangent_symmetric_solver": (["-options_file", "{root}/options/slide2d.yml", "-options_file",
                                         "{root}/options/solver/mumps_cholesky.yml"],
                                        ["nonsymmetric", "-newton_mortar_tangent", "frozen"], {}),
    "newton_max_it_linear": (BEAM + ["-newton_max_it", "3"],
                             ["-newton_max_it 3 applies to -material_model svk only", "-contact_max_it"], {}),
    "load_max_cuts_linear": (BEAM + ["-load_max_cuts", "2"], ["-load_max_cuts 2 applies to -material_model svk only"],
                             {}),
    "mesh_size_factor_on_msh": (BEAM + ["-mesh_size_factor", "0.5"],
                                ["-mesh_size_factor 0.5 applies to meshing a .geo file only", "beam.msh",
                                 "expected a .geo -mesh_file"], {}),
    "mesh_max_cells_on_msh": (BEAM + ["-mesh_max_cells", "10"],
                              ["-mesh_max_cells 10 applies to meshing a .geo file only", "beam.msh"], {}),
    "nested_dissection_iterative": (BEAM + ["-contact_nested_dissection", "metis", "-options_file",
                                            "{root}/options/solver/fieldsplit_gamg.yml"],
                                    ["-contact_nested_dissection metis applies to the kept MUMPS factorisation only"],
                                    {}),
    "nested_dissection_parallel_refactorising": (BEAM + ["-contact_nested_dissection_parallel", "false",
                                                         "-contact_reuse_factorization", "false"],
                                                 ["-contact_nested_dissection_parallel false applies to the kept "
                                                  "MUMPS factorisation only"], {}),
    "nested_dissection_mumps_ordering": (BEAM + ["-contact_nested_dissection", "coordinates",
                                                 "-contact_mat_mumps_icntl_7", "4"],
                                         ["-contact_nested_dissection coordinates does not apply with "
                                          "-contact_mat_mumps_icntl_7 4", "expected -contact_mat_mumps_icntl_7 1"],
                                         {}),
    "nested_dissection_parallel_coordinates": (BEAM + ["-contact_nested_dissection", "coordinates",
                                                       "-contact_nested_dissection_parallel", "true"],
                                               ["-contact_nested_dissection_parallel applies to METIS's ordering "
                                                "only"], {}),
    # Who factors the kept factorisation (-contact_kept_solver): the supernodal Cholesky only where it applies.
    # The null-space preconditioner eliminates each node's active rows with the node's own dofs: not a mortar row.
    "nullspace_between_bodies": (["-options_file", "{root}/options/patch3d.yml", "-contact_solver", "iterative",
                                  "-contact_pc_type", "nullspace"],
                                 ["-contact_pc_type nullspace does not apply to this problem",
                                  "a contact row couples several nodes", "expected -contact_pc_type fieldsplit"], {}),
    "nullspace_friction": (SLIDING + ["-contact_solver", "iterative",
                            "-contact_pc_type", "nullspace"],
                           ["-contact_pc_type nullspace does not apply to this problem",
                            "friction makes the matrix nonsymmetric"], {}),
    "gamg_product_unknown": (["-contact_solver", "iterative", "-contact_gamg_product", "fast"],
                             ["Unknown option fast for -contact_gamg_product", "lean petsc"], {}),
    "kept_solver_unknown": (["-contact_kept_solver", "lapack"],
                            ["Unknown option lapack for -contact_kept_solver", "auto mumps cholesky"], {}),
    "kept_solver_refactorising": (BEAM + ["-contact_kept_solver", "cholesky", "-contact_reuse_factorization", "false"],
                                  ["-contact_kept_solver cholesky applies to the kept factorisation only"], {}),
    "kept_solver_cholesky_lu": (BEAM + ["-contact_kept_solver", "cholesky", "-options_file",
                                        "{root}/options/solver/mumps_lu.yml"],
                                ["-contact_kept_solver cholesky factors a symmetric matrix", "not LU"], {}),
    "kept_solver_cholesky_mumps_controls": (BEAM + ["-contact_kept_solver", "cholesky", "-contact_mat_mumps_cntl_3",
                                                    "1e-10"],
                                            ["-contact_kept_solver cholesky takes no MUMPS controls"], {}),
    "reuse_factorization_mumps_layout": (["-contact_mat_mumps_icntl_19", "1"],
                                         ["-contact_mat_mumps_icntl_19", "cannot be set"], {}),
    # An iterative solver's tolerance above what a solve must reach: refused before any solve (the solve used to fail
    # after it, blaming a singular block and advising to raise the tolerance).
    "contact_ksp_rtol_above_accepted": (["-options_file", "{root}/options/solver/fieldsplit_gamg.yml",
                                         "-contact_ksp_rtol", "0.5"],
                                        ["-contact_ksp_rtol 0.5", "at most 1e-06", "expected a value in [0, 1e-06]"],
                                        {}),
    # MUMPS's controls: MUMPS took a NaN threshold and an unknown ordering without a word.
    "mumps_cntl_nan": (["-contact_mat_mumps_cntl_3", "nan"],
                       ["-contact_mat_mumps_cntl_3 nan", "expected a finite real number"], {}),
    "mumps_cntl_nan_refactorising": (["-contact_reuse_factorization", "false", "-contact_mat_mumps_cntl_1", "nan"],
                                     ["-contact_mat_mumps_cntl_1 nan", "expected a finite real number"], {}),
    "mumps_cntl_1_negative": (["-contact_mat_mumps_cntl_1", "-5"],
                              ["-contact_mat_mumps_cntl_1 -5 is out of range", "expected a number in [0, 1]"], {}),
    "mumps_cntl_7_negative": (["-contact_mat_mumps_cntl_7", "-1"],
                              ["-contact_mat_mumps_cntl_7 -1 is out of range", "expected a number in [0, inf]"], {}),
    "mumps_cntl_not_passed_on": (["-contact_mat_mumps_cntl_15", "3"],
                                 ["-contact_mat_mumps_cntl_15", "CNTL(15) is not among the MUMPS controls",
                                  "expected one of CNTL 1, 2, 3, 4, 5, 7"], {}),
    "mumps_icntl_14_negative": (["-contact_mat_mumps_icntl_14", "-5"],
                                ["-contact_mat_mumps_icntl_14 -5 is out of range for MUMPS's ICNTL(14)",
                                 "expected an integer >= 0"], {}),
    "mumps_icntl_8_undefined": (["-contact_mat_mumps_icntl_8", "5"],
                                ["-contact_mat_mumps_icntl_8 5 is out of range for MUMPS's ICNTL(8)",
                                 "expected one of -2, 0, 1, 3, 4, 7, 8, 77"], {}),
    "mumps_icntl_empty": (["-contact_mat_mumps_icntl_14"],
                          ["-contact_mat_mumps_icntl_14 is given without a value", "expected an integer >= 0"], {}),
    # PETSc's MUMPS interface reads no ICNTL(5): it ran with the value ignored.
    "mumps_icntl_not_passed_on": (["-contact_reuse_factorization", "false", "-contact_mat_mumps_icntl_5", "1"],
                                  ["-contact_mat_mumps_icntl_5", "ICNTL(5) is not among the MUMPS controls",
                                   "PETSc's MUMPS interface would ignore it", "expected one of ICNTL 1, 2"], {}),
    "nested_dissection_empty": (["-contact_nested_dissection"], ["-contact_nested_dissection is given without a value",
                                                                 "expected auto, metis or coordinates"], {}),
    "mumps_icntl_7_out_of_range": (["-contact_mat_mumps_icntl_7", "99"],
                                   ["-contact_mat_mumps_icntl_7 99", "expected a MUMPS ordering", "7 (automatic)"], {}),
    "mumps_icntl_7_not_built": (["-contact_mat_mumps_icntl_7", "5"],
                                ["-contact_mat_mumps_icntl_7 5", "built without METIS", "expected 0 (AMD)"], {}),
    "mumps_icntl_7_given_refactorising": (["-contact_reuse_factorization", "false", "-contact_mat_mumps_icntl_7", "1"],
                                          ["-contact_mat_mumps_icntl_7 1", "kept factorisation only",
                                           "expected 0, 2, 4, 6 or 7"], {}),
    # The kept factorisation declines its dense Schur complement (1050 candidates on a small cube, on 1 and on 2 ranks;
    # 630 were declined on 1 rank only): PETSc's MUMPS then refactorises and takes no given pivot order.
    "mumps_icntl_7_given_schur_declined": (["-mesh_file", "{root}/meshes/cube.msh", "-material_E", "1000",
                                            "-bc_dirichlet", "left:x,front:y", "-bc_pressure", "top:2",
                                            "-contact_groups", "bottom,top,left,front", "-contact_search_radius", "10",
                                            "-obstacle_planes", "0,0,0,0,0,1,0,0,-1,0,0,1,0,0,-2,0,0,1,0,0,-3,0,0,1,"
                                            "0,0,-4,0,0,1,0,0,-5,0,0,1,0,0,-6,0,0,1,0,0,-7,0,0,1,0,0,-8,0,0,1,"
                                            "0,0,-9,0,0,1",
                                            "-contact_mat_mumps_icntl_7", "1"],
                                           ["-contact_mat_mumps_icntl_7 1", "declined its dense Schur complement",
                                            "expected -contact_mat_mumps_icntl_7 0, 2, 4, 6 or 7"], {}),
    # A null-pivot threshold that calls half the pivots null on a held body: the report names it as a possible cause.
    "mumps_cntl_3_pivots_null": (["-options_file", "{root}/options/block_in_notch.yml", "-contact_mat_mumps_cntl_3",
                                  "0.5"],
                                 ["DIVERGED_SINGULAR", "null pivot(s)", "the MUMPS controls -contact_mat_mumps_cntl_3 "
                                  "0.5 may count regular pivots as null", "or the body is not held"], {}),
    # A Schur fieldsplit on a body that nothing holds (no Dirichlet condition, no obstacle): the message says why its
    # block is singular (a rigid-body motion that the supports and the candidates leave free), found before any solve.
    "fieldsplit_on_loose_body": (LOOSE_BEAM + ["-options_file", "{root}/options/solver/fieldsplit_gamg.yml",
                                               "-contact_ksp_max_it", "200"],
                                 # Found before any Krylov solve (the rigid modes against the supports and every
                                 # candidate pair), as the direct path's null pivots find it.
                                 ["DIVERGED_SINGULAR", "leave a rigid-body motion free", "not held by the supports",
                                  "add Dirichlet conditions"], {}),
    "reuse_factorization_iterative": (["-options_file", "{root}/options/solver/fieldsplit_hypre.yml",
                                       "-contact_reuse_factorization", "true"],
                                      ["-contact_reuse_factorization", "MUMPS LU or Cholesky"], {}),
    "load_steps_not_an_integer": (["-load_steps", "1.5"], ["-load_steps 1.5", "expected an integer"], {}),
    # A -mesh_file alone keeps the rest of the default case, whose groups the mesh must have.
    "default_case_on_other_mesh": (["-mesh_file", "{root}/meshes/beam.msh"],
                                   ["-mesh_file", "beam.msh", "the default case (2D Hertz)",
                                    "has no physical group top_centre, contact_point", "expected a mesh of the Hertz"],
                                   {}),
    "default_case_on_3d_mesh": (["-mesh_file", "{root}/meshes/cube.msh"],
                                ["-mesh_file", "cube.msh", "the default case (2D Hertz)", "this mesh is 3D"], {}),
    # Options files.
    "options_file_missing": (["-options_file", "{here}/options/does_not_exist.yml"],
                             ["-options_file", "does_not_exist.yml", "expected"], {}),
    "options_file_bad_yaml": (["-options_file", "{here}/options/bad_options.yml"],
                              ["-options_file ", "bad_options.yml, line 3, column 3", "flow sequence",
                               "expected a valid YAML file"], {}),
    "options_file_yaml_bad_yaml": (["-options_file_yaml", "{here}/options/bad_options.yml"],
                                   ["-options_file_yaml ", "bad_options.yml, line 3, column 3",
                                    "expected a valid YAML file"], {}),
    "options_file_is_directory": (["-options_file", "{here}/options"],
                                  ["-options_file", "options: it is a directory", "expected a readable"], {}),
    # YAML files with what PETSc would take silently: an option set twice (it keeps the last value), a merge after
    # the key that overrides it (it keeps the merged value), an options_file key (it reads no file).
    "yaml_option_twice": (["-options_file", "{here}/options/twice.yml"],
                          ["twice.yml, line 3: option -material_E is set again (first on line 2)",
                           "expected each option once per file"], {}),
    "yaml_option_twice_nested": (["-options_file", "{here}/options/twice_nested.yml"],
                                 ["twice_nested.yml, line 4: option -contact_max_it is set again (first on line 3)"],
                                 {}),
    "yaml_merge_after_key": (["-options_file_yaml", "{here}/options/merge_after_key.yml"],
                             ["merge_after_key.yml, line 4: option -material_E is set again by a later merge",
                              "expected the merge before the keys"], {}),
    "yaml_names_options_file": (["-options_file", "{root}/options/beam_on_floor.yml", "-options_file",
                                 "{here}/options/names_options_file.yml"],
                                ["names_options_file.yml, line 2: options_file in a YAML file is not read",
                                 "expected each options file on the command line"], {}),
    "yaml_option_twice_documents": (["-options_file", "{here}/options/twice_documents.yml"],
                                    ["twice_documents.yml, line 4: option -material_E is set again (first on line 2)",
                                     "in all its documents"], {}),
    # Options that nothing reads (misspelt, or not for this run): refused after the set-up, before the output
    # directory is made, or, for the solver's options that the solve reads as it goes, after the solve and before the
    # output is published.
    "unused_option": (["-materal_E", "5"], ["option -materal_E 5 (on the command line) is set but never read", "expected"],
                      {}),
    "unused_options_two": (["-material_nuu", "0.3", "-contact_max_itt", "5"],
                           ["options -contact_max_itt 5 (on the command line), -material_nuu 0.3 (on the command line) are set but never read"],
                           {}),
    "unused_option_yaml_key": (["-options_file", "{here}/options/unknown_key.yml"],
                               ["option -materal_E 5 (set in options file '", "unknown_key.yml') is set but never read"],
                               {}),
    "unused_option_yaml_nested_key": (["-options_file", "{here}/options/unknown_nested_key.yml"],
                                      ["option -material_EE 5 (set in options file '",
                                       "unknown_nested_key.yml') is set but never read"], {}),
    "unused_solver_option": (["-contact_mat_mumps_icntl_99", "1"],
                             ["option -contact_mat_mumps_icntl_99 1 (on the command line) is set but never read"], {"previous": HERTZ}),
    # An option of a PC that the solver does not use: refused at the solver's set-up, before any solve.
    "unused_solver_option_of_other_solver": (["-contact_pc_gamg_threshold", "0.01"],
                                             ["-contact_pc_gamg_threshold 0.01 does not apply to the kept MUMPS "
                                              "factorisation", "another preconditioner"], {"previous": HERTZ}),
    # The same option twice on the command line: PETSc keeps the last value (the second traction dropped the first).
    "option_before_options_file": (["-bc_traction", "top:0:-1.25", "-options_file", "{root}/options/hertz.yml"],
                                   ["option -bc_traction top:0:-1.25 on the command line is replaced by top:0:-0.625",
                                    "expected the option after the -options_file"], {}),
    "option_twice_command_line": (["-material_E", "300", "-material_E", "400"],
                                  ["option -material_E is given twice on the command line (300, then 400)",
                                   "expected each option once"], {}),
    "bc_traction_twice_command_line": (["-bc_traction", "top:0:-0.625", "-bc_traction", "top:0:-1"],
                                       ["option -bc_traction is given twice", "(top:0:-0.625, then top:0:-1)"],
                                       {}),
    "option_twice_through_prefix": (["-contact_max_it", "5", "-prefix_push", "contact_", "-max_it", "6",
                                     "-prefix_pop"], ["option -contact_max_it is given twice", "(5, then 6)"],
                                    {}),
    # A plain options file naming one that does not exist: every rank would report it.
    "options_file_nested_missing": (["-options_file", "{here}/options/nested_missing.txt"],
                                    ["-options_file does_not_exist_nested.txt: no such file"], {}),
    # The command line as PETSc reads it: what is neither an option nor its value was skipped silently.
    "stray_case_file": (["{root}/options/beam_on_floor.yml"],
                        ["unexpected argument", "beam_on_floor.yml", "give -options_file"], {}),
    "stray_second_value": (["-load_steps", "2", "3"], ["unexpected argument '3'", "-name value"], {}),
    "misspelt_options_file": (["-option_file", "{root}/options/beam_on_floor.yml"],
                              ["unknown option -option_file", "expected -options_file FILE"], {}),
    "options_file_bad_syntax": (["-options_file", "{here}/options/bad_options.txt"],
                                ["-options_file", "bad_options.txt line 3", "expected"], {}),
    # Failures of the solve, after the output directory was opened: its incomplete/ goes too.
    "singular_system": (LOOSE_BEAM, ["singular", "not held", "add Dirichlet"], {"previous": BEAM}),
    # An input refused at the first factorisation.
    "mumps_control_set_by_solver": (["-contact_mat_mumps_icntl_26", "0"],
                                    ["-contact_mat_mumps_icntl_26 cannot be set", "-contact_reuse_factorization"],
                                    {"previous": HERTZ}),
    "mumps_control_set_by_solver_new_dir": (["-contact_mat_mumps_icntl_26", "0", "-output_dir",
                                             "{work}/new/deeper/out"], ["-contact_mat_mumps_icntl_26 cannot be set"],
                                            {}),
    # Supports that hold contact candidates inside the obstacle: no solve can lift them, and with no pair for a node
    # whose normal motion is prescribed the penetration went unchecked (a converged state 0.01 inside the floor).
    "dirichlet_into_obstacle": (["-options_file", "{root}/options/block_on_floor.yml", "-bc_dirichlet",
                                 "left:x,bottom:y=-0.01"],
                                ["candidate node 1", "held by -bc_dirichlet inside the obstacle, by 0.01",
                                 "expected prescribed displacements"], {}),
    "dirichlet_node_into_obstacle": (["-bc_dirichlet", "top_centre:x,contact_point:x:y=-0.05"],
                                     ["candidate node 4", "inside the obstacle, by 0.05"], {}),
    # The same node held at zero under a flat raised into the body: every other candidate is paired (the large search
    # radius) and none has moved, and the check used to look at no facet at all.
    "dirichlet_node_fixed_in_obstacle": (["-bc_dirichlet", "top_centre:x,contact_point:x:y", "-obstacle_segments",
                                          "-12,-7.95,12,-7.95", "-contact_search_radius", "10"],
                                         ["candidate node 4", "inside the obstacle, by 0.05"], {}),
    # svk's iteration limits are both honoured: each iteration is a Newton step (-newton_max_it), and at most
    # -contact_max_it of them change the active set (the loop used to run to the larger of the two).
    "svk_newton_max_it": (["-options_file", "{root}/options/cantilever_large.yml", "-newton_max_it", "1",
                           "-load_max_cuts", "0"], ["DIVERGED_MAX_IT", "-newton_max_it Newton iterations"], {}),
    "svk_contact_max_it": (["-options_file", "{root}/options/beam_on_floor.yml", "-material_model", "svk",
                            "-contact_max_it", "1", "-load_max_cuts", "0"],
                           ["DIVERGED_MAX_IT", "at most -contact_max_it change the active set"], {}),
    # svk out of iterations on a body that only contact holds (seed 31337 case 138: a block on a disc that must roll
    # 0.5 to reach an inclined wall; the linear material converges): the error says where to look.
    "svk_max_it_held_by_contact_alone": (["-mesh_file", "{root}/meshes/block.msh", "-material_E", "5803.01",
                                          "-material_nu", "0.324", "-contact_groups", "bottom,left,right",
                                          "-material_model", "svk", "-bc_traction", "top:0.655577:-49.716",
                                          "-obstacle_segments", "0,2,0,-0.5,2.29919,-0.00973227,3.29919,1.35071",
                                          "-obstacle_discs", "1.00769,-1.00973,1"],
                                         ["DIVERGED_MAX_IT", "no more load-step cuts", "only contact holds the body",
                                          "-material_model linear says whether contact holds it"], {}),
    # Held by contact alone, but pulled up out of the notch: no active set can hold it. The complementarity problem
    # of the linear material says so (ContactSolver::PivotedActiveSet): the whole load is unbalanced.
    "pulled_out_of_notch": (["-options_file", "{root}/options/block_in_notch.yml", "-bc_traction", "top:0:1"],
                            ["DIVERGED_NOT_HELD", "not held", "no contact forces on its", "balance the load",
                             "leaves 1 of it"], {}),
    # Nodes farther than the search radius from the wall at the start get no pair, and the cylinder sinks through it:
    # the certificate must refuse that state (it used to be reported converged with a contact half as wide).
    "rectangle_zero_size": (CUBE + ["-obstacle_rectangles", "0.5,0.5,0,0,0,1,1,0,0,0,1"],
                            ["-obstacle_rectangles item 1", "half-size", "expected A > 0 and B > 0"], {}),
    "rectangle_direction_along_normal": (CUBE + ["-obstacle_rectangles", "0.5,0.5,0,0,0,1,0,0,2,1,1"],
                                         ["-obstacle_rectangles item 1", "along the normal", "in the plane"], {}),
    "rectangle_on_2d_mesh": (["-obstacle_rectangles", "0,0,0,0,0,1,1,0,0,1,1"], ["-obstacle_rectangles", "3D"], {}),
    "active_set_max_it": (["-contact_max_it", "1"], ["did not converge", "-contact_max_it"], {"previous": HERTZ}),
    # A failure after the output directory was made: the directories the run made go again, parents included.
    "output_dirs_made_removed": (["-contact_max_it", "1", "-output_dir", "{work}/new/deeper/out"],
                                 ["did not converge", "-contact_max_it"], {}),
    # A pressure no single svk load step carries (at 50 the multiplier-space search converges in one step).
    "newton_diverges": (BEAM + ["-material_model", "svk", "-newton_max_it", "1", "-load_max_cuts", "0",
                                "-bc_pressure", "top:200"], ["did not converge", "-load_max_cuts"], {"previous": BEAM}),
    # Output directories.
    "output_dir_under_file": (["-output_dir", "{file}/out"], ["-output_dir", "a_file/out", "expected a writable"],
                              {}),
    "output_dir_is_file": (["-output_dir", "{file}"], ["-output_dir", "a_file", "expected a writable"], {}),
    # Reported before the mesh is read (a large mesh takes a while), so ahead of the missing mesh here.
    "output_dir_before_mesh": (["-output_dir", "{file}/out", "-mesh_file", "{here}/meshes/does_not_exist.msh"],
                               ["-output_dir", "a_file/out", "(its parent", "is not a directory"], {}),
    # An output file that cannot be created (strace fails its open with EACCES, on every rank): written by every rank
    # together (MPI-IO), it must still end in one error naming it.
    "output_h5_unwritable": (BEAM, ["cannot write HDF5 file", "incomplete/solution.h5", "MPI_File_open failed",
                                      "expected a writable output directory"], {"deny_open": "solution.h5"}),
    "output_csv_unwritable": (BEAM, ["cannot write", "incomplete/nodes.csv"], {"deny_open": "nodes.csv"}),
    # Interruptions: 20 load steps of the Hertz case keep it busy for seconds after its third step begins.
    "sigterm": (["-load_steps", "20", "-contact_monitor"], [], {"signal": signal.SIGTERM}),
    "sigint": (["-load_steps", "20", "-contact_monitor"], [], {"signal": signal.SIGINT}),
}


class CheckFailed(Exception):
    """The run did not fail the way the case expects; the message says how."""


class Skipped(Exception):
    """The case cannot run here (strace is missing or may not trace); the message says why. Exit status 77."""


def deny_open(out_dir, name):
    """The prefix that runs the executable under strace with every open of DIR/incomplete/NAME failing (EACCES)."""
    strace = shutil.which("strace")
    if not strace or subprocess.run([strace, "-qq", "-o", os.devnull, "true"]).returncode != 0:
        raise Skipped("strace is missing or may not trace here")
    return [strace, "-f", "-qq", "-o", os.devnull, "-P", os.path.join(out_dir, "incomplete", name), "-e",
            "trace=open,openat", "-e", "inject=open,openat:error=EACCES"]


def expand(args, paths):
    return [a.format(**paths) for a in args]


def snapshot(directory):
    """Every file under directory except the staging directory: path -> (size, mtime, sha256)."""
    files = {}
    for base, dirs, names in os.walk(directory):
        dirs[:] = [d for d in dirs if not (base == directory and d == "incomplete")]
        for name in names:
            path = os.path.join(base, name)
            with open(path, "rb") as f:
                digest = hashlib.sha256(f.read()).hexdigest()
            st = os.stat(path)
            files[os.path.relpath(path, directory)] = (st.st_size, st.st_mtime_ns, digest)
    return files


def summaries(directory):
    found = []
    for base, _, names in os.walk(directory):
        found += [os.path.join(base, n) for n in names if n == "summary.json"]
    return found


def environment():
    env = dict(os.environ)
    # After a rank exits non-zero, mpiexec waits odls_base_sigkill_timeout (1 s) twice before it returns, even when
    # every rank is gone already; the messages are written by then, so do not wait.
    env.setdefault("OMPI_MCA_odls_base_sigkill_timeout", "0")
    return env


def reap(proc):
    """Waits until no process of the run's group is left after mpiexec returned. One that never goes is left to
    CTest's TIMEOUT; the line printed after a while says what the test is waiting for."""
    waited = 0
    while True:
        try:
            os.killpg(proc.pid, 0)
        except ProcessLookupError:
            return
        waited += 1
        if waited == 40:
            print(f"waiting for processes of the run's group (pgid {proc.pid}) left after mpiexec returned",
                  flush=True)
        time.sleep(0.05)


def run_failing(cmd, env):
    """Runs cmd in its own process group; returns (exit status, stdout, stderr, seconds)."""
    start = time.monotonic()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env, cwd=ROOT,
                            start_new_session=True)
    out, err = proc.communicate()
    seconds = time.monotonic() - start
    reap(proc)
    return proc.returncode, out, err, seconds


def run_interrupted(cmd, env, sig):
    """Starts cmd, waits for load step 3 to begin, sends sig; returns (status, stdout, stderr, seconds)."""
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env, cwd=ROOT,
                            start_new_session=True)
    lines = []
    try:
        while True:
            line = proc.stdout.readline()
            if not line:
                raise CheckFailed("the run ended before load step 3:\n" + "".join(lines) + proc.stderr.read())
            lines.append(line)
            if "step 3 (" in line:
                break
        # SIGTERM as `kill PID` sends it, to mpiexec alone; SIGINT as Ctrl-C sends it, to the whole process group.
        start = time.monotonic()
        if sig == signal.SIGINT:
            os.killpg(proc.pid, sig)
        else:
            proc.send_signal(sig)
        out, err = proc.communicate()
        seconds = time.monotonic() - start
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.communicate()
    reap(proc)
    return proc.returncode, "".join(lines) + out, err, seconds


def check_case(name, exe, mpiexec, np_, work, env, verbose):
    args, expected, opts = CASES[name]
    out_dir = os.path.join(work, "out")
    a_file = os.path.join(work, "a_file")
    with open(a_file, "w") as f:
        f.write("a regular file, not a directory\n")
    paths = {"root": ROOT, "here": HERE, "meshes": os.path.join(HERE, "meshes"), "out": out_dir, "file": a_file,
             "work": work}
    launch = [mpiexec, "-n", str(np_)] + (deny_open(out_dir, opts["deny_open"]) if "deny_open" in opts else []) + [exe]

    before = None
    if "previous" in opts:
        status, out, err, _ = run_failing(launch + expand(opts["previous"], paths) + ["-output_dir", out_dir], env)
        if status != 0 or not os.path.exists(os.path.join(out_dir, "summary.json")):
            raise CheckFailed(f"the good run before the bad one failed (status {status}):\n{err}")
        before = snapshot(out_dir)

    cmd = launch + expand(args, paths)
    if "-output_dir" not in args:
        cmd += ["-output_dir", out_dir]
    if "signal" in opts:
        status, out, err, seconds = run_interrupted(cmd, env, opts["signal"])
    else:
        # The error paths free what they made: -malloc_dump (through PETSC_OPTIONS, which no case sets, so that the
        # command line each case tests stays as it is) lists at PetscFinalize whatever they did not.
        leak_env = dict(env, PETSC_OPTIONS=(env.get("PETSC_OPTIONS", "") + " -malloc_dump").strip())
        status, out, err, seconds = run_failing(cmd, leak_env)
    if verbose:
        print(f"$ {' '.join(cmd)}\n--- status {status} after {seconds:.2f} s\n--- stdout\n{out}--- stderr\n{err}")

    problems = []
    if status == 0:
        problems.append("exit status 0; expected a failure")
    for text, stream in ((out, "stdout"), (err, "stderr")):
        for bad in FORBIDDEN:
            if bad in text:
                problems.append(f"{stream} holds '{bad}'")
    if LEAKED_MEMORY.search(out) or LEAKED_MEMORY.search(err):
        problems.append("PETSc memory leaked on the error path (-malloc_dump)")
    error_lines = [line for line in err.splitlines() if line.startswith(ERROR_PREFIX)]
    if "signal" not in opts:
        if any(line.startswith(ERROR_PREFIX) for line in out.splitlines()):
            problems.append("the error message went to stdout")
        if len(error_lines) != 1:
            problems.append(f"{len(error_lines)} lines start with '{ERROR_PREFIX}' on stderr; expected exactly 1")
        for line in error_lines[:1]:
            for want in expected:
                if want not in line:
                    problems.append(f"the error line lacks '{want}'")
    # A failed run removes the directories it made (an -output_dir that did not exist, and its parents), and makes
    # none when it fails in its set-up. An interrupted run leaves its output directory.
    kept = {"a_file"} | ({"out"} if before is not None or "signal" in opts else set())
    for name in sorted(set(os.listdir(work)) - kept):
        problems.append(f"{name} is left in the work directory by the failed run")
    if "signal" in opts and not os.path.isdir(os.path.join(out_dir, "incomplete")):
        problems.append("no incomplete/ in the output directory: the run was not interrupted while writing")
    if "signal" not in opts and os.path.exists(os.path.join(out_dir, "incomplete")):
        problems.append("the failed run left its incomplete/ behind (half-written output)")
    if before is None:
        for path in summaries(out_dir):
            problems.append(f"{os.path.relpath(path, work)} exists after the failed run")
    else:
        after = snapshot(out_dir)
        if after != before:
            changed = sorted(k for k in set(before) | set(after) if before.get(k) != after.get(k))
            problems.append(f"the earlier good output changed: {', '.join(changed)}")
        if os.path.exists(os.path.join(out_dir, "incomplete", "summary.json")):
            problems.append("incomplete/summary.json exists after the failed run")
    if problems:
        raise CheckFailed("; ".join(problems) + f"\n--- stdout\n{out[-3000:]}--- stderr\n{err[-3000:]}")
    return error_lines[0] if error_lines else f"exit status {status}", seconds


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("cases", nargs="*", help="case names (see --list)")
    parser.add_argument("--exe", default=os.path.join(ROOT, "build", "signorini"), help="the signorini executable")
    parser.add_argument("--mpiexec", default=shutil.which("mpiexec") or "mpiexec")
    parser.add_argument("--np", type=int, default=1, help="MPI ranks")
    parser.add_argument("--all", action="store_true", help="run every case")
    parser.add_argument("--keep", action="store_true", help="keep the work directories")
    parser.add_argument("--verbose", action="store_true", help="print each run's command and output")
    parser.add_argument("--list", action="store_true", help="list the case names and exit")
    args = parser.parse_args()
    if args.list:
        print("\n".join(CASES))
        return 0
    names = list(CASES) if args.all else args.cases
    unknown = [n for n in names if n not in CASES]
    if not names or unknown:
        parser.print_usage(sys.stderr)
        print(f"unknown case(s): {', '.join(unknown)}" if unknown else "no case given", file=sys.stderr)
        return 2
    exe = os.path.abspath(args.exe)
    env = environment()
    failed = skipped = 0
    for name in names:
        work = tempfile.mkdtemp(prefix=f"signorini_bad_{name}_np{args.np}_")
        try:
            line, seconds = check_case(name, exe, args.mpiexec, args.np, work, env, args.verbose)
            print(f"PASS {name} (np {args.np}, {seconds:.1f} s): {line}")
            if not args.keep:
                shutil.rmtree(work, ignore_errors=True)
        except CheckFailed as e:
            failed += 1
            print(f"FAIL {name} (np {args.np}): {e}\n(work directory kept: {work})")
        except Skipped as e:
            skipped += 1
            print(f"SKIP {name} (np {args.np}): {e}")
            shutil.rmtree(work, ignore_errors=True)
    return 1 if failed else 77 if skipped == len(names) else 0


if __name__ == "__main__":
    sys.exit(main())
