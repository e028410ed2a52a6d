"""The solid models (`noncirc cad`) against OpenCascade (OCP, the kernel of FreeCAD and
CadQuery, from the package index) and trimesh: the STEP assembly read with its names and
placements, every part a valid closed solid of the volume of its exact profile, its flanks
on the cut outline within the tolerance, the gears in mesh at 36 carrier angles, and the
STL watertight with outward normals.

The CLI binary (`cli_binary.NONCIRC_BIN`) writes the files; tests/run_all.sh builds it.
"""

import json
import math
import subprocess
from pathlib import Path

import numpy as np
import pytest
import trimesh
from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepGProp import BRepGProp
from OCP.Bnd import Bnd_Box
from OCP.GCPnts import GCPnts_QuasiUniformDeflection
from OCP.GProp import GProp_GProps
from OCP.IFSelect import IFSelect_RetDone
from OCP.STEPCAFControl import STEPCAFControl_Reader
from OCP.STEPControl import STEPControl_Reader
from OCP.TCollection import TCollection_ExtendedString
from OCP.TDataStd import TDataStd_Name
from OCP.TDF import TDF_Label, TDF_LabelSequence
from OCP.TDocStd import TDocStd_Document
from OCP.BRepTools import BRepTools
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_SHELL, TopAbs_SOLID
from OCP.TopExp import TopExp_Explorer
from OCP.XCAFDoc import XCAFDoc_DocumentTool
from OCP.TopoDS import TopoDS
from OCP.gp import gp_Dir
from shapely.affinity import rotate, translate
from shapely.geometry import MultiLineString, Point
from cli_binary import NONCIRC_BIN

ROOT = Path(__file__).resolve().parents[2]
BIN = NONCIRC_BIN
# The two-arm design cut by a shaper (a rack cannot cut its concave arcs), with 0.1 mm of
# backlash so that the gears' flanks stand apart by the checked clearance.
SETS = ['gear.teeth.cutter={kind="shaper",teeth=100}', "gear.teeth.backlash_mm=0.1"]
TOL = 1e-3  # --tolerance-mm, the default


def run(*args: str, sets=SETS) -> subprocess.CompletedProcess:
    cmd = [str(BIN), *args]
    for s in sets:
        cmd += ["--set", s]
    return subprocess.run(cmd, capture_output=True, text=True)


@pytest.fixture(scope="module")
def cad(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("cad")
    done = run("cad", "two-arm", "--out", str(out))
    assert done.returncode == 0, done.stderr
    return out


def manifest(d: Path) -> dict:
    return json.loads((d / "assembly.json").read_text())


def read_part(path: Path):
    r = STEPControl_Reader()
    assert r.ReadFile(str(path)) == IFSelect_RetDone
    r.TransferRoots()
    return r.OneShape()


def count(shape, kind) -> int:
    ex, n = TopExp_Explorer(shape, kind), 0
    while ex.More():
        n += 1
        ex.Next()
    return n


def volume(shape) -> float:
    g = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, g, 1e-10)
    return g.Mass()


def edge_points(edge, deflection: float) -> np.ndarray:
    """An edge divided within `deflection` (mm) of its curve: its points (x, y, z)."""
    d = GCPnts_QuasiUniformDeflection(BRepAdaptor_Curve(edge), deflection)
    return np.array([(p.X(), p.Y(), p.Z()) for p in (d.Value(i) for i in range(1, d.NbPoints() + 1))])


def outline(shape, deflection: float = 1e-5) -> MultiLineString:
    """The outer boundary of the solid's face at z = 0 (OpenCascade's outer wire of the
    face whose every edge lies there), each edge divided within `deflection` (mm): a
    part is a prism, so this is its profile's outline."""
    ex = TopExp_Explorer(shape, TopAbs_FACE)
    while ex.More():
        face = TopoDS.Face_s(ex.Current())
        wire = BRepTools.OuterWire_s(face)
        edges = []
        we = TopExp_Explorer(wire, TopAbs_EDGE)
        while we.More():
            edges.append(edge_points(TopoDS.Edge_s(we.Current()), deflection))
            we.Next()
        if all(np.all(np.abs(e[:, 2]) < 1e-9) for e in edges):
            return MultiLineString([e[:, :2] for e in edges])
        ex.Next()
    raise AssertionError("no face at z = 0")


def test_the_assembly_reads_with_its_parts_names_and_placements(cad):
    m = manifest(cad)
    doc = TDocStd_Document(TCollection_ExtendedString("noncirc"))
    reader = STEPCAFControl_Reader()
    reader.SetNameMode(True)
    assert reader.ReadFile(str(cad / "train.step")) == IFSelect_RetDone
    assert reader.Transfer(doc)
    tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    free = TDF_LabelSequence()
    tool.GetFreeShapes(free)

    def name(label) -> str:
        a = TDataStd_Name()
        assert label.FindAttribute(TDataStd_Name.GetID_s(), a)
        return a.Get().ToExtString()

    assert free.Length() == 1
    top = free.Value(1)
    assert name(top) == "train" and tool.IsAssembly_s(top)
    comps = TDF_LabelSequence()
    tool.GetComponents_s(top, comps)
    assert comps.Length() == len(m["instances"]) == 11  # sun, 2 × (intermediate, planet, arm, pusher), 2 plates
    for i, inst in enumerate(m["instances"]):
        c = comps.Value(i + 1)
        ref = TDF_Label()
        tool.GetReferredShape_s(c, ref)
        assert name(c) == inst["name"]
        assert name(ref) == m["parts"][inst["part"]]["name"]
        t = tool.GetShape_s(c).Location().Transformation()
        origin = t.TranslationPart()
        assert np.allclose([origin.X(), origin.Y(), origin.Z()], inst["at_mm"], atol=1e-9)
        # The part's x axis turned by the instance's angle about z.
        x = gp_Dir(1, 0, 0).Transformed(t)
        a = math.radians(inst["angle_deg"])
        assert np.allclose([x.X(), x.Y(), x.Z()], [math.cos(a), math.sin(a), 0.0], atol=1e-12)


@pytest.mark.parametrize("part", ["sun", "intermediate", "planet", "carrier_plate", "arm", "pusher"])
def test_each_part_is_one_valid_closed_solid_of_its_profiles_volume(cad, part):
    m = {p["name"]: p for p in manifest(cad)["parts"]}
    shape = read_part(cad / f"{part}.step")
    assert BRepCheck_Analyzer(shape).IsValid()
    assert count(shape, TopAbs_SOLID) == 1 and count(shape, TopAbs_SHELL) == 1
    ex = TopExp_Explorer(shape, TopAbs_SHELL)
    assert BRep_Tool.IsClosed_s(ex.Current())
    # The exact area of the lines and arcs times the thickness.
    assert volume(shape) == pytest.approx(m[part]["volume_mm3"], rel=1e-6)
    box = Bnd_Box()
    BRepBndLib.AddOptimal_s(shape, box, False, False)
    assert box.CornerMin().Z() == pytest.approx(0.0, abs=1e-6)  # OCC widens a box by its 1e-7 mm tolerance
    assert box.CornerMax().Z() == pytest.approx(m[part]["thickness_mm"], abs=1e-6)


@pytest.mark.parametrize("gear,csv", [("sun", "driver.csv"), ("intermediate", "driven.csv")])
def test_the_flanks_follow_the_cut_outline_within_the_tolerance(cad, tmp_path, gear, csv):
    # The outline `noncirc teeth` computes, point by point, against the solid's edges at
    # its face z = 0: every point within the tolerance, and the bounding boxes equal.
    done = run("teeth", "two-arm", "--export", str(tmp_path), "--format", "json")
    assert done.returncode == 0, done.stderr
    cut = np.loadtxt(tmp_path / csv, delimiter=",", skiprows=1)
    outer = outline(read_part(cad / f"{gear}.step"))
    far = max(outer.distance(Point(p)) for p in cut)
    assert far <= TOL + 2e-5, far
    lo, hi = cut.min(axis=0), cut.max(axis=0)
    (x0, y0, x1, y1) = outer.bounds
    assert np.allclose([x0, y0], lo, atol=TOL) and np.allclose([x1, y1], hi, atol=TOL)


# The train with two pairs: layer B of each intermediate and the planets cut on a second
# curve (docs/inverse.md §6).
SECOND = 'gear.second_curve={kind="ellipse",semi_major_mm=30.0,eccentricity=0.2}'


@pytest.mark.parametrize("pairs", [1, 2])
def test_the_gears_mesh_without_overlap_at_36_carrier_angles(tmp_path, pairs):
    # Each gear's profile (its solid's edges at z = 0, within 1e-5 mm) placed as `noncirc cad`
    # places it: each pair that meshes stands apart by no less than the 2D check's least
    # clearance over the turn (less the STEP's tolerance on each side) and no more than
    # its largest backlash: in mesh, never overlapping. With two pairs, each layer's gears
    # share a height and the other layer's stand b + g above or below.
    sets = SETS + ([SECOND] if pairs == 2 else [])
    done = run("cad", "two-arm", "--format", "step", "--out", str(tmp_path / "parts"), sets=sets)
    assert done.returncode == 0, done.stderr
    m0 = manifest(tmp_path / "parts")
    names = [p["name"] for p in m0["parts"]]
    gears = ["sun", "intermediate", "planet"] + (["intermediate_b"] if pairs == 2 else [])
    assert set(gears) <= set(names)
    sections = {g: outline(read_part(tmp_path / "parts" / f"{g}.step")) for g in gears}
    checks = json.loads(run("teeth", "two-arm", "--format", "json", sets=sets).stdout)
    reports = [checks["checks"]["mesh"]] + ([checks["second_checks"]["mesh"]] if pairs == 2 else [])
    for r in reports:
        assert 0 < r["least_clearance_mm"] < r["backlash_mm"][1]
    seen = []
    for k in range(36):
        theta = 10.0 * k
        done = run("cad", "two-arm", "--format", "json", "--carrier-deg", str(theta), "--out", str(tmp_path), sets=sets)
        assert done.returncode == 0, done.stderr
        m = manifest(tmp_path)
        at = {i["name"]: i for i in m["instances"]}

        def placed(name: str) -> MultiLineString:
            inst = at[name]
            lines = sections[m["parts"][inst["part"]]["name"]]
            return translate(rotate(lines, inst["angle_deg"], origin=(0, 0)), *inst["at_mm"][:2])

        for arm in (1, 2):
            meshes = [("sun", f"intermediate_{arm}", reports[0])]
            if pairs == 1:
                meshes.append((f"intermediate_{arm}", f"planet_{arm}", reports[0]))
            else:
                meshes.append((f"intermediate_{arm}_b", f"planet_{arm}", reports[1]))
                # Layer B on the intermediate's axle, one layer up, with the planet.
                assert at[f"intermediate_{arm}_b"]["at_mm"][:2] == at[f"intermediate_{arm}"]["at_mm"][:2]
                assert at[f"intermediate_{arm}_b"]["at_mm"][2] == at[f"planet_{arm}"]["at_mm"][2] > 0
            for a, c, r in meshes:
                # Outlines that do not cross, of gears whose centres lie outside each other:
                # no overlap.
                assert at[a]["at_mm"][2] == at[c]["at_mm"][2]
                ra, rc = placed(a), placed(c)
                assert not ra.intersects(rc)
                d = ra.distance(rc)
                seen.append(d)
                assert r["least_clearance_mm"] - 2 * TOL - 2e-5 <= d <= r["backlash_mm"][1] + 2 * TOL, (theta, a, c, d)
    assert len(seen) == 36 * 4


@pytest.mark.parametrize("part", ["sun", "intermediate", "carrier_plate", "arm", "pusher"])
def test_the_stl_is_watertight_outward_and_of_the_solids_volume(cad, part):
    mesh = trimesh.load(cad / f"{part}.stl")
    assert mesh.is_watertight and mesh.is_winding_consistent
    m = {p["name"]: p for p in manifest(cad)["parts"]}[part]
    # Outward normals: a positive signed volume; the chords within TOL of the arcs cut off
    # at most TOL × perimeter × thickness, and the single-precision coordinates 1e-7
    # relative.
    shape = read_part(cad / f"{part}.step")
    perimeter = 0.0
    ex = TopExp_Explorer(shape, TopAbs_EDGE)
    while ex.More():
        e = edge_points(TopoDS.Edge_s(ex.Current()), 1e-3)
        if np.all(np.abs(e[:, 2]) < 1e-9):
            perimeter += np.hypot(*np.diff(e[:, :2], axis=0).T).sum()
        ex.Next()
    assert mesh.volume > 0
    assert abs(mesh.volume - m["volume_mm3"]) <= TOL * perimeter * m["thickness_mm"] + 1e-6 * m["volume_mm3"]


def test_bad_dimensions_are_refused_naming_the_field_and_nothing_is_written(tmp_path):
    cases = [
        ("cad.bore_diameter_mm=90", "cad.bore_diameter_mm"),
        ("cad.key_width_mm=12", "cad.key_width_mm"),
        ("dynamics.face_width_mm=0", "dynamics.face_width_mm"),
        ("cad.arm_width_mm=10", "cad.arm_width_mm"),
        ("cad.mark_diameter_mm=40", "cad.mark_diameter_mm"),
    ]
    for assignment, field in cases:
        out = tmp_path / field
        done = run("cad", "two-arm", "--out", str(out), sets=SETS + [assignment])
        assert done.returncode == 2, (assignment, done.returncode, done.stderr)
        assert field in done.stderr, done.stderr
        assert not out.exists()
    for flag, value in [("--tolerance-mm", "20"), ("--tolerance-mm", "0"), ("--carrier-deg", "nan")]:
        out = tmp_path / flag
        done = run("cad", "two-arm", flag, value, "--out", str(out))
        assert done.returncode == 2 and flag in done.stderr, done.stderr
        assert not out.exists()


def test_python_writes_what_the_cli_writes(cad, tmp_path):
    import noncirc

    scene = noncirc.Scene.builtin("two-arm").with_set("gear.teeth.cutter", {"kind": "shaper", "teeth": 100})
    scene = scene.with_set("gear.teeth.backlash_mm", 0.1)
    done = noncirc.cad(scene, tmp_path)
    assert not done.failures and done.carrier_deg == 0.0
    names = sorted(p.name for p in done.paths)
    assert names == sorted(p.name for p in cad.iterdir())
    for p in done.paths:
        assert p.read_bytes() == (cad / p.name).read_bytes(), p.name
    assert [p.name for p in done.parts] == [p["name"] for p in manifest(cad)["parts"]]
    assert done.instances[1].part == "intermediate" and done.instances[1].name == "intermediate_1"
    # A dimension that does not fit names its field and writes nothing.
    with pytest.raises(noncirc.ParameterError, match="cad.key_width_mm"):
        noncirc.cad(scene.with_set("cad.key_width_mm", 20.0), tmp_path / "no")
    assert not (tmp_path / "no").exists()
    with pytest.raises(noncirc.ParameterError, match="formats"):
        noncirc.cad(scene, tmp_path / "no", formats=["iges"])
