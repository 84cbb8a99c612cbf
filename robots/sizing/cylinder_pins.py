"""Scan lift-cylinder pin positions for robots/pipe_arm.urdf (robots/README.md, "Drives").

Pins are from the lift pivot (0, 1.2 m in the world): the base pin in the base frame (x along
the catwalk, y up), the arm pin in the arm's hub frame (x along the arm, y across it). The base
pin stays inside the base's 1.2 m box (x in -0.6..0.6, y in -1.2..0 from the pivot).

For each pair it finds the pin-to-pin length over the joint's range (-0.05..1.62 rad), sizes
stroke and closed length around it with a margin at each end, and keeps the pairs that a real
cylinder can be (closed length >= stroke + the cylinder's dead length) and whose moment arm
ds/dtheta over 0..90 deg is >= 0.35 m. Prints the best by the smallest moment arm, then the
chosen design's numbers.

Run: python3 robots/sizing/cylinder_pins.py
"""

import numpy as np

G = 9.80665
MARGIN_M = 0.03  # clearance to each end of the stroke over the joint's range
DEAD_LENGTH_M = 0.55  # closed length minus stroke: clevis eyes, piston, rod guide (180 bore)
JOINT = (-0.05, 1.62)  # lift joint limits, rad


def length_and_arm(base, arm, theta):
    c, s = np.cos(theta), np.sin(theta)
    px, py = c * arm[0] - s * arm[1], s * arm[0] + c * arm[1]
    dx, dy = px - base[0], py - base[1]
    length = np.hypot(dx, dy)
    return length, (px * dy - py * dx) / length


def gravity_moment_n_m(string_kg):
    """Moment about the pivot of the arm and what it carries, horizontal, N*m."""
    box = 0.5 * 0.25 - 0.475 * 0.225  # 500 x 250 x 12.5 mm section, m^2
    arm_kg = 7850 * box * 9.0
    moment = arm_kg * 4.5 + 180 * 8.2 + 96 * 9.0 + 24 * 9.0 + string_kg * 9.0
    return G * moment, arm_kg


def scan():
    theta_path = np.linspace(0.0, np.pi / 2, 91)
    theta_joint = np.linspace(*JOINT, 200)
    rows = []
    for bx in np.arange(-0.6, 0.61, 0.05):
        for by in np.arange(-1.2, -0.09, 0.05):
            for ax in np.arange(0.4, 2.01, 0.05):
                for ay in np.arange(-0.7, -0.249, 0.05):
                    base, arm = (bx, by), (ax, ay)
                    s, _ = length_and_arm(base, arm, theta_joint)
                    lo, hi = s.min(), s.max()
                    stroke = hi - lo + 2 * MARGIN_M
                    closed = lo - MARGIN_M
                    if closed < stroke + DEAD_LENGTH_M:
                        continue
                    _, r = length_and_arm(base, arm, theta_path)
                    rows.append((r.min(), r[0], bx, by, ax, ay, closed, stroke))
    rows.sort(reverse=True)
    return rows


def report(base, arm, bore, rod, closed, stroke, dead_volumes_m3):
    """The design's lengths, levers, holding pressures and oil spring (robots/README.md)."""
    a1 = np.pi / 4 * bore**2
    a2 = np.pi / 4 * (bore**2 - rod**2)
    print(f"\nbase pin {base}, arm pin {arm}, bore/rod {bore * 1e3:.0f}/{rod * 1e3:.0f} mm")
    print(f"A1 = {a1:.5f} m^2, A2 = {a2:.5f} m^2, ratio {a1 / a2:.2f}")
    for deg in (np.degrees(JOINT[0]), 0, 30, 45, 60, 90, np.degrees(JOINT[1])):
        s, r = length_and_arm(base, arm, np.radians(deg))
        print(f"  {deg:6.1f} deg: s = {s:.4f} m (extension {s - closed:+.4f} of {stroke}), ds/dtheta = {r:.4f} m")
    _, r = length_and_arm(base, arm, np.linspace(0, np.pi / 2, 901))
    print(f"  moment arm over 0..90: {r.min():.4f} .. {r.max():.4f} m")
    s_joint, _ = length_and_arm(base, arm, np.linspace(*JOINT, 2001))
    print(f"  over the joint's range: s {s_joint.min():.4f} .. {s_joint.max():.4f}; "
          f"margins {s_joint.min() - closed:.4f} (closed), {closed + stroke - s_joint.max():.4f} (stroke)")
    print(f"  closed - stroke = {closed - stroke:.3f} m (the cylinder's dead length)")
    ps, pt = 21e6, 0.5e6
    for name, kg in (("no string", 0.0), ("2-7/8 (121 kg)", 121.0), ("4-1/2 (200 kg)", 200.2)):
        torque, _ = gravity_moment_n_m(kg)
        force = torque / length_and_arm(base, arm, 0.0)[1]
        p1 = (force + a2 * (ps + pt)) / (a1 + a2)
        print(f"  {name}: T = {torque / 1e3:.1f} kN*m, F = {force / 1e3:.1f} kN, "
              f"p1 = {p1 / 1e6:.2f} MPa, p2 = {(ps + pt - p1) / 1e6:.2f} MPa (ps {ps / 1e6}, pt {pt / 1e6} MPa)")
    # Dead volumes: 25 mm of bore at each end of the stroke, plus 2 m of 1 in hose (1.0 L).
    hose = 2.0 * np.pi / 4 * 0.0254**2
    print(f"  dead volume estimate: cap {(a1 * 0.025 + hose) * 1e3:.2f} L, rod {(a2 * 0.025 + hose) * 1e3:.2f} L")
    v1, v2 = dead_volumes_m3
    beta = 1.2e9
    for deg in (0.0, 45.0, 90.0):
        s, r = length_and_arm(base, arm, np.radians(deg))
        x = s - closed
        V1, V2 = v1 + a1 * x, v2 + a2 * (stroke - x)
        k = beta * (a1**2 / V1 + a2**2 / V2)
        print(f"  {deg:4.0f} deg: V1 = {V1 * 1e3:.2f} L, V2 = {V2 * 1e3:.2f} L, k_oil = {k:.4e} N/m, "
              f"hub k = k r^2 = {k * r * r:.4e} N*m/rad")


if __name__ == "__main__":
    torque, arm_kg = gravity_moment_n_m(0.0)
    print(f"arm {arm_kg:.1f} kg; empty moment {torque / 1e3:.2f} kN*m")
    rows = scan()
    print(f"{len(rows)} feasible pairs; best by the smallest moment arm over 0..90 deg:")
    for row in rows[:15]:
        print("  r_min {:.3f} r0 {:.3f}  base ({:+.2f}, {:+.2f})  arm ({:.2f}, {:+.2f})  closed {:.3f} stroke {:.3f}".format(*row))
    # The design in robots/pipe_arm.urdf: the best pair, round lengths, ISO 3320 180/100 mm.
    report((0.40, -0.50), (2.00, -0.70), 0.180, 0.100, 1.56, 1.00, (1.65e-3, 1.45e-3))
