"""Render a STEP assembly written by `noncirc cad` as a PNG, from the STEP file itself:
OpenCascade (OCP) reads it with its names and placements and meshes every solid, and
matplotlib draws the triangles shaded by their normals. docs/cad.md's picture.

    .venv/bin/python scripts/render_step.py DIR/train.step docs/figures/cad_train.png
"""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from mpl_toolkits.mplot3d.art3d import Poly3DCollection
from OCP.BRep import BRep_Tool
from OCP.BRepMesh import BRepMesh_IncrementalMesh
from OCP.IFSelect import IFSelect_RetDone
from OCP.STEPCAFControl import STEPCAFControl_Reader
from OCP.TCollection import TCollection_ExtendedString
from OCP.TDataStd import TDataStd_Name
from OCP.TDF import TDF_LabelSequence
from OCP.TDocStd import TDocStd_Document
from OCP.TopAbs import TopAbs_FACE, TopAbs_REVERSED
from OCP.TopExp import TopExp_Explorer
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS
from OCP.XCAFDoc import XCAFDoc_DocumentTool

# A colour per kind of part (the instance's name without its number).
COLOURS = {
    "sun": "#8c9aa8",
    "intermediate": "#6f8fb3",
    "intermediate_b": "#5a7ca3",
    "planet": "#9fb4c8",
    "carrier_plate": "#d9d2c3",
    "arm": "#d08a3c",
    "pusher": "#b5532c",
    "driver": "#8c9aa8",
    "driven": "#6f8fb3",
}


def components(path: str):
    """(instance name, placed shape) of every component of the assembly."""
    doc = TDocStd_Document(TCollection_ExtendedString("noncirc"))
    reader = STEPCAFControl_Reader()
    reader.SetNameMode(True)
    if reader.ReadFile(path) != IFSelect_RetDone or not reader.Transfer(doc):
        sys.exit(f"{path}: not a STEP file OpenCascade reads")
    tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    free = TDF_LabelSequence()
    tool.GetFreeShapes(free)
    comps = TDF_LabelSequence()
    tool.GetComponents_s(free.Value(1), comps)
    for i in range(1, comps.Length() + 1):
        label = comps.Value(i)
        name = TDataStd_Name()
        label.FindAttribute(TDataStd_Name.GetID_s(), name)
        yield name.Get().ToExtString(), tool.GetShape_s(label)


def triangles(shape, deflection: float) -> np.ndarray:
    """The shape's faces meshed within `deflection` (mm): an (n, 3, 3) array, outward."""
    BRepMesh_IncrementalMesh(shape, deflection, False, 0.3, True)
    out = []
    ex = TopExp_Explorer(shape, TopAbs_FACE)
    while ex.More():
        face = TopoDS.Face_s(ex.Current())
        loc = TopLoc_Location()
        tri = BRep_Tool.Triangulation_s(face, loc)
        if tri is not None:
            t = loc.Transformation()
            nodes = np.array([(p.X(), p.Y(), p.Z()) for p in (tri.Node(i).Transformed(t) for i in range(1, tri.NbNodes() + 1))])
            idx = np.array([tri.Triangle(i).Get() for i in range(1, tri.NbTriangles() + 1)]) - 1
            if face.Orientation() == TopAbs_REVERSED:
                idx = idx[:, ::-1]
            out.append(nodes[idx])
        ex.Next()
    return np.concatenate(out)


def draw(ax, parts, title: str, elev: float, azim: float) -> None:
    """The meshed parts on a 3D axis, each axis to scale, shaded from one light."""
    light = np.array([0.4, -0.5, 0.75])
    light /= np.linalg.norm(light)
    lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
    for kind, tris in parts:
        n = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
        n /= np.linalg.norm(n, axis=1, keepdims=True) + 1e-300
        shade = 0.45 + 0.55 * np.clip(n @ light, 0, 1)
        base = np.array(matplotlib.colors.to_rgb(COLOURS.get(kind, "#999999")))
        alpha = 0.25 if kind == "carrier_plate" else 1.0
        colours = np.column_stack([np.outer(shade, base), np.full(len(tris), alpha)])
        # Opaque faces edged in their own colour (no seams between triangles).
        edges = colours if alpha == 1.0 else "none"
        ax.add_collection3d(Poly3DCollection(tris, facecolors=colours, edgecolors=edges, linewidths=0.15))
        lo, hi = np.minimum(lo, tris.reshape(-1, 3).min(0)), np.maximum(hi, tris.reshape(-1, 3).max(0))
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(lo[2], hi[2])
    ax.set_box_aspect(hi - lo)
    ax.view_init(elev=elev, azim=azim)
    ax.set_xlabel("x (mm)", labelpad=8)
    ax.set_ylabel("y (mm)", labelpad=8)
    ax.set_zticks([])
    ax.set_title(title, fontsize=10)


def main(step: str, png: str) -> None:
    parts = []
    for name, shape in components(step):
        kind = "_".join(w for w in name.split("_") if not w.isdigit() and w not in ("top", "bottom"))
        parts.append((kind, triangles(shape, 0.05)))
    fig = plt.figure(figsize=(12, 5.6), dpi=150)
    whole = fig.add_subplot(1, 2, 1, projection="3d", computed_zorder=False)
    draw(whole, parts, "(a) the assembly: plates (translucent), gears, arms and pushers", 35, -60)
    gears = fig.add_subplot(1, 2, 2, projection="3d", computed_zorder=False)
    draw(gears, [p for p in parts if p[0] not in ("carrier_plate", "arm", "pusher")], "(b) the gears alone, in mesh", 65, -75)
    fig.suptitle(f"{step.split('/')[-1]}, as OpenCascade reads it (meshed within 0.05 mm)", fontsize=11)
    fig.tight_layout()
    fig.savefig(png)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
