#!/usr/bin/env python3
"""Scene tests of mesh import (issue 13, P1.3): glide run on bodies read from
Abaqus and Gmsh files, statistics checked. Each case states what it checks
and why the expected answer is right. Uses the helpers of scene_tests.py.
Usage: mesh_import_tests.py --glide PATH --case NAME
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scene_tests as st  # noqa: E402
from scene_tests import check, close  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SCENES = os.path.join(HERE, "mesh-import")
DATA = os.path.join(os.path.dirname(HERE), "data", "mesh")


def case_abaqus_two_bodies_contact():
    """A two-body contact problem in one Abaqus file written for another
    solver (tests/data/mesh/two_bodies.inp: both bodies in one file, picked
    by *ELSET; element ids 641-648 and node ids 1001-1015 for the second;
    *NSET FIXED and LOADED for the supports and the push; element-based
    *SURFACE SLAVE and MASTER; a deformable master). The file has exactly
    the nodes and cells of block-on-block-builtin.prm (built-in blocks), so
    the reactions and the contact force must be the same to solver
    tolerance; in each run the support balances the push and the contact
    force (equilibrium of each body). The node-based *SURFACE SLAVE_NODES
    (the same 5 nodes, each with contact area 1) constrains the same nodes,
    so it carries the same force. The problem is linear and the interface
    is closed everywhere from the start, so the active set is right in the
    first iteration: one Newton step and one to confirm, at most 4 with
    margin."""
    inp, log, out = st.run(os.path.join(SCENES, "block-on-block-inp.prm"), "Output/Write VTU=false")
    ref, _, _ = st.run(os.path.join(SCENES, "block-on-block-builtin.prm"), "Output/Write VTU=false")
    check("lower.MASTER" in log and "upper.SLAVE" in log, "the log lists the surfaces of the file by name")
    check("upper.LOADED" in log and "lower.FIXED" in log, "the log lists the node sets of the file")
    check("slave upper.SLAVE with 5 nodes" in log, "5 slave nodes on SLAVE")
    check(len(inp) == 2 and len(ref) == 2, "both runs finish their 2 steps")
    for a, b in zip(inp, ref):
        t = a["load_factor"]
        check(a["kinsol_iterations"] <= 4, f"{int(a['kinsol_iterations'])} iterations at t={t}")
        check(a["reaction_hold_y"] > 0, f"the support pushes up at t={t}")
        close(a["reaction_hold_y"], b["reaction_hold_y"], 1e-8, f"support reaction as with built-in meshes at t={t}")
        close(a["contact_interface_force_y"], b["contact_interface_force_y"], 1e-8,
              f"contact force as with built-in meshes at t={t}")
        close(a["reaction_hold_y"], -a["reaction_push_y"], 1e-9, f"support balances the push at t={t}")
        close(a["contact_interface_force_y"], a["reaction_hold_y"], 1e-9, f"contact force = support reaction at t={t}")
        check(a["contact_interface_active"] == b["contact_interface_active"], f"same active set at t={t}")
    nodes, log, _ = st.run(os.path.join(SCENES, "block-on-block-inp.prm"), "Output/Write VTU=false",
                           "Contact pair interface/Slave=upper.SLAVE_NODES", name="node-based")
    check("slave upper.SLAVE_NODES with 5 nodes" in log,
          "5 slave nodes on the node-based surface SLAVE_NODES (none of the lower body)")
    for a, b in zip(nodes, inp):
        close(a["reaction_hold_y"], b["reaction_hold_y"], 1e-8,
              f"node-based slave surface: same reaction at t={a['load_factor']}")


def one_body(mesh, *sets, name):
    return st.run(os.path.join(SCENES, "one-body.prm"), "Output/Write VTU=false",
                  f"Body part/Mesh file={os.path.join(DATA, mesh)}", *sets, name=name)


def case_gmsh_and_abaqus_bodies_balance():
    """Single bodies from the other kinds of file, each held on a named
    surface and loaded on another named surface or node set; the support
    reaction must balance the load exactly (global equilibrium):
    - plate41.msh (written by Gmsh 4 in format 4.1): the physical point
      'corner' is a node set carrying a force (0, -3): R = (0, 3);
    - straight_cpe8.inp (CPE8R elements with straight edges, read with their
      corners; Element degree = 2): traction (0, -2) on TOP, length 2, held
      on the rest of the boundary: R = (0, 4);
    - parts.inp, instance Block-1 (a *PART placed by *INSTANCE with a
      translation): held on the assembly-level surface Bottom, traction
      (1, -1) on the part-level surface Top of length 1: R = (-1, 1);
    - box41.msh (3D, 2 hexahedra, Gmsh 4.1): held on 'bottom', pressure 1 on
      'top' (area 2): R_z = 2."""
    rows, _, _ = one_body("plate41.msh", "Boundary conditions=hold, load", "Boundary condition hold/Surface=part.bottom",
                          "Boundary condition load/Surface=part.corner", "Boundary condition load/Type=force",
                          "Boundary condition load/Function=0; -3*t", name="plate41")
    close(rows[-1]["reaction_hold_y"], 3., 1e-9, "plate41.msh: the support carries the force on the node set 'corner'")
    close(abs(rows[-1]["reaction_hold_x"]) + 1, 1., 1e-9, "plate41.msh: no horizontal reaction")
    rows, _, _ = one_body("straight_cpe8.inp", "Discretization/Element degree=2", "Boundary conditions=hold, load",
                          "Boundary condition hold/Surface=part.unnamed", "Boundary condition load/Surface=part.TOP",
                          "Boundary condition load/Type=traction", "Boundary condition load/Function=0; -2*t",
                          name="cpe8")
    close(rows[-1]["reaction_hold_y"], 4., 1e-9, "straight_cpe8.inp: the support carries the traction on TOP")
    rows, _, _ = one_body("parts.inp", "Body part/Part=Block-1", "Boundary conditions=hold, load",
                          "Boundary condition hold/Surface=part.Bottom", "Boundary condition load/Surface=part.Top",
                          "Boundary condition load/Type=traction", "Boundary condition load/Function=t; -t",
                          name="parts")
    close(rows[-1]["reaction_hold_x"], -1., 1e-9, "parts.inp: x reaction of the instance Block-1")
    close(rows[-1]["reaction_hold_y"], 1., 1e-9, "parts.inp: y reaction of the instance Block-1")
    rows, _, _ = one_body("box41.msh", "Dimension=3", "Analysis type=3d", "Boundary conditions=hold, load",
                          "Boundary condition hold/Surface=part.bottom", "Boundary condition load/Surface=part.top",
                          "Boundary condition load/Type=pressure", "Boundary condition load/Function=t",
                          name="box41")
    close(rows[-1]["reaction_hold_z"], 2., 1e-9, "box41.msh: the support carries the pressure on 'top'")


def case_byte_order_mark():
    """P1.3: a mesh file saved with a UTF-8 byte-order mark (Windows editors
    write one) is read as without it, as scene files are (until 2026-12-07
    an Abaqus file's first keyword was taken for a data line, and a Gmsh
    file's '$MeshFormat' was not found). plate41.msh and parts.inp of
    case_gmsh_and_abaqus_bodies_balance, each with the mark: the same
    reactions."""
    import shutil
    import tempfile
    work = tempfile.mkdtemp(prefix="glide-bom-")
    try:
        for mesh in ("plate41.msh", "parts.inp"):
            with open(os.path.join(DATA, mesh), "rb") as f:
                text = f.read()
            with open(os.path.join(work, mesh), "wb") as f:
                f.write(b"\xef\xbb\xbf" + text)
        rows, _, _ = st.run(os.path.join(SCENES, "one-body.prm"), "Output/Write VTU=false",
                            f"Body part/Mesh file={os.path.join(work, 'plate41.msh')}", "Boundary conditions=hold, load",
                            "Boundary condition hold/Surface=part.bottom", "Boundary condition load/Surface=part.corner",
                            "Boundary condition load/Type=force", "Boundary condition load/Function=0; -3*t",
                            name="plate41_bom")
        close(rows[-1]["reaction_hold_y"], 3., 1e-9, "plate41.msh with a byte-order mark: R = (0, 3)")
        rows, _, _ = st.run(os.path.join(SCENES, "one-body.prm"), "Output/Write VTU=false",
                            f"Body part/Mesh file={os.path.join(work, 'parts.inp')}", "Body part/Part=Block-1",
                            "Boundary conditions=hold, load", "Boundary condition hold/Surface=part.Bottom",
                            "Boundary condition load/Surface=part.Top", "Boundary condition load/Type=traction",
                            "Boundary condition load/Function=t; -t", name="parts_bom")
        close(rows[-1]["reaction_hold_y"], 1., 1e-9, "parts.inp with a byte-order mark: R_y = 1")
    finally:
        shutil.rmtree(work, ignore_errors=True)


def case_omitted_coordinates():
    """P1.3: Abaqus node lines whose trailing coordinates are left out, or
    left blank, have 0 there, as in Abaqus (until 2026-12-07 refused: 'a
    node line needs its id and 2 coordinates'). omitted_coordinates.inp
    is two_quads.inp (2 x 1) written so; held on the rest of the boundary,
    traction (0, -1) on its top SS2 of length 2: R_y = 2, and the same
    reactions as two_quads.inp to round-off."""
    loads = ("Boundary conditions=hold, load", "Boundary condition hold/Surface=part.unnamed",
             "Boundary condition load/Surface=part.SS2", "Boundary condition load/Type=traction",
             "Boundary condition load/Function=0.5*t; -t")
    rows, _, _ = one_body("omitted_coordinates.inp", *loads, name="omitted")
    reference, _, _ = one_body(os.path.join("..", "two_quads.inp"), *loads, name="written")
    close(rows[-1]["reaction_hold_y"], 2., 1e-9, "coordinates left out: the support carries the traction")
    for c in ("x", "y"):
        close(rows[-1][f"reaction_hold_{c}"], reference[-1][f"reaction_hold_{c}"], 1e-12,
              f"reaction {c} as with the coordinates written")


def case_unused_interior_surface():
    """P1.3: a surface with a face inside the body (between two elements)
    that the scene does not use does not stop the file from being read
    (bad_interior_surface.inp: two CPE4 side by side, *SURFACE MIDDLE on
    the face between them; until 2026-12-07 refused as a whole); held on
    the rest of the boundary, which MIDDLE is not part of, and loaded
    with a body force (0, -1) over the area 2: R_y = 2. Where the scene
    names MIDDLE it is an error (error.mesh.abaqus_interior_surface)."""
    rows, _, _ = one_body("bad_interior_surface.inp", "Boundary conditions=hold",
                          "Boundary condition hold/Surface=part.unnamed", "Body part/Body force=0; -t",
                          name="interior")
    close(rows[-1]["reaction_hold_y"], 2., 1e-9, "read, and the body force is carried")


def case_midside_nodes_in_a_node_set():
    """P1.3: a node set of the file that holds mid-side nodes of
    second-order elements, which glide reads with their corners only: a
    force on it acts on its corner nodes only, and a set-up warning says
    so (until 2026-12-07 in silence; Abaqus' *CLOAD would load every node
    of the set). c3d20_mixed_node_set.inp: C3D20R block, *NSET MIXED = one
    corner node and two mid-side nodes, a force (0, -1, 0) per node: the
    reaction is 1, and the warning names the set, the 2 mid-side and the 1
    corner node. The node sets of element sets (every node of the
    elements) get no warning, nor does straight_cpe8.inp, whose *NSET TOP
    with mid-side nodes is the node set of its surface TOP. Nor does the
    file where the scene does not use MIXED (until 2026-12-07 its warning
    was printed at every run of a scene on that file). An *NSET named like
    an *ELSET is the *NSET, and warned about as such
    (c3d20_nset_named_like_an_elset.inp: MIXED renamed E_zmax_2; until
    2026-12-07 no warning)."""
    rows, log, _ = one_body("c3d20_mixed_node_set.inp", "Dimension=3", "Analysis type=3d",
                            "Boundary conditions=hold, load", "Boundary condition hold/Surface=part.B_ymin",
                            "Boundary condition load/Surface=part.MIXED", "Boundary condition load/Type=force",
                            "Boundary condition load/Function=0; -t; 0", name="midside")
    check("the node set 'MIXED' of" in log and "has 2 mid-side node(s) of second-order elements" in log
          and "acts on its 1 corner node(s) only" in log, "the node set with mid-side nodes is named in a warning")
    check(log.count("mid-side node(s) of second-order") == 1, "no warning for the element sets' node sets")
    close(rows[-1]["reaction_hold_y"], 1., 1e-9, "the force acts on the corner node only")
    rows, log, _ = one_body("straight_cpe8.inp", "Discretization/Element degree=2", "Boundary conditions=hold, load",
                            "Boundary condition hold/Surface=part.unnamed", "Boundary condition load/Surface=part.TOP",
                            "Boundary condition load/Type=traction", "Boundary condition load/Function=0; -2*t",
                            name="cpe8")
    check("mid-side node(s) of second-order" not in log, "straight_cpe8.inp: no warning")
    rows, log, _ = one_body("c3d20_mixed_node_set.inp", "Dimension=3", "Analysis type=3d",
                            "Boundary conditions=hold, load", "Boundary condition hold/Surface=part.B_ymin",
                            "Boundary condition load/Surface=part.B_ymax", "Boundary condition load/Type=traction",
                            "Boundary condition load/Function=0; -t; 0", name="midside-unused")
    check("mid-side node(s) of second-order" not in log, "MIXED not used by the scene: no warning")
    rows, log, _ = one_body("c3d20_nset_named_like_an_elset.inp", "Dimension=3", "Analysis type=3d",
                            "Boundary conditions=hold, load", "Boundary condition hold/Surface=part.B_ymin",
                            "Boundary condition load/Surface=part.E_zmax_2", "Boundary condition load/Type=force",
                            "Boundary condition load/Function=0; -t; 0", name="midside-elset-name")
    check("the node set 'E_zmax_2' of" in log and "has 2 mid-side node(s) of second-order elements" in log,
          "an *NSET named like an *ELSET is warned about")
    close(rows[-1]["reaction_hold_y"], 1., 1e-9, "the *NSET's corner node is loaded, not the element set's nodes")
    close(rows[-1]["reaction_hold_y"], 1., 1e-9, "the traction on the unit face B_ymax is carried")


def case_z_round_off_in_2d():
    """P1.3: a 2D mesh whose generator wrote z = 1e-14 at a node (round-off
    of a 3D writer) is read as lying in z = 0 (until 2026-12-06 it was
    refused as 'z = 0.000000'); 0.001 is still refused
    (error.mesh.gmsh_z_in_2d). z_roundoff.msh: two quadrilaterals on
    [0, 2] x [0, 1], held on 'bottom', traction (0, -1) on 'top' (length 2):
    R_y = 2."""
    rows, _, _ = one_body("z_roundoff.msh", "Boundary conditions=hold, load",
                          "Boundary condition hold/Surface=part.bottom", "Boundary condition load/Surface=part.top",
                          "Boundary condition load/Type=traction", "Boundary condition load/Function=0; -t",
                          name="z_roundoff")
    close(rows[-1]["reaction_hold_y"], 2., 1e-9, "z = 1e-14 read as 0: the support carries the traction")


def case_element_types_against_the_analysis():
    """Abaqus 2D element types say what the analysis is (CAX: axisymmetric,
    CPE: plane strain, CPS: plane stress); glide takes it from the scene's
    'Analysis type' (doc/mesh-import.md) and warns where they disagree:
    - cax4r.inp (CAX4R) in a plane-strain scene: a warning that names the
      type and the parameter; with 'Analysis type = axisymmetric', none;
    - two_quads.inp (CPE4) in an axisymmetric scene: a warning.
    Each run is held on the rest of the boundary and loaded on the top, and
    finishes (a warning, not an error)."""
    loads = ("Boundary conditions=hold, load", "Boundary condition hold/Surface=part.unnamed",
             "Boundary condition load/Type=traction", "Boundary condition load/Function=0; -t")
    rows, log, _ = one_body("cax4r.inp", *loads, "Boundary condition load/Surface=part.TOP", name="cax-plane")
    check("warning: body 'part': the mesh file" in log and "has elements of type CAX4R, axisymmetric in Abaqus, "
          "but the scene's 'Analysis type' is plane strain" in log, "CAX4R in plane strain: warned")
    check(len(rows) > 0, "the plane-strain run finishes")
    rows, log, _ = one_body("cax4r.inp", *loads, "Boundary condition load/Surface=part.TOP",
                            "Analysis type=axisymmetric", name="cax-axi")
    check("warning: body" not in log, "CAX4R in an axisymmetric scene: no warning")
    check(len(rows) > 0, "the axisymmetric run finishes")
    rows, log, _ = one_body(os.path.join("..", "two_quads.inp"), *loads, "Boundary condition load/Surface=part.SS2",
                            "Analysis type=axisymmetric", name="cpe-axi")
    check("has elements of type CPE4, plane elements in Abaqus, but the scene's 'Analysis type' is axisymmetric"
          in log, "CPE4 in an axisymmetric scene: warned")


def case_duplicate_nodes_warned():
    """Duplicate nodes (two nodes of one body at one place, e.g. regions
    meshed apart without merging their nodes) leave the elements on either
    side unconnected; it may be meant (a crack, two parts in contact), so
    the log warns, naming the nodes and what to do.
    duplicate_nodes.inp: two quadrilaterals whose shared side has its nodes
    twice, each held at its bottom and pressed on its top: the log names 2
    pairs and nodes 2 and 7; two_quads.inp (the same cells with shared
    nodes): no warning. The pressed parts carry the load either way."""
    sets = ("Boundary conditions=hold, load", "Boundary condition load/Type=traction",
            "Boundary condition load/Function=0; -t")
    rows, log, _ = one_body("duplicate_nodes.inp", *sets, "Boundary condition hold/Surface=part.BOTTOM",
                            "Boundary condition load/Surface=part.TOP", name="duplicates")
    check("warning: body 'part': 2 pair(s) of nodes of the mesh file" in log and "(nodes 2 and 7 at (1, 0))" in log
          and "Coherence Mesh" in log, "duplicate nodes: warned with the nodes and what to do")
    close(rows[-1]["reaction_hold_y"], 2., 1e-9, "duplicate nodes: the supports carry the traction")
    rows, log, _ = one_body(os.path.join("..", "two_quads.inp"), *sets, "Boundary condition hold/Surface=part.unnamed",
                            "Boundary condition load/Surface=part.SS2", name="shared")
    check("lie at the same place" not in log, "shared nodes: no warning")


def case_node_set_points():
    """Issue 13: 'set Points = 0, 10;0, 5' (points separated by ';' without
    a blank) is a node set of two vertices of the 10 x 10 block; a force
    (1, 0) on each gives the support reaction R_x = -2 (global
    equilibrium)."""
    rows, _, _ = st.run(os.path.join(SCENES, "node-set-points.prm"), "Output/Write VTU=false")
    close(rows[-1]["reaction_hold_x"], -2., 1e-9, "the support balances the force on both points")


def case_mixed_node_set_and_surface():
    """P2 (boundary conditions): one condition's 'Surface' list may mix a
    node set from a mesh file and a surface (before, each worked alone but
    the list 'lower.FIXED, upper.SLAVE' was 'no such surface'). On
    block-on-block-inp.prm, the condition 'hold' on 'lower.FIXED,
    upper.SLAVE' (the lower body's bottom nodes and the upper body's bottom
    faces) must be the same problem as two conditions, 'hold' on
    'upper.SLAVE' and 'fix' on 'lower.FIXED': the mixed condition's
    reaction is the sum of the two, and the push's reaction is the same.
    Without the node set the lower body would not be held (an input
    error); without the surface the upper body would press on the lower
    one, and the reactions would differ."""
    scene = os.path.join(SCENES, "block-on-block-inp.prm")
    mixed, _, _ = st.run(scene, "Output/Write VTU=false",
                         "Boundary condition hold/Surface=lower.FIXED, upper.SLAVE", name="mixed")
    split, _, _ = st.run(scene, "Output/Write VTU=false", "Boundary conditions=hold, push, fix",
                         "Boundary condition hold/Surface=upper.SLAVE", "Boundary condition fix/Surface=lower.FIXED",
                         "Boundary condition fix/Type=fixed", name="split")
    check(len(mixed) == len(split) == 2, "both runs finish their 2 steps")
    for a, b in zip(mixed, split):
        t = a["load_factor"]
        check(abs(a["reaction_hold_y"]) > 0, f"the mixed support carries load at t={t}")
        close(a["reaction_hold_y"], b["reaction_hold_y"] + b["reaction_fix_y"], 1e-9,
              f"mixed reaction = sum of the two conditions' at t={t}")
        close(a["reaction_push_y"], b["reaction_push_y"], 1e-9, f"same push reaction at t={t}")
        # To the solver's tolerance (the contact force at the fixed slave
        # nodes is resolved to it): measured 2e-8.
        close(a["reaction_hold_y"], -a["reaction_push_y"], 1e-6, f"the support balances the push at t={t}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--glide", required=True)
    ap.add_argument("--case", required=True)
    st.ARGS = ap.parse_args()
    st.ARGS.glide = os.path.abspath(st.ARGS.glide)
    globals()["case_" + st.ARGS.case]()
    print("PASSED" if not st.failures else f"FAILED: {len(st.failures)} check(s)")
    sys.exit(1 if st.failures else 0)


if __name__ == "__main__":
    main()
