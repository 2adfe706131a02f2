#!/usr/bin/python3
"""Reads `nsbench run --fields` output back with a real VTK reader (meshio) and checks it
against the run: the .pvd's times are the run's written steps, and the fields agree with the
series (read from the same run) and with an independent recomputation from the read-back
displacements (the bar's stress, the block's Cauchy stress and strain energy, the springs'
forces and energy, bar-3d's hexahedra and their stress), for every kind of problem: bars,
blocks, 3D bars, a bar and a striker, point masses, a rigid disk, a spring chain and a ball
chain. series.csv is the same with and
without --fields.

    fields_test.py NSBENCH

Exit 77 (CTest: skipped) without meshio (Debian python3-meshio) or numpy."""
import csv
import json
import os
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

try:
    import meshio
    import numpy as np
except ImportError:
    print("SKIPPED: meshio or numpy absent (Debian python3-meshio)")
    sys.exit(77)

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


def close(a, b, rtol, atol=0.0):
    return bool(np.all(np.abs(np.asarray(a) - np.asarray(b)) <= atol + rtol * np.abs(np.asarray(b))))


def run_parts(nsbench, tmp, name, args):
    """The run's series and summary, and per written state (t, {file prefix: mesh}) from
    the .pvd (part 0 and, for a problem with elements and bodies, part 1)."""
    out, fields = os.path.join(tmp, name), os.path.join(tmp, name + "-fields")
    subprocess.run([nsbench, "run", "--out", out, "--fields", fields] + args, check=True, capture_output=True)
    with open(os.path.join(out, "series.csv"), "rb") as f:
        raw = f.read()
    plain = os.path.join(tmp, name + "-plain")
    cut = args.index("--fields-every")
    subprocess.run([nsbench, "run", "--out", plain] + args[:cut] + args[cut + 2:], check=True, capture_output=True)
    with open(os.path.join(plain, "series.csv"), "rb") as f:
        check(f.read() == raw, f"{name}: series.csv differs with --fields")
    rows = list(csv.DictReader(raw.decode().splitlines()))
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    series = {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
    collection = ET.parse(os.path.join(fields, "fields.pvd")).getroot().find("Collection")
    steps = {}
    for d in collection.findall("DataSet"):
        prefix = d.get("file").split("_")[0]
        steps.setdefault(float(d.get("timestep")), {})[prefix] = meshio.read(os.path.join(fields, d.get("file")))
    parts = sorted({d.get("part") + d.get("file").split("_")[0] for d in collection.findall("DataSet")})
    return series, summary, list(steps.items()), parts


def run(nsbench, tmp, name, args):
    """The same for a problem of elements only: per written state (t, mesh)."""
    series, summary, steps, parts = run_parts(nsbench, tmp, name, args)
    check(parts == ["0fields"], f"{name}: parts {parts}, expected fields_ alone")
    return series, summary, [(t, p["fields"]) for t, p in steps]


def written_rows(series, steps, every):
    """Series rows (one per step: --sample-every 1) of the written states: every `every`-th
    step, the first and the last."""
    n = len(series["t"])
    rows = list(range(0, n, every))
    if rows[-1] != n - 1:
        rows.append(n - 1)
    check(len(steps) == len(rows), f"{len(steps)} files written, expected {len(rows)}")
    check([t for t, _ in steps] == [series["t"][r] for r in rows][: len(steps)], "the .pvd's times are not the steps'")
    return rows


def test_bar(nsbench, tmp):
    E, L, N, every = 2.0, 1.0, 20, 4
    series, summary, steps = run(nsbench, tmp, "bar", [
        "--problem", "signorini-bar", "--integrator", "moreau-jean", "--dt", "0.01", "--t-end", "2.5",
        "--set", f"N={N}", "--set", f"E={E}", "--set", "g0=0.2", "--fields-every", str(every)])
    rows = written_rows(series, steps, every)
    h, rho_c = L / N, np.sqrt(E)
    mass = np.full(N + 1, h)
    mass[[0, -1]] *= 0.5
    for (t, mesh), r in zip(steps, rows):
        u, v = mesh.point_data["displacement"], mesh.point_data["velocity"]
        check(mesh.cells[0].type == "line" and len(mesh.points) == N + 1, "bar mesh: N + 1 points, lines")
        check(close(mesh.points[:, 0], np.arange(N + 1) * h, 1e-15, 1e-15), "bar points")
        check(np.all(u[:, 1:] == 0) and np.all(v[:, 1:] == 0), "bar fields have y, z components")
        check(u[0, 0] == series["u_contact"][r] and v[0, 0] == series["v_contact"][r], f"t = {t}: node 0 is not the series'")
        check(close(0.5 * np.dot(mass, v[:, 0] ** 2), series["kinetic"][r], 1e-12, 1e-300), f"t = {t}: kinetic energy")
        sigma = np.ravel(mesh.cell_data["sigma"][0])
        check(close(sigma, E * np.diff(u[:, 0]) / h, 1e-12, 1e-14), f"t = {t}: stress is not E du/dx")
        check(close(mesh.point_data["contact_impulse"][0, 0], series["impulse"][r], 0.0), f"t = {t}: contact impulse")
    check(steps[-1][0] == summary["t_final"], "the last file is not the final state")
    loaded = [np.min(np.ravel(m.cell_data["sigma"][0])) for _, m in steps]
    check(min(loaded) < -0.5 * rho_c, f"the bar is never compressed to about -rho c v0 ({min(loaded)})")
    check(max(np.max(m.point_data["contact_impulse"][:, 0]) for _, m in steps) > 0, "no contact impulse written")


def svk_cauchy_and_energy(X, u, lam, mu):
    """Cauchy stress (Gauss-point mean) and strain energy of one Q4 cell, SVK, plane strain."""
    g = 1.0 / np.sqrt(3.0)
    xi_n, eta_n = np.array([-1, 1, 1, -1]), np.array([-1, -1, 1, 1])
    sigma, W = np.zeros((2, 2)), 0.0
    for xi, eta in [(-g, -g), (g, -g), (g, g), (-g, g)]:
        dN = np.stack([0.25 * xi_n * (1 + eta_n * eta), 0.25 * eta_n * (1 + xi_n * xi)], axis=1)  # 4 x 2
        J = X.T @ dN
        grad = dN @ np.linalg.inv(J)
        F = np.eye(2) + u.T @ grad
        Eg = 0.5 * (F.T @ F - np.eye(2))
        S = lam * np.trace(Eg) * np.eye(2) + 2 * mu * Eg
        sigma += 0.25 * F @ S @ F.T / np.linalg.det(F)
        W += np.linalg.det(J) * (0.5 * lam * np.trace(Eg) ** 2 + mu * np.sum(Eg * Eg))
    return sigma, W


def test_block(nsbench, tmp):
    E, nu, rho, every = 1e6, 0.3, 1000.0, 25
    lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
    series, summary, steps = run(nsbench, tmp, "block", [
        "--problem", "block-2d", "--integrator", "cd-lagrange", "--dt", "2e-5", "--t-end", "0.03",
        "--set", "height=0.01", "--set", "vy=-2", "--fields-every", str(every)])
    rows = written_rows(series, steps, every)
    strained = 0.0
    for (t, mesh), r in zip(steps, rows):
        X, u, v = mesh.points[:, :2], mesh.point_data["displacement"][:, :2], mesh.point_data["velocity"][:, :2]
        cells = mesh.cells[0].data
        check(mesh.cells[0].type == "quad" and len(cells) == 32, "block mesh: 8 x 4 quads")
        # Lumped mass of a parallelogram Q4: a quarter of the cell's mass on each node.
        mass = np.zeros(len(X))
        W = 0.0
        for c, nodes in enumerate(cells):
            d1, d2 = X[nodes[2]] - X[nodes[0]], X[nodes[3]] - X[nodes[1]]
            mass[nodes] += 0.25 * rho * 0.5 * abs(d1[0] * d2[1] - d1[1] * d2[0])
            sigma, Wc = svk_cauchy_and_energy(X[nodes], u[nodes], lam, mu)
            W += Wc
            got = [np.ravel(mesh.cell_data[k][0])[c] for k in ("sigma_xx", "sigma_yy", "sigma_xy")]
            check(close(got, [sigma[0, 0], sigma[1, 1], sigma[0, 1]], 1e-9, 1e-9 * E * 1e-6),
                  f"t = {t}, cell {c}: Cauchy stress {got} against {sigma}")
        check(close(mass @ v, [series["px"][r], series["py"][r]], 1e-12, 1e-12), f"t = {t}: momentum")
        check(close(W, series["strain_energy"][r], 1e-9, 1e-12), f"t = {t}: strain energy {W} against {series['strain_energy'][r]}")
        strained = max(strained, W)
    check(strained > 0, "the block never deforms")
    check(steps[-1][0] == summary["t_final"], "the last file is not the final state")
    check(any(np.abs(m.point_data["contact_impulse"][:, 1]).max() > 0 for _, m in steps), "no floor impulse written")


def test_bar3d(nsbench, tmp):
    N, S, E, nu, every = 4, 2, 1.0, 0.3, 10
    lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
    series, summary, steps = run(nsbench, tmp, "bar-3d", [
        "--problem", "bar-3d", "--integrator", "cd-lagrange", "--dt", "0.005", "--t-end", "0.5",
        "--set", f"N={N}", "--set", f"N_side={S}", "--set", "lateral=free", "--fields-every", str(every)])
    rows = written_rows(series, steps, every)
    compressed = 0.0
    for (t, mesh), r in zip(steps, rows):
        X, u, v = mesh.points, mesh.point_data["displacement"], mesh.point_data["velocity"]
        cells = mesh.cells[0].data
        check(mesh.cells[0].type == "hexahedron" and len(cells) == N * S * S, "bar-3d mesh: N x N_side^2 hexahedra")
        check(len(X) == (N + 1) * (S + 1) ** 2 and close(X.max(axis=0), [1, 1, 1], 1e-15), "bar-3d: the unit cube's points")
        wall = X[:, 0] == 0
        check(close(np.mean(u[wall, 0]), series["u_contact"][r], 1e-13, 1e-15), f"t = {t}: wall face's mean u_x")
        mass = np.zeros(len(X))
        for c, nodes in enumerate(cells):
            P = X[nodes]
            e1, e3, e4 = P[1] - P[0], P[3] - P[0], P[4] - P[0]
            volume = np.dot(np.cross(e1, e3), e4)
            check(volume > 0, f"cell {c}: not in VTK's hexahedron order")
            mass[nodes] += volume / 8
            # Linear strain at the box's centre: grad N_a = (+-1 / 4 h, +-1 / 4 a, +-1 / 4 a).
            sign = np.sign(P - P.mean(axis=0))
            grad = sign / (4 * np.array([np.linalg.norm(e1), np.linalg.norm(e3), np.linalg.norm(e4)]))
            H = u[nodes].T @ grad
            eps = 0.5 * (H + H.T)
            sigma = lam * np.trace(eps) * np.eye(3) + 2 * mu * eps
            got = [np.ravel(mesh.cell_data[k][0])[c] for k in ("sigma_xx", "sigma_yy", "sigma_zz", "sigma_yz", "sigma_xz", "sigma_xy")]
            check(close(got, [sigma[0, 0], sigma[1, 1], sigma[2, 2], sigma[1, 2], sigma[0, 2], sigma[0, 1]], 1e-12, 1e-15),
                  f"t = {t}, cell {c}: stress {got}")
            compressed = min(compressed, sigma[0, 0])
        check(close(mass @ v[:, 0], series["momentum"][r], 1e-12, 1e-14), f"t = {t}: momentum along x")
    check(compressed < -0.1, f"bar-3d: the wall never compresses the bar ({compressed})")
    check(steps[-1][0] == summary["t_final"], "the last file is not the final state")


def flat(mesh, name):
    return np.ravel(mesh.point_data[name]) if name in mesh.point_data else None


def vertices(mesh, n, what):
    check(len(mesh.cells) == 1 and mesh.cells[0].type == "vertex" and len(mesh.cells[0].data) == n,
          f"{what}: {n} vertex cells")
    check(np.array_equal(np.ravel(mesh.cells[0].data), np.arange(n)), f"{what}: a point per vertex")
    check(not mesh.cell_data.keys() - {"body"}, f"{what}: cell arrays besides body on vertices: {list(mesh.cell_data)}")


def test_bouncing_mass(nsbench, tmp):
    every = 1  # every step: the impact steps are written
    series, summary, steps, parts = run_parts(nsbench, tmp, "bouncing-mass", [
        "--problem", "bouncing-mass", "--integrator", "moreau-jean", "--dt", "2e-3", "--t-end", "0.6",
        "--fields-every", str(every)])
    check(parts == ["0bodies"], f"bouncing-mass: parts {parts}")
    rows = written_rows(series, steps, every)
    for (t, p), r in zip(steps, rows):
        m = p["bodies"]
        vertices(m, 1, "bouncing-mass")
        check(np.array_equal(m.points, [[0, 0, 0]]), "bouncing-mass: the reference point is on the floor")
        u, v, lam = m.point_data["displacement"][0], m.point_data["velocity"][0], m.point_data["contact_impulse"][0]
        check(list(u) == [0, series["q"][r], 0] and list(v) == [0, series["v"][r], 0], f"t = {t}: height and velocity on y")
        check(u[1] == series["min_gap"][r], f"t = {t}: the height is the gap")
        check(lam[1] == series["impulse"][r] and lam[0] == 0, f"t = {t}: the floor impulse along +y")
        check(close(0.5 * v[1] ** 2, series["kinetic"][r], 1e-15, 1e-300), f"t = {t}: kinetic energy")
    check(steps[-1][0] == summary["t_final"], "the last file is not the final state")
    check(max(p["bodies"].point_data["contact_impulse"][0, 1] for _, p in steps) > 0, "bouncing-mass: no impact written")


def test_sliding_mass(nsbench, tmp):
    every = 25
    series, summary, steps, parts = run_parts(nsbench, tmp, "sliding-mass", [
        "--problem", "sliding-mass", "--integrator", "moreau-jean", "--dt", "2e-3", "--t-end", "0.5",
        "--fields-every", str(every)])
    check(parts == ["0bodies"], f"sliding-mass: parts {parts}")
    rows = written_rows(series, steps, every)
    for (t, p), r in zip(steps, rows):
        m = p["bodies"]
        vertices(m, 1, "sliding-mass")
        u, v, lam = m.point_data["displacement"][0], m.point_data["velocity"][0], m.point_data["contact_impulse"][0]
        check(u[0] == series["x"][r] and v[0] == series["v"][r], f"t = {t}: x and x' along the slope")
        check(lam[0] * v[0] <= 0, f"t = {t}: friction along the motion")
        check(u[1] == series["min_gap"][r], f"t = {t}: y is the height above the plane")
        # The series has |Lambda_T|; the friction impulse opposes the slip.
        check(lam[1] == series["impulse"][r] and abs(lam[0]) == series["tangential_impulse"][r], f"t = {t}: impulses")
    check(max(abs(p["bodies"].point_data["contact_impulse"][0, 0]) for _, p in steps) > 0, "sliding-mass: no friction")


def test_rolling_disk(nsbench, tmp):
    R, every = 0.1, 10
    series, summary, steps, parts = run_parts(nsbench, tmp, "rolling-disk", [
        "--problem", "rolling-disk", "--integrator", "moreau-jean", "--dt", "1e-3", "--t-end", "0.3",
        "--set", f"R={R}", "--set", "omega0=20", "--set", "h0=0.05", "--fields-every", str(every)])
    check(parts == ["0bodies"], f"rolling-disk: parts {parts}")
    rows = written_rows(series, steps, every)
    angles = []
    for (t, p), r in zip(steps, rows):
        m = p["bodies"]
        vertices(m, 1, "rolling-disk")
        check(np.array_equal(m.points, [[0, R, 0]]), "rolling-disk: the reference centre is at (0, R)")
        u, v = m.point_data["displacement"][0], m.point_data["velocity"][0]
        lam = m.point_data["contact_impulse"][0]
        theta, omega, n = flat(m, "angle")[0], flat(m, "angular_velocity")[0], m.point_data["orientation"][0]
        check(u[0] == series["x"][r] and u[1] == series["min_gap"][r] and u[2] == 0, f"t = {t}: centre at (x, y)")
        check(v[0] == series["v"][r] and omega == series["omega"][r], f"t = {t}: x' and theta'")
        check(close(v[0] + R * omega, series["slip"][r], 1e-14, 1e-14), f"t = {t}: slip x' + R theta'")
        check(flat(m, "radius")[0] == R, "rolling-disk: radius")
        check(close(n, [np.cos(theta), np.sin(theta), 0], 0, 1e-15), f"t = {t}: orientation (cos, sin) of the angle")
        # The series has |Lambda_T|; the friction impulse opposes the slip.
        check(lam[1] == series["impulse"][r] and abs(lam[0]) == series["tangential_impulse"][r], f"t = {t}: impulses")
        angles.append(theta)
    # The angle is the integral of the spin: trapezoid rule over the written states.
    times, omegas = [t for t, _ in steps], [flat(p["bodies"], "angular_velocity")[0] for _, p in steps]
    check(abs(angles[-1] - angles[0]) > 0.5, f"rolling-disk: the disk does not turn ({angles[-1]})")
    turned = np.trapz(omegas, times)
    check(close(angles[-1] - angles[0], turned, 0.05), f"rolling-disk: angle {angles[-1]} against the spin's integral {turned}")


def test_spring_chain(nsbench, tmp):
    n, k, m, ratio, every = 5, 100.0, 1.0, 2.0, 1  # every step: the wall impacts are written
    series, summary, steps, parts = run_parts(nsbench, tmp, "spring-chain", [
        "--problem", "spring-chain", "--integrator", "moreau-jean", "--dt", "5e-3", "--t-end", "0.5",
        "--set", f"n={n}", "--set", "wall=left", "--fields-every", str(every)])
    check(parts == ["0fields", "1bodies"], f"spring-chain: parts {parts}")
    rows = written_rows(series, steps, every)
    mass = np.array([m if i % 2 == 0 else ratio * m for i in range(n)])
    for (t, p), r in zip(steps, rows):
        lines, masses = p["fields"], p["bodies"]
        check(lines.cells[0].type == "line" and np.array_equal(lines.cells[0].data, [[i, i + 1] for i in range(n - 1)]),
              "spring-chain: a line between consecutive masses")
        check(np.array_equal(lines.points[:, 0], np.arange(n)), "spring-chain: masses 1 m apart")
        vertices(masses, n, "spring-chain")
        u, v = lines.point_data["displacement"][:, 0], lines.point_data["velocity"][:, 0]
        check(np.array_equal(masses.point_data["displacement"][:, 0], u), f"t = {t}: the two parts' masses disagree")
        force = np.ravel(lines.cell_data["spring_force"][0])
        check(close(force, k * np.diff(u), 1e-12, 1e-14), f"t = {t}: spring force k (u_i+1 - u_i)")
        check(close(np.sum(force ** 2) / (2 * k), series["potential"][r], 1e-12, 1e-14), f"t = {t}: spring energy")
        check(close(0.5 * mass @ v ** 2, series["kinetic"][r], 1e-12, 1e-14), f"t = {t}: kinetic energy")
        check(close(mass @ v, series["momentum"][r], 1e-12, 1e-14), f"t = {t}: momentum")
        check(masses.point_data["contact_impulse"][0, 0] == series["impulse"][r], f"t = {t}: the wall impulse on mass 0")
    check(max(p["bodies"].point_data["contact_impulse"][0, 0] for _, p in steps) > 0, "spring-chain: no wall impulse")


def test_ball_chain(nsbench, tmp):
    n, gap, every = 3, 0.01, 5
    series, summary, steps, parts = run_parts(nsbench, tmp, "ball-chain", [
        "--problem", "ball-chain", "--integrator", "moreau-jean", "--dt", "1e-3", "--t-end", "0.1",
        "--set", f"n={n}", "--set", f"gap={gap}", "--fields-every", str(every)])
    check(parts == ["0bodies"], f"ball-chain: parts {parts}")
    rows = written_rows(series, steps, every)
    for (t, p), r in zip(steps, rows):
        m = p["bodies"]
        vertices(m, n, "ball-chain")
        check(np.array_equal(np.ravel(m.cell_data["body"][0]), np.arange(n)), "ball-chain: a body per ball")
        check(close(m.points[:, 0], gap * np.arange(n), 1e-15, 1e-18), "ball-chain: balls gap apart")
        x = m.points[:, 0] + m.point_data["displacement"][:, 0]
        check(close(np.min(np.diff(x)), series["min_gap"][r], 1e-12, 1e-15), f"t = {t}: distances are the gaps")
        check(list(m.point_data["velocity"][:, 0]) == [series[f"v{i + 1}"][r] for i in range(n)], f"t = {t}: velocities")
    check(steps[-1][1]["bodies"].point_data["velocity"][-1, 0] > 0.5, "ball-chain: the last ball never moves")


def test_mass_on_bar(nsbench, tmp):
    N, every = 10, 5
    series, summary, steps, parts = run_parts(nsbench, tmp, "mass-on-bar", [
        "--problem", "mass-on-bar", "--integrator", "cd-lagrange", "--dt", "0.01", "--t-end", "3",
        "--set", f"N={N}", "--fields-every", str(every)])
    check(parts == ["0fields", "1bodies"], f"mass-on-bar: parts {parts}")
    rows = written_rows(series, steps, every)
    for (t, p), r in zip(steps, rows):
        bar, striker = p["fields"], p["bodies"]
        check(bar.cells[0].type == "line" and len(bar.points) == N + 1, "mass-on-bar: the bar's N + 1 nodes, lines")
        vertices(striker, 1, "mass-on-bar")
        check(np.array_equal(striker.points, [[0, 0, 0]]) and np.ravel(striker.cell_data["body"][0])[0] == 1,
              "mass-on-bar: the striker at the free end, body 1")
        check(not striker.point_data.keys() - {"displacement", "velocity", "contact_impulse"}, "mass-on-bar: striker arrays")
        u = bar.point_data["displacement"][:, 0]
        X, V = striker.point_data["displacement"][0, 0], striker.point_data["velocity"][0, 0]
        check(V == series["v_mass"][r], f"t = {t}: the striker's velocity")
        check(close(u[0] - X, series["min_gap"][r], 1e-12, 1e-15), f"t = {t}: the gap u(0) - X")
        check(np.ravel(bar.cell_data["sigma"][0]).size == N, "mass-on-bar: a stress per element")
        check(close(np.ravel(bar.cell_data["sigma"][0]), np.diff(u) * N, 1e-12, 1e-14), f"t = {t}: sigma = E du/dx")
        lam_bar, lam_striker = bar.point_data["contact_impulse"][0, 0], striker.point_data["contact_impulse"][0, 0]
        check(lam_bar == series["impulse"][r] and lam_striker == -lam_bar, f"t = {t}: the impulse and its reaction")
    check(max(p["bodies"].point_data["displacement"][0, 0] for _, p in steps) > 0, "mass-on-bar: the striker does not move")


def main():
    nsbench = sys.argv[1]
    with tempfile.TemporaryDirectory() as tmp:
        test_bar(nsbench, tmp)
        test_block(nsbench, tmp)
        test_bar3d(nsbench, tmp)
        test_bouncing_mass(nsbench, tmp)
        test_sliding_mass(nsbench, tmp)
        test_rolling_disk(nsbench, tmp)
        test_spring_chain(nsbench, tmp)
        test_ball_chain(nsbench, tmp)
        test_mass_on_bar(nsbench, tmp)
    for f in failures[:20]:
        print("FAILED:", f)
    print(f"fields_test: {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
