"""Forces: virtual work, closed forms, equilibrium of every link, invariance, the
textbook's turning-moment diagram and flywheel, and every bad input."""

from __future__ import annotations

import math
import random
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import chaingraph
from chaingraph import Chain, Joint, LinkMass, Load, Mechanism
from chaingraph.dynamics.equilibrium import UNIT_METRES
from chaingraph.naming.catalog import catalog_files, catalog_path

from ..conftest import run_cli
from .conftest import L, R, slider_crank

def engine(*, friction=None, load=-1000.0, masses=(), gravity=None, units="mm"):
    """The shared test engine with a piston load ``load`` (N along x, none if falsy)."""
    return slider_crank(*((Load("piston", "B", (load, 0.0)),) if load else ()),
                        friction=friction, masses=masses, gravity=gravity, units=units)


# -- closed forms ----------------------------------------------------------------------
@pytest.mark.parametrize("theta", [20.0, 60.0, 90.0, 135.0, 200.0, 300.0])
def test_slider_crank_with_a_piston_load_against_the_virtual_displacement(theta):
    f = chaingraph.forces(engine(), at=theta, static=True)
    t = math.radians(theta)
    r, l = R / 1000, L / 1000
    # x_B = r cos t + sqrt(l^2 - r^2 sin^2 t): the crank holds -F dx_B/dt
    dx = -r * math.sin(t) - r * r * math.sin(t) * math.cos(t) / math.sqrt(l * l - (r * math.sin(t)) ** 2)
    assert f.effort() == pytest.approx(1000.0 * dx, rel=1e-9)   # -F dx, F = -1000 N
    # the guide's normal force: the load times tan(phi), phi the rod's angle
    phi = math.asin(r * math.sin(t) / l)
    assert abs(f.reaction("S").normal) == pytest.approx(1000.0 * abs(math.tan(phi)), rel=1e-9)
    assert f.reaction("S").couple == pytest.approx(0.0, abs=1e-9)
    assert f.power_balance == pytest.approx(0.0, abs=1e-9)


@pytest.mark.parametrize("theta", [30.0, 60.0, 120.0, 240.0, 300.0])
@pytest.mark.parametrize("mu", [0.05, 0.3])
def test_friction_at_the_guide_by_hand_equilibrium_of_the_piston(theta, mu):
    f = chaingraph.forces(engine(friction=mu), at=theta, static=True)
    t = math.radians(theta)
    r, l = R / 1000, L / 1000
    # the piston (massless): the load P, the rod's thrust C along the rod, the guide's
    # normal reaction Ny and friction -mu |Ny| sign(v) along x
    ax, ay = r * math.cos(t), r * math.sin(t)
    bx = ax + math.sqrt(l * l - ay * ay)
    ux, uy = (bx - ax) / l, (0 - ay) / l              # from A to B: the thrust's direction
    v = -r * math.sin(t) - r * r * math.sin(t) * math.cos(t) / math.sqrt(l * l - ay * ay)
    s = math.copysign(1.0, v)
    # C ux - mu |Ny| s - 1000 = 0, C uy + Ny = 0; try both signs of Ny
    for sign in (1.0, -1.0):
        # |Ny| = sign * Ny, Ny = -C uy -> |Ny| = -sign C uy
        c = 1000.0 / (ux + mu * s * sign * uy)
        ny = -c * uy
        if ny * sign >= 0:
            break
    torque = -(ax * (-c * uy) - ay * (-c * ux))        # the crank holds the rod's push
    assert f.effort() == pytest.approx(torque, rel=1e-9)
    assert abs(f.reaction("S").normal) == pytest.approx(abs(ny), rel=1e-9)
    fx = f.reaction("S").force[0]                      # friction on the frame, along x
    assert fx == pytest.approx(mu * abs(ny) * s, rel=1e-9)


@pytest.mark.parametrize("theta", [30.0, 75.0, 110.0, 250.0])
def test_a_parallelogram_four_bar_holds_its_coupler_s_weight_by_m_g_r_cos_theta(theta):
    """Cranks of 80 mm, massless, a 4 kg coupler that translates: the crank holds
    m g r cos(theta) (counter-clockwise), the other crank carries the rest."""
    r, d = 80.0, 150.0
    bar = Chain("parallelogram", (
        Joint("O2", "R", ("frame", "crank"), at=(0.0, 0.0)),
        Joint("A", "R", ("crank", "coupler"), at=(0.0, r)),
        Joint("B", "R", ("coupler", "rocker"), at=(d, r)),
        Joint("O4", "R", ("rocker", "frame"), at=(d, 0.0))),
        units="mm", mechanism=Mechanism("frame", driver="crank"),
        masses=(LinkMass("coupler", 4.0, (d / 2, r + 20.0), 0.3),), gravity=(0.0, -9.81))
    f = chaingraph.forces(bar, at=theta, static=True)
    assert f.effort() == pytest.approx(4.0 * 9.81 * r / 1000 * math.cos(math.radians(theta)),
                                       rel=1e-9)
    # kinetostatic at a constant speed: the coupler's centre moves on a circle of r
    w = 12.0
    k = chaingraph.forces(bar, at=theta, omega=w)
    t = math.radians(theta)
    a = np.array([-math.cos(t), -math.sin(t)]) * r / 1000 * w * w       # centripetal
    v = np.array([-math.sin(t), math.cos(t)]) * r / 1000 * w
    weight = 4.0 * np.array([0.0, -9.81])
    assert k.effort() == pytest.approx(-float((weight - 4.0 * a) @ v) / w, rel=1e-9)


# -- virtual work over mechanisms of every kind ------------------------------------------
def with_masses(chain, seed):
    """The chain with masses whose centres sit on R joints (whose CSV columns follow
    both their links), gravity, and loads at R joints: the data for an independent
    power balance from the solver's columns."""
    rng = random.Random(seed)
    fixed = chain.mechanism.fixed
    masses, loads, centres = [], [], {}
    for link in chain.links:
        if link == fixed:
            continue
        pins = sorted(j.id for j in chain.joints if j.kind == "R" and link in j.links)
        if not pins:
            continue
        j = chain.joint(rng.choice(pins))
        masses.append(LinkMass(link, rng.uniform(0.5, 3.0), j.at, rng.uniform(1e-3, 5e-2)))
        centres[link] = j.id
        if rng.random() < 0.6:
            loads.append(Load(link, j.id, (rng.uniform(-100, 100), rng.uniform(-100, 100)),
                              rng.uniform(-5, 5)))
    return replace(chain, masses=tuple(masses), loads=tuple(loads), gravity=(0.0, -9.81),
                   units=chain.units if chain.units in UNIT_METRES else "mm"), centres


def power_from_columns(chain, centres, motion, k, static):
    """The power of gravity, loads and inertia at step k from the solver's CSV columns
    alone (the kinetic energy's rate from its velocities and accelerations)."""
    u = UNIT_METRES[chain.units]
    g = chain.gravity
    power = 0.0
    for mass in chain.masses:
        j, link = centres[mass.link], mass.link
        v = np.array([motion[f"vx:{j}"][k], motion[f"vy:{j}"][k]]) * u
        a = np.array([motion[f"ax:{j}"][k], motion[f"ay:{j}"][k]]) * u
        w, al = motion[f"omega:{link}"][k], motion[f"alpha:{link}"][k]
        power += mass.mass * (g[0] * v[0] + g[1] * v[1])
        if not static:
            power -= mass.mass * float(v @ a) + mass.inertia * w * al
    for load in chain.loads:
        v = np.array([motion[f"vx:{load.at}"][k], motion[f"vy:{load.at}"][k]]) * u
        power += load.force[0] * v[0] + load.force[1] * v[1] + load.torque * motion[f"omega:{load.on}"][k]
    return power


def input_rates(motion, plan):
    """Each input's rate (rad/s, or m/s) from the sweep, where the inputs move linearly
    together: the lead at omega, the others in proportion."""
    u = UNIT_METRES[plan.chain.units]
    lead = plan.inputs[plan.lead]
    per_second = motion.omega * (180 / math.pi if lead.kind == "R" else 1.0)
    out = {}
    for item in plan.inputs:
        if motion.inputs:
            col, lead_col = motion["input:" + item.joint], motion["input:" + lead.joint]
            slope = (col[-1] - col[0]) / (lead_col[-1] - lead_col[0])
        else:
            slope = 1.0
        rate = slope * per_second                        # the item's value units per s
        out[item.joint] = rate * (math.pi / 180 if item.kind == "R" else u)
    return out


def balanced(chain, centres, f, static):
    """How many steps of ``f`` keep the power balance from the solver's columns to
    1e-9 of the powers' size."""
    m = f.motion
    rates = input_rates(m, m.plan)
    checked = 0
    for k in range(m.steps + 1):
        efforts = [f[f"effort:{j}"][k] for j in f.inputs]
        if not all(np.isfinite(efforts)):
            continue
        p = power_from_columns(chain, centres, m, k, static)
        if not np.isfinite(p):              # a limit of the range: no rates there
            continue
        terms = [e * rates[j] for e, j in zip(efforts, f.inputs)]
        scale = abs(p) + sum(abs(t) for t in terms) + 1e-9
        assert abs(sum(terms) + p) <= 1e-9 * scale, (chain.name, k, sum(terms) + p, scale)
        checked += 1
    return checked


MECHANISMS = [p.stem for p in catalog_files()
              if (c := chaingraph.load(p)).mechanism is not None and c.has_pose
              and all(j.kind in ("R", "P") for j in c.joints)]


@pytest.mark.parametrize("name", MECHANISMS)
@pytest.mark.parametrize("static", [True, False])
def test_virtual_work_over_every_catalog_mechanism(name, static):
    chain, centres = with_masses(chaingraph.load(catalog_path(name)), seed=len(name))
    if not chain.masses:
        pytest.skip("no link with a turning pair to hang a mass on")
    f = chaingraph.forces(chain, steps=24, static=static, omega=3.0)
    assert balanced(chain, centres, f, static) >= 18


@pytest.mark.parametrize("static", [True, False])
def test_virtual_work_with_two_inputs_and_with_sliding_inputs(static):
    robot, centres = with_masses(chaingraph.load(Path(__file__).parents[2] / "examples"
                                                 / "five-bar-robot.toml"), seed=11)
    f = chaingraph.forces(robot, steps=16, static=static, omega=2.0)
    assert len(f.inputs) == 2 and balanced(robot, centres, f, static) >= 15
    boom, centres = with_masses(chaingraph.load(Path(__file__).parents[2] / "examples"
                                                / "hydraulic-boom.toml"), seed=12)
    f = chaingraph.forces(boom, steps=16, static=static, omega=20.0)
    assert balanced(boom, centres, f, static) >= 15


def test_virtual_work_over_atlas_mechanisms_with_sliding_pairs():
    """Six-link R/P chains of the atlas in their generic poses, every inversion driven
    by its natural input (a crank or a slide on the fixed link): Assur groups of every
    class the solver meets."""
    from chaingraph.structure.atlas import atlas_graphs
    from chaingraph.structure.atlas.illustrate import generic_pose, inversion_mechanism
    from chaingraph.structure.atlas.sliding import sliding_atlas
    from chaingraph.structure.isomorphism import automorphism_orbits
    done = 0
    for entry in sliding_atlas(atlas_graphs(6, 1), prismatic=range(4)):
        if entry.id % 10:
            continue
        chain = generic_pose(entry.chain(1))
        for links in automorphism_orbits(chain, oriented=False)[:2]:
            mech = inversion_mechanism(chain, links[0])
            if mech is None:
                continue
            loaded, centres = with_masses(mech, seed=entry.id)
            if not loaded.masses:
                continue
            try:
                f = chaingraph.forces(loaded, steps=12, static=entry.id % 2 == 0, omega=4.0)
            except chaingraph.UnboundedRangeError:
                continue
            assert balanced(loaded, centres, f, entry.id % 2 == 0) >= 8
            done += 1
    assert done >= 4


# -- equilibrium and Newton's third law ---------------------------------------------------
def test_every_link_is_in_equilibrium_with_the_reported_reactions():
    chain, centres = with_masses(chaingraph.load(catalog_path("stephenson-iii-mechanism")),
                                 seed=3)
    u = UNIT_METRES[chain.units]
    for theta in (10.0, 80.0, 170.0):
        f = chaingraph.forces(chain, at=theta, omega=2.0)
        state = chaingraph.instant_centres(chain, at=theta, omega=2.0).state
        sums = {link: np.zeros(3) for link in chain.links}
        for r in f.reactions:
            j = chain.joint(r.joint)
            q = np.array(state.positions[r.joint]) * u
            force = np.array(r.force)
            # on r.on the reported force; on the other link (two-link joints) its opposite
            sums[r.on] += [force[0], force[1], q[0] * force[1] - q[1] * force[0]]
            if len(j.links) == 2:
                other = r.by[0]
                sums[other] -= [force[0], force[1], q[0] * force[1] - q[1] * force[0]]
        for mass in chain.masses:
            q = np.array(state.positions[centres[mass.link]]) * u
            a = np.array(state.acceleration(centres[mass.link])) * u
            w = np.array(chain.gravity) * mass.mass - mass.mass * a
            link = state.links[mass.link]
            sums[mass.link] += [w[0], w[1], q[0] * w[1] - q[1] * w[0] - mass.inertia * link.alpha]
        for load in chain.loads:
            q = np.array(state.positions[load.at]) * u
            F = np.array(load.force)
            sums[load.on] += [F[0], F[1], q[0] * F[1] - q[1] * F[0] + load.torque]
        driver = chain.mechanism.driver
        sums[driver][2] += f.effort()
        scale = max(abs(r.force[0]) + abs(r.force[1]) for r in f.reactions)
        for link, s in sums.items():
            if link != chain.mechanism.fixed:
                assert np.abs(s[:2]).max() <= 1e-9 * scale and abs(s[2]) <= 1e-9 * scale, (link, s)


def test_a_multiple_joint_reports_the_force_on_each_link_summing_to_zero():
    chain, _ = with_masses(chaingraph.load(catalog_path("crank-rocker-with-slider")), seed=5)
    multiple = [j for j in chain.joints if len(j.links) > 2]
    assert multiple
    f = chaingraph.forces(chain, steps=12)
    for j in multiple:
        fx = sum(f[f"Fx:{j.id}:{link}"] for link in j.links)
        fy = sum(f[f"Fy:{j.id}:{link}"] for link in j.links)
        assert np.allclose(fx, 0, atol=1e-9) and np.allclose(fy, 0, atol=1e-9)


# -- invariance -------------------------------------------------------------------------
def turned(chain, deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))

    def rot(p):
        return None if p is None else (c * p[0] - s * p[1], s * p[0] + c * p[1])
    joints = tuple(replace(j, at=rot(j.at), axis=None if j.axis is None else j.axis + deg)
                   for j in chain.joints)
    masses = tuple(replace(m, centre=rot(m.centre)) for m in chain.masses)
    loads = tuple(replace(x, force=rot(x.force)) for x in chain.loads)
    return replace(chain, joints=joints, masses=masses, loads=loads,
                   gravity=rot(chain.gravity))


def test_rotating_the_drawing_with_gravity_renaming_and_scaling_change_nothing_else():
    base = engine(friction=0.2, masses=(LinkMass("rod", 1.5, None, 0.01),
                                        LinkMass("piston", 2.0, None, 0.0)),
                  gravity=(0.0, -9.81))
    ref = chaingraph.forces(base, at=60.0, omega=50.0)
    # rotated by 37 degrees: the crank's angle turns with it
    rot = chaingraph.forces(turned(base, 37.0), at=97.0, omega=50.0)
    assert rot.effort() == pytest.approx(ref.effort(), rel=1e-9)
    assert rot.reaction("S").normal == pytest.approx(ref.reaction("S").normal, rel=1e-9)
    for joint in "OAB":
        assert math.hypot(*rot.reaction(joint).force) == pytest.approx(
            math.hypot(*ref.reaction(joint).force), rel=1e-9)
    # renamed links and joints
    names = {"frame": "ground", "crank": "arm", "rod": "link", "piston": "slider"}
    ids = {"O": "J1", "A": "J2", "B": "J3", "S": "J4"}
    renamed = replace(
        base, joints=tuple(replace(j, id=ids[j.id], links=tuple(names[x] for x in j.links))
                           for j in base.joints),
        masses=tuple(replace(m, link=names[m.link]) for m in base.masses),
        loads=tuple(replace(x, on=names[x.on], at=ids[x.at]) for x in base.loads),
        mechanism=Mechanism("ground", driver="arm"))
    ren = chaingraph.forces(renamed, at=60.0, omega=50.0)
    assert ren.effort() == pytest.approx(ref.effort(), rel=1e-12)
    assert ren.reaction("J4").normal == pytest.approx(ref.reaction("S").normal, rel=1e-12)
    # the same drawing in metres: the same forces
    metres = replace(base, units="m", joints=tuple(
        replace(j, at=(j.at[0] / 1000, j.at[1] / 1000)) for j in base.joints))
    same = chaingraph.forces(metres, at=60.0, omega=50.0)
    assert same.effort() == pytest.approx(ref.effort(), rel=1e-9)
    # lengths scaled by 2 (static, a load only): reactions the same, the torque doubled
    static = engine()
    big = replace(static, joints=tuple(replace(j, at=(2 * j.at[0], 2 * j.at[1]))
                                       for j in static.joints))
    one, two = (chaingraph.forces(c, at=60.0, static=True) for c in (static, big))
    assert two.effort() == pytest.approx(2 * one.effort(), rel=1e-9)
    assert two.reaction("S").normal == pytest.approx(one.reaction("S").normal, rel=1e-9)


# -- the textbook's engine: turning-moment diagram and flywheel ----------------------------
def test_single_cylinder_engine_turning_moment_and_flywheel_by_the_textbook_method():
    """Reciprocating mass m_r, rod massless, steady gas-free inertia: the textbook's
    crank effort T = F_p r (sin t + sin 2t / (2 sqrt(n^2 - sin^2 t))) with the piston
    effort F_p = P - m_r a_p, with the exact a_p (the textbook's cos t + cos 2t / n is
    its first order); the flywheel I = dE / (w^2 Cs)."""
    m_r, w, load = 2.5, 150.0, -1500.0
    ch = engine(load=load, masses=(LinkMass("piston", m_r, None, 0.0),))
    f = chaingraph.forces(ch, omega=w, steps=720, speed_fluctuation=0.03)
    theta = np.radians(f["theta"])
    r, l = R / 1000, L / 1000
    s = np.sin(theta)
    root = np.sqrt(l * l - r * r * s * s)
    dx = -r * s - r * r * s * np.cos(theta) / root                 # dx/dtheta
    c = np.cos(theta)
    ddx = -r * c - r * r * np.cos(2 * theta) / root - r ** 4 * s * s * c * c / root ** 3
    a_p = ddx * w * w
    piston = load - m_r * a_p                                        # along +x on the piston
    torque = -piston * dx                                            # the crank holds it
    assert np.allclose(f["effort:O"], torque, rtol=1e-9, atol=1e-9 * np.abs(torque).max())
    # the energy swing of the turning-moment diagram about its mean, by the test's own
    # integration (the trapezoid rule on the same grid)
    u = theta - theta[0]
    work = np.concatenate([[0.0], np.cumsum(0.5 * (torque[1:] + torque[:-1]) * np.diff(u))])
    mean = work[-1] / (2 * math.pi)
    swing = work - mean * u
    de = swing.max() - swing.min()
    assert f.summary.energy_fluctuation == pytest.approx(de, rel=1e-4)
    assert f.summary.flywheel.inertia == pytest.approx(de / (w * w * 0.03), rel=1e-4)
    assert f.summary.efforts["O"].mean == pytest.approx(mean, abs=1e-6 * abs(torque).max())


# -- dead centres and inputs of every kind -------------------------------------------------
def test_driven_by_its_piston_the_effort_at_a_dead_centre_is_unbounded():
    ch = replace(engine(), mechanism=Mechanism("frame", inputs=(chaingraph.Input("S"),)))
    far = math.sqrt(L * L - R * R)
    # the outer dead centre: the piston at R + L from O, a slide of R + L - far
    f = chaingraph.forces(ch, at=R + L - far, static=True)
    assert f.effort() is None and "dead centre" in " ".join(f.notes)
    text = chaingraph.forces(ch, static=True, steps=10).to_csv()
    assert "nan" in text


def test_a_piston_input_needs_the_load_back_and_a_crank_load_by_virtual_work():
    ch = replace(engine(load=None), mechanism=Mechanism("frame", inputs=(chaingraph.Input("S"),)),
                 loads=(Load("crank", None, None, 20.0),))
    f = chaingraph.forces(ch, at=-30.0, static=True)
    st = chaingraph.instant_centres(ch, at=-30.0).state
    w = st.links["crank"].omega                      # rad/s per mm/s of slide
    # effort (N) x 1 mm/s = -(20 N m x w): a slide of 1 mm/s = 0.001 m/s
    assert f.effort() * 1e-3 == pytest.approx(-20.0 * w, rel=1e-9)


# -- bad input ----------------------------------------------------------------------------
GOOD = """
name = "e"
units = "mm"
joints = [{id = "O", kind = "R", links = ["frame", "crank"], at = [0, 0]},
          {id = "A", kind = "R", links = ["crank", "rod"], at = [0, 50]},
          {id = "B", kind = "R", links = ["rod", "piston"], at = [193.6491673, 0]},
          {id = "S", kind = "P", links = ["frame", "piston"], at = [193.6491673, 0], axis = 0%s}]
mechanism = {fixed = "frame", driver = "crank"}
%s
"""


@pytest.mark.parametrize("joint_extra, tables, words", [
    ("", '[[links]]\nname = "rod"\nmass = -1.0', "'mass' must be a finite number of kg >= 0"),
    ("", '[[links]]\nname = "rod"\nmass = nan', "key 'mass': must be a finite number"),
    ("", '[[links]]\nname = "rod"\nmass = 1.0\ninertia = -2.0', "'inertia' must be"),
    ("", '[[links]]\nname = "wheel"\nmass = 1.0', "names no link of the chain: 'wheel'"),
    ("", '[[loads]]\non = "wheel"\nat = "A"\nforce = [1, 0]', "'on' names no link"),
    ("", '[[loads]]\non = "piston"\nat = "A"\nforce = [1, 0]', "'at' is not on link 'piston'"),
    ("", '[[loads]]\non = "piston"\nat = "Q"\nforce = [1, 0]', "'at' names no joint or point"),
    ("", '[[loads]]\non = "piston"\nforce = [1, 0]', "needs 'at'"),
    ("", '[[loads]]\non = "piston"\nat = "B"', "needs a 'force'"),
    ("", '[forces]\ngravity = [0, "down"]', "'gravity' must be two finite numbers"),
    (", friction = -0.1", '[[links]]\nname = "rod"\nmass = 1.0', "'friction' must be"),
])
def test_bad_masses_and_loads_get_one_line_and_exit_2(tmp_path, joint_extra, tables, words):
    path = tmp_path / "bad.toml"
    path.write_text(GOOD % (joint_extra, tables))
    status, out, err = run_cli("forces", path, "--at", "30")
    assert status == 2 and words in err and "Traceback" not in err and err.count("\n") == 1


def test_friction_on_a_turning_pair_is_refused(tmp_path):
    text = (GOOD % ("", '[[links]]\nname = "rod"\nmass = 1.0')).replace(
        'at = [0, 50]}', 'at = [0, 50], friction = 0.2}')
    path = tmp_path / "bad.toml"
    path.write_text(text)
    status, out, err = run_cli("forces", path)
    assert status == 2 and "'friction' is only for P joints" in err


def test_forces_need_units_masses_and_a_mechanism_the_solver_runs(tmp_path):
    path = tmp_path / "nounits.toml"
    path.write_text((GOOD % ("", '[[links]]\nname = "rod"\nmass = 1.0')).replace('units = "mm"\n', ""))
    status, out, err = run_cli("forces", path)
    assert status == 2 and "forces need the file's length 'units'" in err
    path = tmp_path / "nomass.toml"
    path.write_text(GOOD % ("", ""))
    status, out, err = run_cli("forces", path)
    assert status == 2 and "no masses, loads or gravity" in err
    path = tmp_path / "far.toml"
    path.write_text(GOOD % ("", '[[links]]\nname = "rod"\nmass = 1.0'))
    status, out, err = run_cli("forces", path, "--at", "30", "--csv", tmp_path / "x.csv")
    assert status == 2 and "--csv is for a sweep" in err
    status, out, err = run_cli("forces", path, "--speed-fluctuation", "5")
    assert status == 2 and "--speed-fluctuation" in err


# -- the command line ---------------------------------------------------------------------
def test_forces_on_the_command_line_json_and_csv(tmp_path):
    path = tmp_path / "engine.toml"
    path.write_text(GOOD % (", friction = 0.1", '[[links]]\nname = "rod"\nmass = 1.5\n'
                                                'inertia = 0.01\n[[loads]]\non = "piston"\n'
                                                'at = "B"\nforce = [-1000, 0]'))
    status, out, err = run_cli("forces", path, "--at", "60", "--json")
    assert status == 0
    import json
    d = json.loads(out)
    assert set(d) >= {"name", "fixed", "inputs", "at", "static", "joints", "efforts",
                      "power_balance"}
    assert [j["joint"] for j in d["joints"]] == ["O", "A", "B", "S"]
    s = next(j for j in d["joints"] if j["joint"] == "S")
    assert s["on"] == "frame" and s["by"] == "piston" and s["normal"] is not None
    assert d["efforts"][0]["unit"] == "N m" and abs(d["power_balance"]) < 1e-9
    csv_path = tmp_path / "f.csv"
    status, out, err = run_cli("forces", path, "--steps", "36", "--csv", csv_path, "--json",
                               "--omega", "100", "--speed-fluctuation", "0.02")
    assert status == 0
    d = json.loads(out)
    assert set(d["summary"]) >= {"efforts", "reactions", "energy_fluctuation", "flywheel"}
    header = csv_path.read_text().splitlines()[0].split(",")
    assert header == ["theta", "Fx:O", "Fy:O", "Fx:A", "Fy:A", "Fx:B", "Fy:B", "Fx:S", "Fy:S",
                      "N:S", "M:S", "effort:O", "shaking:Fx", "shaking:Fy", "shaking:M"]
    status, out, err = run_cli("forces", path, "--at", "60")
    assert status == 0 and "effort O" in out and "power balance" in out


def test_the_free_bodies_and_the_turning_moment_diagram(tmp_path):
    import xml.etree.ElementTree as ET
    path = catalog_path("shaper-crank-and-slotted-lever")
    status, out, err = run_cli("forces", path, "--omega", "5", "--draw", tmp_path / "fb.svg",
                               "--plot", tmp_path / "tm.svg", "--steps", "72")
    assert status == 0, err
    root = ET.fromstring((tmp_path / "fb.svg").read_text())
    ns = {"s": "http://www.w3.org/2000/svg"}
    # five moving links, each with its name; every force an arrow with its head
    labels = [t.text for t in root.findall(".//s:text[@class='label']", ns)]
    assert labels == ["crank", "block", "slotted lever", "link", "ram"]
    arrows = root.findall(".//s:line[@class='force']", ns)
    # (12: the cutting force against the ram's motion leaves the guide G's reaction and
    # the ram's inertia force too small to draw at the first pose)
    assert len(arrows) == len(root.findall(".//s:polygon[@class='arrowhead']", ns)) >= 12
    assert any(a.get("data-force") == "load" for a in arrows)
    assert "<svg" in (tmp_path / "tm.svg").read_text()
    status, out, err = run_cli("forces", path, "--draw", tmp_path / "fb.png")
    assert status == 2 and "give a .svg file" in err


def test_the_arrows_are_the_forces_to_one_scale():
    from chaingraph.drawing.forces import forces_on, free_body_shapes
    f = chaingraph.forces(engine(masses=(LinkMass("rod", 40.0),), gravity=(0.0, -9.81)),
                          at=60.0, static=True)
    shapes, _ = free_body_shapes(f)
    pin = next(s.radius for s in shapes if s.cls == "pin")
    lines = [s for s in shapes if s.cls == "force"]
    forces = [x for link in ("crank", "rod", "piston") for x in forces_on(f, link)]
    assert len(lines) == len(forces) >= 8           # the weight too: nothing too small here
    ratios = []
    for s, (_, _, _, force) in zip(lines, forces):
        (x0, y0), (x1, y1) = s.points
        # the shaft stops at the arrowhead's base, 2 x 1.6 pin radii short of the point
        ratios.append((math.hypot(x1 - x0, y1 - y0) + 3.2 * pin) / math.hypot(*force))
        # and points the force's way
        assert (x1 - x0) * force[0] + (y1 - y0) * force[1] > 0
    assert max(ratios) == pytest.approx(min(ratios), rel=1e-9)


def test_the_report_has_a_forces_section_for_the_engines(tmp_path):
    from chaingraph.report.build import build_report
    build_report([catalog_path("reciprocating-engine")], tmp_path, progress=None, steps=36,
                 frames=6)
    page = (tmp_path / "reciprocating-engine.html").read_text()
    assert "<h2>Forces</h2>" in page and "energy fluctuation" in page
    assert (tmp_path / "img" / "reciprocating-engine-free-bodies.svg").exists()
    assert (tmp_path / "img" / "reciprocating-engine-turning-moment.svg").exists()
    # the shaking force's polar diagram, shown on the page
    assert (tmp_path / "img" / "reciprocating-engine-shaking.svg").exists()
    assert "img/reciprocating-engine-shaking.svg" in page and "largest shaking force" in page


def test_notebook_displays_and_renaming_carries_masses_and_loads():
    from chaingraph.drawing.notebook import DISPLAYS
    f = chaingraph.forces(engine(masses=(LinkMass("rod", 1.0),)), at=45.0)
    assert "<svg" in DISPLAYS["PoseForces"][1](f)
    s = chaingraph.forces(engine(), steps=24)
    assert "<svg" in DISPLAYS["SweepForces"][1](s)
    renamed = engine(masses=(LinkMass("rod", 1.0),)).relabelled(
        links={"rod": "connecting rod", "piston": "crosshead"}, joints={"B": "gudgeon"})
    assert renamed.masses[0].link == "connecting rod"
    assert (renamed.loads[0].on, renamed.loads[0].at) == ("crosshead", "gudgeon")
    assert chaingraph.forces(renamed, at=45.0).effort() == pytest.approx(
        chaingraph.forces(engine(masses=(LinkMass("rod", 1.0),)), at=45.0).effort(), rel=1e-12)


def test_the_force_polygon_of_each_dyad_closes(tmp_path):
    from chaingraph.drawing.forces import force_polygon_shapes
    chain = chaingraph.load(catalog_path("whitworth-quick-return-with-ram"))
    f = chaingraph.forces(chain, at=60.0, omega=8.0)
    shapes, _ = force_polygon_shapes(f)
    labels = [s.text for s in shapes if s.cls == "label"]
    assert labels and all(t.startswith("dyad ") for t in labels)
    # each panel's arrows run head to tail and come back to where they began: the
    # dyad's last force ends at its first's start, and so does the dashed reaction
    panels = []
    for s in shapes:
        if s.cls == "label":
            panels.append({"start": None, "tips": []})
        elif s.cls == "force" and panels[-1]["start"] is None:
            panels[-1]["start"] = s.points[0]
        elif s.cls == "arrowhead":
            panels[-1]["tips"].append(s.points[0])
    assert panels
    for p in panels:
        assert len(p["tips"]) >= 4
        assert math.dist(p["tips"][-2], p["start"]) <= 1e-9
        assert math.dist(p["tips"][-1], p["start"]) <= 1e-9
    status, out, err = run_cli("forces", catalog_path("reciprocating-engine"), "--at", "60",
                               "--polygon", tmp_path / "p.svg")
    assert status == 0 and 'class="arrowhead"' in (tmp_path / "p.svg").read_text()


def test_forces_of_a_chain_the_solver_refuses_and_the_frame_of_a_sweep(tmp_path):
    chain = replace(chaingraph.load(catalog_path("four-bar-chain")),
                    masses=(LinkMass("coupler", 1.0),))
    with pytest.raises(chaingraph.MechanismError):
        chaingraph.forces(chain)                       # no mechanism: refused, exit 2
    path = tmp_path / "chain.toml"
    path.write_text(chaingraph.dumps(chain))
    status, out, err = run_cli("forces", path)
    assert status == 2 and err.count("\n") == 1
    # beyond its range: the analysis fails, exit 1 with the range
    watt = replace(chaingraph.load(catalog_path("watts-indicator-mechanism")),
                   masses=(LinkMass("lever", 0.2),), gravity=(0.0, -9.81))
    path = tmp_path / "watt.toml"
    path.write_text(chaingraph.dumps(watt))
    status, out, err = run_cli("forces", path, "--at", "10")
    assert status == 1 and "can turn only from" in err and "Traceback" not in err
    import pandas                     # the test extra installs it
    frame = chaingraph.forces(engine(), steps=8).to_frame()
    assert isinstance(frame, pandas.DataFrame) and list(frame.columns)[-4:] == [
        "effort:O", "shaking:Fx", "shaking:Fy", "shaking:M"]


# -- issue 36: the solved state taken as it is; typed arrays, the CSV a view -------------
def _count_pose_solves(monkeypatch):
    """Count the evaluations the pose solver is asked for (every path of the kinematics
    goes through tracking.evaluate, which sweep.py calls)."""
    import chaingraph.kinematics.sweep as sweep
    calls = []
    evaluate = sweep.evaluate

    def counted(*args, **kwargs):
        calls.append(args[1])
        return evaluate(*args, **kwargs)
    monkeypatch.setattr(sweep, "evaluate", counted)
    return calls


@pytest.mark.parametrize("at, inputs", [(60.0, None), (-20.0, ["S"])])
def test_forces_at_one_value_solves_its_pose_once(monkeypatch, at, inputs):
    # (a steady load: the catalog's gas force and mean torque need the whole cycle)
    chain = replace(chaingraph.load(catalog_path("reciprocating-engine")), name="once",
                    loads=(Load("crosshead", "B", (-2000.0, 0.0)),))
    calls = _count_pose_solves(monkeypatch)
    f = chaingraph.forces(chain, at=at, inputs=inputs)
    # one evaluation continued from the drawn pose to the value asked for (the anchor,
    # the drawn pose itself, needs none for this chain of dyads)
    assert len(calls) == 1 and f.at == (at,)
    # and the forces are those of that pose: the crank's effort balances the power
    assert f.power_balance == pytest.approx(0.0, abs=1e-9)


def test_the_command_line_draws_the_free_bodies_without_solving_again(monkeypatch, tmp_path):
    path = catalog_path("reciprocating-engine")
    chaingraph.forces(chaingraph.load(path), steps=12)   # its plan and cycle cached
    calls = _count_pose_solves(monkeypatch)
    assert run_cli("forces", path, "--at", "60", "--draw", tmp_path / "a.svg",
                   "--polygon", tmp_path / "p.svg")[0] == 0
    assert len(calls) == 1                               # the pose, solved once
    del calls[:]
    chaingraph.forces(chaingraph.load(path), steps=12)
    swept = len(calls)                  # its steps, and its summary's grid
    del calls[:]
    assert run_cli("forces", path, "--steps", "12", "--draw", tmp_path / "b.svg",
                   "--polygon", tmp_path / "q.svg")[0] == 0
    # the sweep's own evaluations, and nothing more for the drawings of its first pose
    assert len(calls) == swept >= 1 and len(calls[0]) >= 13
    assert "<svg" in (tmp_path / "b.svg").read_text()


def test_a_sweep_s_pose_is_the_pose_forces_at_that_step():
    chain = chaingraph.load(catalog_path("shaper-crank-and-slotted-lever"))
    sweep = chaingraph.forces(chain, steps=24, omega=5.0)
    for k in (0, 7, 24):
        from_sweep, solved = sweep.pose(k), chaingraph.forces(
            chain, at=sweep.motion.input_values(k), omega=5.0)
        assert from_sweep.at == solved.at and from_sweep.inputs == solved.inputs
        scale = max(abs(v) for r in solved.reactions for v in r.force)
        for a, b in zip(from_sweep.reactions, solved.reactions):
            assert (a.joint, a.on, a.by) == (b.joint, b.on, b.by)
            assert a.force == pytest.approx(b.force, abs=1e-9 * scale)
        assert from_sweep.effort() == pytest.approx(solved.effort(), rel=1e-9)
        assert from_sweep.points.keys() == solved.points.keys()
        for name, p in solved.points.items():
            assert from_sweep.points[name] == pytest.approx(p, abs=1e-9)
        assert [(a.link, a.what) for a in from_sweep.applied] == \
            [(a.link, a.what) for a in solved.applied]


def test_a_sweep_s_forces_are_typed_arrays_and_its_csv_their_view():
    chain = chaingraph.load(catalog_path("reciprocating-engine"))
    s = chaingraph.forces(chain, steps=12)
    header = s.to_csv().splitlines()[0].split(",")
    assert header == list(s.columns) == ["theta", "Fx:O", "Fy:O", "Fx:A", "Fy:A", "Fx:B",
                                         "Fy:B", "Fx:S", "Fy:S", "N:S", "M:S", "effort:O",
                                         "shaking:Fx", "shaking:Fy", "shaking:M"]
    assert s.shaking is not None and s["shaking:M"] is s.shaking.moment
    rod_on_crank, guide = s.reaction("A"), s.reaction("S")
    assert (rod_on_crank.on, rod_on_crank.by) == ("crank", ("connecting rod",))
    assert rod_on_crank.fx is s["Fx:A"] and guide.normal is s["N:S"]
    assert rod_on_crank.normal is None and guide.couple is s["M:S"]
    effort = s.effort()
    assert effort.joint == "O" and effort.unit == "N m" and effort.value is s["effort:O"]
    # each step's largest reaction is the summary's, from the typed arrays
    assert s.summary.reactions["A"] == pytest.approx(
        float(np.nanmax(np.hypot(rod_on_crank.fx, rod_on_crank.fy))), rel=1e-12)
    # a multiple joint: a reaction per link, by the others, each named in its columns
    chain, _ = with_masses(chaingraph.load(catalog_path("crank-rocker-with-slider")), seed=5)
    j = next(j for j in chain.joints if len(j.links) > 2)
    f = chaingraph.forces(chain, steps=6)
    on_j = [r for r in f.reactions if r.joint == j.id]
    assert [r.on for r in on_j] == list(j.links)
    assert all(set(r.by) == set(j.links) - {r.on} for r in on_j)
    assert all(r.fx is f[f"Fx:{j.id}:{r.on}"] for r in on_j)
