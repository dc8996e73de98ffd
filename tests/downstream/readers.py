"""Downstream readers load regolith's output (run by tests/downstream_readers.rs from the
folder holding post/): OVITO reads the text dump and the gzip dump series with their
columns, VTK reads the custom/vtk polydata and its bounding box, and the numbers agree."""
import sys

from ovito.io import import_file
import vtk

text = import_file("post/t.dump")
assert text.source.num_frames == 3, text.source.num_frames
frame = text.compute(2)
assert frame.particles.count == 36
for key in ["Particle Identifier", "Particle Type", "Position", "Velocity", "Radius", "c_s[1]"]:
    assert key in frame.particles.keys(), (key, list(frame.particles.keys()))
assert frame.attributes["Timestep"] == 20

packed = import_file("post/g*.dump.gz")
assert packed.source.num_frames == 3, packed.source.num_frames
gz = packed.compute(2)
assert gz.particles.count == 36
ids_text = list(frame.particles["Particle Identifier"])
ids_gz = list(gz.particles["Particle Identifier"])
pos_text = {i: tuple(p) for i, p in zip(ids_text, frame.particles["Position"])}
for i, p in zip(ids_gz, gz.particles["Position"]):
    assert pos_text[i] == tuple(p), (i, pos_text[i], tuple(p))

single = import_file("post/all.dump.gz", multiple_frames=True)
assert single.source.num_frames == 3, single.source.num_frames
assert single.compute(2).attributes["Timestep"] == 20

reader = vtk.vtkGenericDataObjectReader()
reader.SetFileName("post/d20.vtk")
reader.Update()
poly = reader.GetOutput()
assert poly.IsA("vtkPolyData")
assert poly.GetNumberOfPoints() == 36 and poly.GetNumberOfVerts() == 36
data = poly.GetPointData()
arrays = {data.GetArrayName(k): data.GetArray(k) for k in range(data.GetNumberOfArrays())}
for name, comps in [("id", 1), ("v", 3), ("radius", 1), ("c_s[1-3]", 3), ("k", 1)]:
    assert name in arrays and arrays[name].GetNumberOfComponents() == comps, (name, list(arrays))
vel_text = {i: tuple(v) for i, v in zip(ids_text, frame.particles["Velocity"])}
for n in range(36):
    atom = int(arrays["id"].GetValue(n))
    v = arrays["v"].GetTuple3(n)
    # the text dump prints 6 significant digits (%g), VTK 11
    assert all(abs(a - b) <= 1e-5 * abs(b) + 1e-12 for a, b in zip(v, vel_text[atom])), (atom, v)

box = vtk.vtkGenericDataObjectReader()
box.SetFileName("post/dboundingBox_20.vtk")
box.Update()
assert box.GetOutput().IsA("vtkRectilinearGrid")
assert box.GetOutput().GetBounds()[1] == 1.0
for name, cls, box_name in [
    ("post/p20.vtp", vtk.vtkXMLPolyDataReader, "post/pboundingBox_20.vtr"),
    ("post/u20.vtu", vtk.vtkXMLUnstructuredGridReader, "post/uboundingBox_20.vtr"),
]:
    xml = cls()
    xml.SetFileName(name)
    xml.Update()
    grid = xml.GetOutput()
    assert grid.GetNumberOfPoints() == 36 and grid.GetNumberOfCells() == 36, name
    pdata = grid.GetPointData()
    ids = pdata.GetArray("id")
    vel = pdata.GetArray("v")
    assert vel.GetNumberOfComponents() == 3, name
    for n in range(36):
        assert vel.GetTuple3(n) == arrays["v"].GetTuple3(n) or all(
            abs(a - b) <= 1e-9 * abs(b) + 1e-15 for a, b in zip(vel.GetTuple3(n), arrays["v"].GetTuple3(n))
        ), (name, n)
        assert ids.GetValue(n) == arrays["id"].GetValue(n)
    box_xml = vtk.vtkXMLRectilinearGridReader()
    box_xml.SetFileName(box_name)
    box_xml.Update()
    assert box_xml.GetOutput().GetBounds()[1] == 1.0, box_name
print("downstream readers: ok")
