#!/usr/bin/python3
"""Convert a 2D gmsh mesh (MSH 2.2 ASCII, physical groups) to cellphase's XDMF.

    msh_to_xdmf.py mesh.msh mesh.xdmf

Called by CMake at build time (meshes/*.geo -> gmsh -2 -format msh2 -> this script). The
output is one self-contained XDMF 3 file with the data inline (Format="XML"), readable by
ParaView and by cellphase without HDF5:

  Grid "mesh"        the triangles of the physical surfaces and their nodes (only the
                     nodes the triangles use, renumbered from 0; coordinates x y)
  Grid "facet_tags"  the lines of the physical curves (node numbers of "mesh") with
                     their physical group number as the cell attribute "facet_tags", and
                     one <Information Name="NAME" Value="NUMBER"/> per physical curve

Only the standard library is used.
"""
import sys


def read_msh(path):
    names, nodes, triangles, lines = {}, {}, [], []
    with open(path) as f:
        tokens = iter(f.read().split("\n"))

        def section(name):
            out = []
            for line in tokens:
                if line.strip() == "$End" + name:
                    return out
                out.append(line)
            raise SystemExit(f"{path}: ${name} has no $End{name}")

        for line in tokens:
            tag = line.strip()
            if tag == "$MeshFormat":
                version = section("MeshFormat")[0].split()
                if not version[0].startswith("2") or version[1] != "0":
                    raise SystemExit(f"{path}: expected MSH 2.2 ASCII (gmsh -format msh2), "
                                     f"found version {version[0]} type {version[1]}")
            elif tag == "$PhysicalNames":
                for row in section("PhysicalNames")[1:]:
                    dim, number, name = row.split(maxsplit=2)
                    names[(int(dim), int(number))] = name.strip().strip('"')
            elif tag == "$Nodes":
                for row in section("Nodes")[1:]:
                    i, x, y, z = row.split()
                    if abs(float(z)) > 0:
                        raise SystemExit(f"{path}: node {i} has z = {z}; only 2D meshes")
                    nodes[int(i)] = (x, y)
            elif tag == "$Elements":
                for row in section("Elements")[1:]:
                    v = [int(t) for t in row.split()]
                    kind, ntags = v[1], v[2]
                    physical = v[3] if ntags > 0 else 0
                    vertices = v[3 + ntags:]
                    if kind == 2:
                        triangles.append(vertices)
                    elif kind == 1:
                        lines.append((physical, vertices))
                    elif kind != 15:  # points of physical points are ignored
                        raise SystemExit(f"{path}: element type {kind} is not supported "
                                         "(first-order triangles and lines only)")
    return names, nodes, triangles, lines


def main(src, dst):
    names, nodes, triangles, lines = read_msh(src)
    if not triangles:
        raise SystemExit(f"{src}: no triangles; the .geo file needs a Physical Surface")
    number = {}
    for t in triangles:
        for n in t:
            number.setdefault(n, len(number))
    for physical, (a, b) in lines:
        if a not in number or b not in number:
            raise SystemExit(f"{src}: a line of physical curve {physical} is not on the mesh")
    tags = {n: name for (dim, n), name in names.items() if dim == 1}
    for physical, _ in lines:
        if physical not in tags:
            raise SystemExit(f"{src}: physical curve {physical} has no name")
    points = [None] * len(number)
    for n, i in number.items():
        points[i] = nodes[n]

    def rows(items):
        return "\n".join(" ".join(str(x) for x in item) for item in items)

    cells = rows([number[n] for n in t] for t in triangles)
    facets = rows([number[a], number[b]] for _, (a, b) in lines)
    values = "\n".join(str(p) for p, _ in lines)
    info = "\n".join(f'      <Information Name="{name}" Value="{n}"/>'
                     for n, name in sorted(tags.items()))
    with open(dst, "w") as f:
        f.write(f"""<?xml version="1.0"?>
<!-- generated from {src.split('/')[-1]} by python/msh_to_xdmf.py -->
<Xdmf Version="3.0" xmlns:xi="http://www.w3.org/2001/XInclude">
  <Domain>
    <Grid Name="mesh" GridType="Uniform">
      <Topology TopologyType="Triangle" NumberOfElements="{len(triangles)}" NodesPerElement="3">
        <DataItem Dimensions="{len(triangles)} 3" NumberType="Int" Format="XML">
{cells}
        </DataItem>
      </Topology>
      <Geometry GeometryType="XY">
        <DataItem Dimensions="{len(points)} 2" NumberType="Float" Precision="8" Format="XML">
{rows(points)}
        </DataItem>
      </Geometry>
    </Grid>
    <Grid Name="facet_tags" GridType="Uniform">
      <xi:include xpointer="xpointer(/Xdmf/Domain/Grid[@Name='mesh']/Geometry)"/>
      <Topology TopologyType="PolyLine" NumberOfElements="{len(lines)}" NodesPerElement="2">
        <DataItem Dimensions="{len(lines)} 2" NumberType="Int" Format="XML">
{facets}
        </DataItem>
      </Topology>
      <Attribute Name="facet_tags" AttributeType="Scalar" Center="Cell">
        <DataItem Dimensions="{len(lines)} 1" NumberType="Int" Format="XML">
{values}
        </DataItem>
      </Attribute>
{info}
    </Grid>
  </Domain>
</Xdmf>
""")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    main(sys.argv[1], sys.argv[2])
