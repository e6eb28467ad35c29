# ---------------------------------------------------------------------------------------
# The model below is generic: it reads SCENE (above) and nothing else.
# ---------------------------------------------------------------------------------------
import os
import sys

import openseespy.opensees as ops

GROUND, BODY, NODE, ORIGIN = 1, 2, 3, 4  # tags of the oscillator's nodes


def series(tag, signal, factor):
    """A timeSeries for the excitation signal, times `factor`."""
    if signal["shape"] == "sine-pulse":
        end = signal["cycles"] * 2.0 * math.pi / signal["omega"]
        ops.timeSeries("Trig", tag, 0.0, end, 2.0 * math.pi / signal["omega"],
                       "-factor", factor * signal["amplitude"])
    elif "values" in signal:
        ops.timeSeries("Path", tag, "-dt", signal["dt"], "-values", *signal["values"],
                       "-factor", factor)
    else:
        here = os.path.dirname(os.path.abspath(__file__))
        ops.timeSeries("Path", tag, "-dt", signal["dt"],
                       "-filePath", os.path.join(here, signal["file"]), "-factor", factor)


def sine_value(signal, t):
    end = signal["cycles"] * 2.0 * math.pi / signal["omega"]
    return signal["amplitude"] * math.sin(signal["omega"] * t) if 0.0 <= t <= end else 0.0


def friction_material(tag, k, mu, normal):
    """Elastic-perfectly-plastic slider: yields at mu*normal (elastic when mu is inf)."""
    if math.isinf(mu):
        ops.uniaxialMaterial("Elastic", tag, k)
    else:
        ops.uniaxialMaterial("ElasticPP", tag, k, mu * normal / k)


def build_oscillator(m):
    """PEPO: mass on a zeroLength ElasticPP slider (double: through a massless node)."""
    ops.model("basic", "-ndm", 1, "-ndf", 1)
    ops.node(GROUND, 0.0)
    ops.fix(GROUND, 1)
    ops.node(BODY, 0.0)
    ops.mass(BODY, m["mass"])
    normal = m["mass"] * m["gravity"]
    if m.get("double"):
        lower, upper = m["double"]
        ops.node(NODE, 0.0)
        friction_material(1, lower["kx"], lower["mu"], normal)
        friction_material(2, upper["kx"], upper["mu"], normal)
        ops.element("zeroLength", 1, GROUND, NODE, "-mat", 1, "-dir", 1)
        ops.element("zeroLength", 2, NODE, BODY, "-mat", 2, "-dir", 1)
    else:
        c = m["contact"]
        friction_material(1, c["kx"], c["mu"], normal)
        ops.element("zeroLength", 1, GROUND, BODY, "-mat", 1, "-dir", 1)
    if m["damping"] > 0.0:
        ops.uniaxialMaterial("Viscous", 9, m["damping"], 1.0)
        ops.element("zeroLength", 9, GROUND, BODY, "-mat", 9, "-dir", 1)
    return [BODY]


def rocking_tags(m):
    n = len(m["supports"])
    return {"cm": 100, "origin": 200, "base": [201 + i for i in range(n)],
            "ground": [301 + i for i in range(n)]}


def build_rocking(m):
    """RPEPO: point mass and rotational inertia at the CM, rigid links to the supports."""
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    t = rocking_tags(m)
    h = m["cm_height"]
    ops.node(t["cm"], 0.0, h)
    ops.mass(t["cm"], m["mass"], m["mass"], m["rotational_inertia"])
    ops.node(t["origin"], 0.0, 0.0)
    links = m["links"]
    if links != "rigid":
        ops.geomTransf(links, 1)
    stiff = 1.0e6 * m["contact"]["kz"] * h  # E of the stiff beams (A = I = 1): EA/L >> kz
    beams = [1000]

    def link(retained, constrained):
        """Rigid link (small-rotation constraint) or a stiff beam with the chosen transformation."""
        if links == "rigid":
            ops.rigidLink("beam", retained, constrained)
        else:
            beams[0] += 1
            ops.element("elasticBeamColumn", beams[0], retained, constrained, 1.0, stiff, 1.0, 1)

    link(t["cm"], t["origin"])
    contact = m["contact"]  # single arrangement only (the exporter refuses the double)
    ops.frictionModel("Coulomb", 1, contact["mu"])
    ops.uniaxialMaterial("Elastic", 1, contact["kz"])  # tension = uplift (zero force)
    ops.uniaxialMaterial("Elastic", 2, 0.0)            # no moment at a support
    for i, x in enumerate(m["supports"]):
        g, b = t["ground"][i], t["base"][i]
        ops.node(g, x, 0.0)
        ops.fix(g, 1, 1, 1)
        ops.node(b, x, 0.0)
        link(t["cm"], b)
        ops.element("flatSliderBearing", 1 + i, g, b, 1, contact["kx"], "-P", 1, "-Mz", 2,
                    "-orient", 0.0, 1.0, 0.0, -1.0, 0.0, 0.0)
    return [t["cm"]]


def apply_gravity(m, cm):
    """Static gravity first (linear: every support in compression), then held constant."""
    ops.timeSeries("Linear", 90)
    ops.pattern("Plain", 90, 90)
    ops.load(cm, 0.0, -m["mass"] * m["gravity"], 0.0)
    ops.constraints("Transformation")
    ops.numberer("RCM")
    ops.system("UmfPack")
    ops.test("NormDispIncr", 1.0e-12, 50)
    ops.algorithm("Newton")
    ops.integrator("LoadControl", 0.1)
    ops.analysis("Static")
    if ops.analyze(10) != 0:
        sys.exit("opensees: static gravity analysis failed")
    ops.loadConst("-time", 0.0)
    ops.wipeAnalysis()


def apply_excitation(scene, massive, rocking):
    """Mass acceleration: force M·a(t). Ground acceleration: UniformExcitation. Ground
    displacement (sine pulse): relative coordinates, force −M·ẍg(t) plus the ground
    velocity's jumps as jumps of the relative velocity (returned as (time, size))."""
    ex = scene["excitation"]
    m = scene["model"]
    kind = ex["kind"]
    if kind == "none":
        return []
    if kind == "ground-acceleration":
        series(1, ex["signal"], 1.0)
        ops.pattern("UniformExcitation", 1, 1, "-accel", 1)
        return []
    sig = ex["signal"]
    if kind == "mass-acceleration":
        series(1, sig, 1.0)
    else:  # ground displacement A sin θt: −ẍg = A θ² sin θt
        series(1, sig, sig["omega"] ** 2)
    ops.pattern("Plain", 1, 1)
    for node in massive:
        ops.load(node, *([m["mass"], 0.0, 0.0] if rocking else [m["mass"]]))
    if kind == "ground-displacement":
        a, th = sig["amplitude"], sig["omega"]
        end = sig["cycles"] * 2.0 * math.pi / th
        return [(0.0, -a * th), (end, a * th * math.cos(th * end))]
    return []


def velocity_jump(node, size):
    ops.setNodeVel(node, 1, ops.nodeVel(node, 1) + size, "-commit")


def oscillator_row(scene, t):
    m = scene["model"]
    u = ops.nodeDisp(BODY, 1)
    force = ops.eleResponse(1, "basicForces")[0]
    k = (m["double"][0] if m.get("double") else m["contact"])["kx"]
    slip_node = NODE if m.get("double") else BODY
    row = [t, u, ops.nodeDisp(slip_node, 1) - force / k, force, ops.nodeVel(BODY, 1)]
    if m.get("double"):
        row.append(ops.nodeDisp(NODE, 1))
    return row


def rocking_row(scene, t, cm_z0):
    m = scene["model"]
    tags = rocking_tags(m)
    ops.reactions()
    k = m["contact"]["kx"]
    shear = normal = contacts = 0.0
    uplift, slips = 0.0, []
    for i in range(len(m["supports"])):
        g = tags["ground"][i]
        top = tags["base"][i]
        fx, fz = ops.nodeReaction(g, 1), ops.nodeReaction(g, 2)
        tangential = -fx  # the support's force on the structure, resisting +x
        shear += tangential
        normal += fz
        if fz > 0.0:
            contacts += 1.0
        slips.append(ops.nodeDisp(top, 1) - tangential / k)
        uplift = max(uplift, ops.nodeDisp(top, 2))
    cm = tags["cm"]
    return [t, ops.nodeDisp(tags["origin"], 1), sum(slips) / len(slips),
            max(slips) - min(slips), shear, ops.nodeVel(cm, 1),
            ops.nodeDisp(cm, 1), ops.nodeDisp(cm, 2) - cm_z0, ops.nodeDisp(cm, 3),
            max(uplift, 0.0), contacts, shear, normal]


OSCILLATOR_HEADER = ["time [s]", "rel_disp [m]", "slide [m]", "resistance [N]", "vel [m/s]"]
ROCKING_HEADER = ["time [s]", "rel_disp [m]", "slide [m]", "slide_spread [m]",
                  "resistance [N]", "vel [m/s]", "cm_x [m]", "cm_z [m]", "rotation [rad]",
                  "uplift [m]", "contacts", "base_shear [N]", "normal [N]"]


def transient_analysis(run):
    """Newmark average acceleration, full Newton, displacement-increment test."""
    ops.constraints("Transformation")
    ops.numberer("RCM")
    ops.system("UmfPack")
    ops.test("NormDispIncr", run["tolerance"], 100)
    ops.algorithm("Newton")
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")


def step(dt):
    """One step; on failure retry with smaller substeps and other algorithms."""
    if ops.analyze(1, dt) == 0:
        return True
    for algorithm in (["KrylovNewton"], ["NewtonLineSearch"]):
        ops.algorithm(*algorithm)
        ok = ops.analyze(1, dt) == 0
        ops.algorithm("Newton")
        if ok:
            return True
    for parts in (4, 16):
        if ops.analyze(parts, dt / parts) == 0:
            return True
    return False


def main(out_path):
    scene = SCENE
    m = scene["model"]
    rocking = m["kind"] == "rocking-body"
    ops.wipe()
    massive = build_rocking(m) if rocking else build_oscillator(m)
    cm_z0 = 0.0
    if rocking:
        apply_gravity(m, massive[0])
        cm_z0 = ops.nodeDisp(massive[0], 2)
    jumps = apply_excitation(scene, massive, rocking)
    run = scene["run"]
    dt, steps, every = run["dt"], run["steps"], run["output_every"]
    transient_analysis(run)
    header = ROCKING_HEADER if rocking else OSCILLATOR_HEADER
    if not rocking and m.get("double"):
        header = header + ["node_disp [m]"]
    if scene["excitation"]["kind"] == "ground-displacement":
        header = header + ["ground_disp [m]"]
    rows = []
    pending = sorted(jumps)

    def record(t):
        row = rocking_row(scene, t, cm_z0) if rocking else oscillator_row(scene, t)
        if scene["excitation"]["kind"] == "ground-displacement":
            row.append(sine_value(scene["excitation"]["signal"], t))
        rows.append(row)

    for n in range(steps + 1):
        t = n * dt
        jumped = False
        while pending and pending[0][0] <= t + 0.5 * dt:
            for node in massive:
                velocity_jump(node, pending[0][1])
            pending.pop(0)
            jumped = True
        if jumped:  # the integrator keeps its own velocities: rebuild it from the nodes
            ops.wipeAnalysis()
            transient_analysis(run)
        if n % every == 0:
            record(t)
        if n == steps:
            break
        if not step(dt):
            sys.exit(f"opensees: the analysis did not converge at t = {t + dt:.6g} s")
    lines = [",".join(header)] + [",".join(repr(float(v)) for v in row) for row in rows]
    text = "\n".join(lines) + "\n"
    if out_path == "-":
        sys.stdout.write(text)
        return
    tmp = out_path + ".part"  # written whole, then renamed: never a half-written file
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(tmp, out_path)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), SCENE["run"]["results"]))
