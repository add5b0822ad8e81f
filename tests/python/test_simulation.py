"""rcdem.Simulation: stepping, numpy views without copies, measures, checkpoints, the GIL."""
import os
import threading

import numpy as np
import pytest

import rcdem


def address(a):
    return a.__array_interface__["data"][0]


def test_steps_advance_time(small):
    sim = rcdem.Simulation(small)
    sim.step(25)
    assert sim.steps == 25
    assert sim.time == pytest.approx(25 * sim.time_step, rel=1e-12)
    with pytest.raises(rcdem.Error):
        sim.step(-1)


def test_views_follow_the_state_without_a_copy(small):
    sim = rcdem.Simulation(small)
    position = sim.position
    assert position.shape == (sim.body_count, 3)
    assert not position.flags["OWNDATA"]
    before = position.copy()
    sim.step(50)
    assert address(sim.position) == address(position)  # the same memory, updated in place
    assert not np.array_equal(position, before)
    assert np.array_equal(position, sim.position)


def test_velocity_writes_through(small):
    sim = rcdem.Simulation(small)
    v = sim.velocity
    v[0] = [0.0, 0.0, 1.0]
    assert np.array_equal(sim.velocity[0], [0.0, 0.0, 1.0])
    x0 = sim.position[0].copy()
    sim.step(1)
    assert sim.position[0][2] > x0[2]  # the body moved with the velocity written from Python


def test_state_views_are_read_only(small):
    sim = rcdem.Simulation(small)
    for name in ("position", "force", "orientation", "point_damage", "mass"):
        with pytest.raises(ValueError):
            getattr(sim, name)[0] = 0.0


def test_point_damage_agrees_with_the_counts(small):
    sim = rcdem.Simulation(small)
    sim.step(400)
    d = sim.point_damage
    assert d.strides == (128,)  # read in place from the point records
    assert int(np.sum(d == 1.0)) == sim.broken_points
    assert int(np.sum((d > 0.0) & (d < 1.0))) == sim.damaged_points
    assert sim.damaged_points > 0
    begin = sim.contact_point_begin
    assert begin[-1] == len(d) and len(begin) == len(sim.contact_particles) + 1


def test_measures_and_energies(small):
    sim = rcdem.Simulation(small)
    sim.step(300)
    e = sim.energies
    assert e["external_work"] > 0
    assert e["balance_error"] < 1e-2
    plates = sim.plates
    assert set(plates) == {"bottom", "top"}
    assert sim.load == pytest.approx(plates["top"]["load"])
    assert sim.displacement == plates["top"]["displacement"] < 0
    assert sim.gauges == {}
    assert len(sim.node_axial_force) == 3  # the bar's four cylinders


def test_a_checkpoint_restores_bitwise(small, tmp_path):
    a = rcdem.Simulation(small)
    a.step(100)
    file = a.save_checkpoint(tmp_path)
    a.step(100)
    b = rcdem.Simulation(small)
    b.restore_checkpoint(file)
    assert b.steps == 100
    b.step(100)
    assert np.array_equal(a.position, b.position)
    assert np.array_equal(a.point_damage, b.point_damage)


def test_a_checkpoint_of_another_scenario_is_refused(small, tmp_path):
    a = rcdem.Simulation(small)
    file = a.save_checkpoint(tmp_path)
    other = rcdem.Simulation(small.set("solver.damping", 0.1))
    with pytest.raises(rcdem.Error):
        other.restore_checkpoint(file)


def test_stepping_releases_the_gil(small):
    sim = rcdem.Simulation(small)
    ticks = 0
    worker = threading.Thread(target=sim.step, args=(3000,))
    worker.start()
    while worker.is_alive():
        ticks += 1
    worker.join()
    assert sim.steps == 3000
    assert ticks > 1000  # Python ran while the steps did


def test_point_opening_and_snapshots_on_demand(small, tmp_path):
    sim = rcdem.Simulation(small)
    sim.step(400)
    opening, damage = sim.point_opening, sim.point_damage
    assert opening.strides == (128,) and opening.shape == damage.shape
    assert np.all(np.isfinite(opening))
    assert opening[damage > 0].max() > 0  # damaged points have opened (or slid)
    sim.write_snapshot(tmp_path / "snap")
    names = sorted(os.listdir(tmp_path / "snap" / "snapshots"))
    assert any(n.startswith("particles_000000400") for n in names)
    assert os.path.exists(tmp_path / "snap" / "particles.pvd")


def test_damaged_checkpoints_are_refused_never_read_by_hdf5(small, tmp_path):
    """600 random damages of an HDF5 checkpoint (bits flipped in its metadata or anywhere, bytes
    overwritten, cut short): each refused with rcdem.Error and the state left as it was. On the
    files of af4d780, before rcdem's header (size, CRC-32) was checked first, HDF5 1.10 crashed
    within 70 damages like these."""
    import random

    a = rcdem.Simulation(small)
    a.step(100)
    good = open(a.save_checkpoint(tmp_path), "rb").read()
    b = rcdem.Simulation(small)
    before = b.position.copy()
    rng = random.Random(46)
    bad = tmp_path / "damaged.h5"
    for k in range(600):
        d = bytearray(good)
        kind = k % 3
        if kind == 0:
            for _ in range(rng.randint(1, 4)):
                at = rng.randrange(4096) if rng.random() < 0.5 else rng.randrange(len(d))
                d[at] ^= 1 << rng.randrange(8)
        elif kind == 1:
            d = d[:rng.randrange(len(d))]
        else:
            at = rng.randrange(len(d) - 8)
            d[at:at + 8] = rng.randbytes(8)
        if d == good:
            continue
        bad.write_bytes(bytes(d))
        with pytest.raises(rcdem.Error, match="rejected"):
            b.restore_checkpoint(bad)
    assert b.steps == 0 and np.array_equal(b.position, before)


def test_a_checkpoint_reads_with_h5py_as_the_state(small, tmp_path):
    """The HDF5 checkpoint's arrays are the simulation's, bit for bit, with their units."""
    import h5py  # python3-h5py: scripts/setup.sh installs it
    sim = rcdem.Simulation(small)
    sim.step(150)
    with h5py.File(sim.save_checkpoint(tmp_path), "r") as f:
        assert f.attrs["step"] == 150 and f.attrs["time"] == sim.time
        assert f["bodies/position"].attrs["unit"] == "m"
        assert np.array_equal(f["bodies/position"][()], sim.position)
        assert np.array_equal(f["contacts.points/record.history.damage"][()], sim.point_damage)
