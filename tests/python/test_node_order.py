"""Node orders against Gmsh and VTK themselves: the library's tables of local nodes (VTK's and
Gmsh's) match gmsh's getElementProperties and VTK's parametric coordinates; meshes made by the
gmsh package (a disk of Q9 cells, a box of H27 cells) relocate with order="gmsh" exactly as their
VTK-ordered twins, and given as VTK by mistake they are refused with a message naming the node
order; meshio names and meshio meshes are accepted."""

import numpy as np
import pytest

import igaparam
from igaparam import IgaparamError, Mesh, Status

gmsh = pytest.importorskip("gmsh")
vtk = pytest.importorskip("vtk")
meshio = pytest.importorskip("meshio")

# Gmsh element type, VTK cell class and the library's name of each supported cell type.
TYPES = [(3, "vtkQuad", "Q4"), (16, "vtkQuadraticQuad", "Q8"), (10, "vtkBiQuadraticQuad", "Q9"),
         (5, "vtkHexahedron", "H8"), (17, "vtkQuadraticHexahedron", "H20"),
         (12, "vtkTriQuadraticHexahedron", "H27")]


@pytest.fixture(scope="module")
def gmsh_session():
    gmsh.initialize(["-noenv"])
    gmsh.option.setNumber("General.Terminal", 0)
    yield gmsh
    gmsh.finalize()


def vtk_coordinates(class_name):
    """VTK's reference coordinates of the cell's nodes, mapped from [0, 1] to [-1, 1]."""
    cell = getattr(vtk, class_name)()
    n, d = cell.GetNumberOfPoints(), cell.GetCellDimension()
    pcoords = cell.GetParametricCoords()
    return np.array([[2 * pcoords[3 * i + k] - 1 for k in range(d)] for i in range(n)])


def gmsh_coordinates(element_type):
    _, dim, _, n, coords, _ = gmsh.model.mesh.getElementProperties(element_type)
    return np.asarray(coords, dtype=float).reshape(n, dim)


@pytest.mark.parametrize("element_type,vtk_class,name", TYPES)
def test_tables_match_gmsh_and_vtk(gmsh_session, element_type, vtk_class, name):
    assert np.array_equal(igaparam.node_coordinates(name, "gmsh"), gmsh_coordinates(element_type))
    assert np.array_equal(igaparam.node_coordinates(name, "vtk"), vtk_coordinates(vtk_class))


def vtk_twin(element_type, vtk_class, gmsh_cells):
    """The connectivity in VTK's order, by matching reference coordinates of gmsh and VTK."""
    g, v = gmsh_coordinates(element_type), vtk_coordinates(vtk_class)
    permutation = [int(np.flatnonzero((g == row).all(axis=1))[0]) for row in v]
    return gmsh_cells[:, permutation]


def gmsh_mesh(dim, element_type):
    """Nodes (n, 3) and cells in Gmsh's order of the current gmsh model, second order."""
    gmsh.model.mesh.generate(dim)
    gmsh.model.mesh.setOrder(2)
    tags, coords, _ = gmsh.model.mesh.getNodes()
    index = np.zeros(int(tags.max()) + 1, dtype=np.int64)
    index[tags.astype(np.int64)] = np.arange(len(tags))
    points = np.asarray(coords).reshape(-1, 3)
    _, node_tags = gmsh.model.mesh.getElementsByType(element_type)
    k = gmsh.model.mesh.getElementProperties(element_type)[3]
    cells = index[np.asarray(node_tags, dtype=np.int64)].reshape(-1, k)
    return points, cells


def disk_q9():
    gmsh.clear()
    gmsh.model.add("disk")
    disk = gmsh.model.occ.addDisk(0, 0, 0, 1, 1)
    gmsh.model.occ.synchronize()
    gmsh.option.setNumber("Mesh.MeshSizeMax", 0.25)
    gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 0)
    gmsh.model.mesh.setRecombine(2, disk)
    points, cells = gmsh_mesh(2, 10)
    boundary = np.flatnonzero(np.abs(np.hypot(points[:, 0], points[:, 1]) - 1) < 1e-9)
    moved = points[boundary] * [1.4, 0.8, 1.0]  # the circle becomes an ellipse
    return points, cells, boundary, moved


def box_h27():
    gmsh.clear()
    gmsh.model.add("box")
    gmsh.model.occ.addBox(0, 0, 0, 1, 1, 1)
    gmsh.model.occ.synchronize()
    gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 0)
    for _, curve in gmsh.model.getEntities(1):
        gmsh.model.mesh.setTransfiniteCurve(curve, 4)
    for _, surface in gmsh.model.getEntities(2):
        gmsh.model.mesh.setTransfiniteSurface(surface)
        gmsh.model.mesh.setRecombine(2, surface)
    gmsh.model.mesh.setTransfiniteVolume(1)
    gmsh.model.mesh.setRecombine(3, 1)
    points, cells = gmsh_mesh(3, 12)
    on_boundary = ((points < 1e-12) | (points > 1 - 1e-12)).any(axis=1)
    boundary = np.flatnonzero(on_boundary)
    moved = points[boundary].copy()
    top = moved[:, 2] > 1 - 1e-12
    moved[top, 2] += 0.45 * np.sin(np.pi * moved[top, 0]) * np.sin(np.pi * moved[top, 1])
    return points, cells, boundary, moved


def relocated(mesh, boundary, moved):
    with mesh:
        mask = np.zeros(mesh.node_count, dtype=np.uint8)
        mask[boundary] = 7 if mesh.dimension == 3 else 3
        mesh.set_fixed(mask)
        mesh.move_nodes(moved, indices=boundary)
        report = mesh.relocate(threads=1)
        return report, mesh.positions


@pytest.mark.parametrize("case,element_type,vtk_class,name", [
    (disk_q9, 10, "vtkBiQuadraticQuad", "quad9"),
    (box_h27, 12, "vtkTriQuadraticHexahedron", "hexahedron27"),
])
def test_gmsh_ordered_mesh_relocates_as_its_vtk_twin(gmsh_session, tmp_path, case, element_type, vtk_class, name):
    points, gmsh_cells, boundary, moved = case()
    vtk_cells = vtk_twin(element_type, vtk_class, gmsh_cells)
    # meshio's reading of the same mesh from a .msh file gives the same VTK-ordered cells.
    gmsh.write(str(tmp_path / "mesh.msh"))
    via_meshio = meshio.read(tmp_path / "mesh.msh")
    block = [b for b in via_meshio.cells if b.type == name][0]
    assert np.allclose(via_meshio.points[block.data], points[vtk_cells], rtol=0, atol=1e-12)

    with Mesh(name, points, gmsh_cells, order="gmsh") as mesh:
        assert mesh.order == "gmsh" and mesh.invalid_cell_count == 0
        assert np.array_equal(mesh.cells, gmsh_cells)
        assert np.array_equal(mesh.cells_in("vtk"), vtk_cells)
        assert np.array_equal(mesh.to_meshio().cells[0].data, vtk_cells)
    report_g, positions_g = relocated(Mesh(name, points, gmsh_cells, order="gmsh"), boundary, moved)
    report_v, positions_v = relocated(Mesh(name, points, vtk_cells), boundary, moved)
    assert report_v.invalid_before > 0 and report_v.invalid_after == 0
    assert np.array_equal(positions_g, positions_v)
    assert report_g.as_dict() | {"seconds": 0} == report_v.as_dict() | {"seconds": 0}

    if name == "quad9":
        # Gmsh's quadrilaterals list their nodes as VTK's do: the twins are one connectivity.
        assert np.array_equal(gmsh_cells, vtk_cells)
    else:
        with pytest.raises(IgaparamError) as error:
            Mesh(name, points, gmsh_cells)  # given as VTK by mistake
        assert error.value.status == Status.INVALID_MESH
        assert "node order" in error.value.message and "Gmsh" in error.value.message


def test_inverted_cells_are_refused_with_the_likely_cause():
    points = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=float)
    with pytest.raises(IgaparamError) as error:
        Mesh("quad", points, [[0, 3, 2, 1]])  # clockwise
    assert error.value.status == Status.INVALID_MESH
    assert "oriented" in error.value.message and "node order" in error.value.message
    with pytest.raises(ValueError):
        Mesh("Q4", points, [[0, 1, 2, 3]], order="abaqus")


def test_meshio_names_and_meshes(tmp_path):
    assert [igaparam.cell_type_code(n) for n in ("quad", "quad8", "quad9", "hexahedron", "hexahedron20",
                                                 "hexahedron27")] == [9, 23, 28, 12, 25, 29]
    airfoil = meshio.read(igaparam_root() / "tests" / "data" / "airfoil_0012_q9.vtu")
    # A boundary block of lines is left out; the point data constrain and move the nodes.
    airfoil.cells.append(meshio.CellBlock("line", np.array([[0, 1]])))
    with Mesh.from_meshio(airfoil) as mesh, Mesh.read_vtu(igaparam_root() / "tests" / "data" / "airfoil_0012_q9.vtu") as read:
        assert mesh.cell_type == 28 and mesh.order == "vtk"
        assert np.array_equal(mesh.positions, read.positions) and np.array_equal(mesh.fixed, read.fixed)
        back = mesh.to_meshio()
        assert np.array_equal(back.cells[0].data, airfoil.cells[0].data)
        assert np.array_equal(back.point_data["fixed_components"], read.fixed)
    with pytest.raises(ValueError):
        Mesh.from_meshio(meshio.Mesh(airfoil.points, [("triangle", np.array([[0, 1, 2]]))]))


def igaparam_root():
    from pathlib import Path

    return Path(__file__).resolve().parents[2]
