"""hpcplan.sph: the fluid stepped from Python equals hpcplan sph; its views are the engine's
memory, read-only."""
import json

import numpy as np
import pytest

import hpcplan
from conftest import TIMING_KEYS, cli_error, run_cli, without

WATER = dict(preset="water", scenario="dambreak", particles=300, seed=3)
SEED = dict(preset="seed", scenario="dynamic", particles=400, seed=5)


def argv(kw):
    return [x for k, v in kw.items() for x in ("--" + k.replace("_", "-"), str(v))]


@pytest.mark.parametrize("kw", [WATER, SEED], ids=["water", "seed"])
def test_stepping_equals_the_cli_byte_for_byte(kw, tmp_path):
    fluid = hpcplan.sph.Fluid(**kw, threads=2)
    for _ in range(3):
        assert fluid.step(frames=4)["stable"]
    fluid.checkpoint(tmp_path / "py.ck")
    run_cli("sph", *argv(kw), "--threads", "2", "--frames", "12",
            "--checkpoint", tmp_path / "cli.ck", "--output", tmp_path / "cli.json")
    assert (tmp_path / "py.ck").read_bytes() == (tmp_path / "cli.ck").read_bytes()
    cli = json.load(open(tmp_path / "cli.json"))
    assert without(fluid.report(), TIMING_KEYS) == without(cli, TIMING_KEYS)
    assert fluid.frame == 12 and np.isclose(fluid.time, 0.24)


def test_a_restart_continues_bit_for_bit(tmp_path):
    straight = hpcplan.sph.Fluid(**WATER)
    straight.step(frames=10)
    first = hpcplan.sph.Fluid(**WATER)
    first.step(frames=4)
    first.checkpoint(tmp_path / "half.ck")
    again = hpcplan.sph.Fluid.restart(tmp_path / "half.ck")
    assert again.restarted_at_frame == 4 and again.frame == 4
    again.step(frames=6)
    straight.checkpoint(tmp_path / "a.ck")
    again.checkpoint(tmp_path / "b.ck")
    assert (tmp_path / "a.ck").read_bytes() == (tmp_path / "b.ck").read_bytes()
    # and the CLI continues the module's checkpoint to the same state
    run_cli("sph", "--restart", tmp_path / "half.ck", "--frames", "10",
            "--checkpoint", tmp_path / "c.ck")
    assert (tmp_path / "c.ck").read_bytes() == (tmp_path / "a.ck").read_bytes()


def test_views_are_the_engines_memory_read_only():
    fluid = hpcplan.sph.Fluid(**WATER)
    fluid.step()
    x, v = fluid.positions, fluid.velocities
    n = fluid.size
    assert x.shape == (n, 3) and v.shape == (n, 3) and x.dtype == np.float64
    assert fluid.density.shape == (n,) and fluid.ids.dtype == np.uint32
    for view in (x, v, fluid.density, fluid.pressure, fluid.ids, fluid.wall):
        assert not view.flags.writeable and not view.flags.owndata
        with pytest.raises(ValueError):
            view[0] = 0
    # The same memory each time it is asked for, with no copy: x, y and z are three runs of
    # one block, so the (n, 3) view strides over them.
    assert np.shares_memory(x, fluid.positions)
    assert fluid.positions.__array_interface__["data"][0] == x.__array_interface__["data"][0]
    assert x.strides[0] == 8 and x.strides[1] >= 8 * n
    assert np.shares_memory(v, fluid.velocities) and not np.shares_memory(x, v)
    # ids are a permutation; the wall flags and the fluid count agree.
    assert sorted(fluid.ids.tolist()) == list(range(n))
    assert int((fluid.wall == 0).sum()) == fluid.fluid_count


def test_views_match_what_vtk_reads_back(tmp_path):
    # A plain import: the test command's machines have VTK (Debian's python3-vtk9, installed by
    # scripts/setup.sh), so a missing or broken VTK is a failure here, never a skip.
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
    fluid = hpcplan.sph.Fluid(**WATER)
    fluid.step(frames=3)
    fluid.write_vtk(tmp_path)
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(str(tmp_path / "fluid_000003.vtu"))
    reader.Update()
    grid = reader.GetOutput()
    points = vtk_to_numpy(grid.GetPoints().GetData())
    fluid_rows = fluid.wall == 0
    assert np.array_equal(points, fluid.positions[fluid_rows])
    assert np.array_equal(vtk_to_numpy(grid.GetPointData().GetArray("density")),
                          fluid.density[fluid_rows])
    assert np.array_equal(vtk_to_numpy(grid.GetPointData().GetArray("velocity")),
                          fluid.velocities[fluid_rows])
    fluid.step()
    fluid.write_vtk(tmp_path)
    assert (tmp_path / "fluid_000004.vtu").exists()
    assert "fluid_000003.vtu" in (tmp_path / "fluid.pvd").read_text()


def test_a_view_taken_before_a_step_stays_readable():
    fluid = hpcplan.sph.Fluid(**SEED)
    old = fluid.positions
    before = old.copy()
    for _ in range(5):
        fluid.step()
    assert np.isfinite(old).all()  # still allocated (an earlier ordering's storage)
    assert not np.array_equal(fluid.positions, before)
    del fluid  # the views keep the fluid alive
    assert np.isfinite(old.sum())


def test_the_result_does_not_depend_on_threads(tmp_path):
    for threads in (1, 2):
        f = hpcplan.sph.Fluid(**WATER, threads=threads)
        f.step(frames=5)
        f.checkpoint(tmp_path / f"t{threads}.ck")
    assert (tmp_path / "t1.ck").read_bytes() == (tmp_path / "t2.ck").read_bytes()


def test_probes_are_the_cli_front(tmp_path):
    fluid = hpcplan.sph.Fluid(**WATER)
    fluid.step(frames=5)
    run_cli("sph", *argv(WATER), "--frames", "5", "--front-csv", tmp_path / "front.csv")
    rows = np.loadtxt(tmp_path / "front.csv", delimiter=",", skiprows=1)
    probes = fluid.probes
    assert probes["columns"] == ["T", "Z"]
    assert np.allclose(probes["rows"], rows, atol=5e-7)


@pytest.mark.parametrize("kw,args", [
    (dict(preset="lava"), ["--preset", "lava"]),
    (dict(preset="seed", scenario="tank"), ["--preset", "seed", "--scenario", "tank"]),
    (dict(particles=0), ["--particles", "0"]),
    (dict(backend="opencl"), ["--backend", "opencl"]),
    (dict(particles=10_000_000, memory_mb=1), ["--particles", "10000000", "--memory-mb", "1"]),
])
def test_bad_input_is_a_value_error_with_the_cli_message(kw, args):
    message = cli_error("sph", *args, "--frames", "1")
    with pytest.raises(ValueError) as e:
        hpcplan.sph.Fluid(**kw)
    assert str(e.value) == message


def test_paths_and_frames_are_typed(tmp_path):
    fluid = hpcplan.sph.Fluid(**SEED)
    for call in (lambda: fluid.write_vtk(None), lambda: fluid.checkpoint(None),
                 lambda: hpcplan.sph.Fluid.restart(5)):
        with pytest.raises(TypeError, match="must be a str or a path"):
            call()
    with pytest.raises(TypeError, match="frames must be an integer"):
        fluid.step(True)
    with pytest.raises(TypeError, match="frames must be an integer"):
        fluid.step(1.5)
    with pytest.raises(ValueError, match="frames must be at least 1"):
        fluid.step(-1)
    assert not (tmp_path / "None").exists()
    message = cli_error("sph", "--frames", "1", "--checkpoint", tmp_path)
    with pytest.raises(ValueError) as e:
        fluid.checkpoint(tmp_path)
    assert str(e.value) == message
    message = cli_error("sph", "--frames", "1", "--restart", "")
    with pytest.raises(ValueError) as e:
        hpcplan.sph.Fluid.restart("")
    assert str(e.value) == message


def test_a_series_is_one_folder_and_a_frame_is_written_once(tmp_path):
    fluid = hpcplan.sph.Fluid(**SEED)
    fluid.write_vtk(tmp_path / "d")
    fluid.step()
    fluid.write_vtk(str(tmp_path / "d") + "/")
    fluid.write_vtk(tmp_path / "d")  # the same frame again: nothing new
    fluid.step()
    fluid.write_vtk(tmp_path / "d" / ".")
    pvd = (tmp_path / "d" / "fluid.pvd").read_text()
    for frame in range(3):
        assert pvd.count(f"fluid_{frame:06d}.vtu") == 1, pvd


def test_bad_checkpoints_are_refused(tmp_path):
    (tmp_path / "junk.ck").write_bytes(b"not a checkpoint")
    message = cli_error("sph", "--restart", tmp_path / "junk.ck")
    with pytest.raises(ValueError) as e:
        hpcplan.sph.Fluid.restart(tmp_path / "junk.ck")
    assert str(e.value) == message
    with pytest.raises(ValueError, match="frames must be at least 1"):
        hpcplan.sph.Fluid(**SEED).step(frames=0)
