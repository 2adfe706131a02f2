#!/usr/bin/python3
"""Reads `nsbench run --fields` output back with a real VTK reader (meshio) and checks it
against the run: the .pvd's times are the run's written steps, and the fields agree with the
series (read from the same run) and with an independent recomputation from the read-back
displacements (the bar's stress, the block's Cauchy stress and strain energy).

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


def run(nsbench, tmp, name, args):
    out, fields = os.path.join(tmp, name), os.path.join(tmp, name + "-fields")
    subprocess.run([nsbench, "run", "--out", out, "--fields", fields] + args, check=True, capture_output=True)
    with open(os.path.join(out, "series.csv")) as f:
        rows = list(csv.DictReader(f))
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    series = {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
    collection = ET.parse(os.path.join(fields, "fields.pvd")).getroot().find("Collection")
    steps = [(float(d.get("timestep")), os.path.join(fields, d.get("file"))) for d in collection.findall("DataSet")]
    return series, summary, [(t, meshio.read(path)) for t, path in steps]


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


def main():
    nsbench = sys.argv[1]
    with tempfile.TemporaryDirectory() as tmp:
        test_bar(nsbench, tmp)
        test_block(nsbench, tmp)
    for f in failures[:20]:
        print("FAILED:", f)
    print(f"fields_test: {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
