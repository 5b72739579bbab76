"""The figures of docs/theory-guide.md, drawn from closed forms with numpy and matplotlib.

Run from the repository root: ``python docs/images/make_figures.py``. It writes
``serial.png``, ``bifurcation.png``, ``five_bar.png`` and ``three_rpr.png`` next to itself.
Nothing here uses mechsing: each figure is the textbook geometry of its example (lengths in
metres, angles in radians).
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

HERE = Path(__file__).resolve().parent
LINK = {"color": "0.15", "lw": 3, "solid_capstyle": "round"}
JOINT = {"s": 60, "facecolor": "white", "edgecolor": "0.15", "zorder": 5, "lw": 1.5}


def _joints(ax: plt.Axes, pts: list) -> None:
    p = np.array(pts)
    ax.scatter(p[:, 0], p[:, 1], **JOINT)


def _ground(ax: plt.Axes, p: tuple, w: float = 0.35) -> None:
    x, y = p
    ax.plot([x - w, x + w], [y - 0.12, y - 0.12], color="0.3", lw=1.5)
    for t in np.linspace(x - w, x + w, 6):
        ax.plot([t, t - 0.1], [y - 0.12, y - 0.24], color="0.3", lw=1)


def _arrow(ax: plt.Axes, p: np.ndarray, d: np.ndarray, color: str, text: str) -> None:
    ax.annotate("", xy=p + d, xytext=p, arrowprops={"arrowstyle": "-|>", "color": color, "lw": 2})
    ax.text(*(p + 1.1 * d), text, color=color, fontsize=10, ha="center", va="center")


def serial() -> None:
    """A planar 2R arm stretched: the hand cannot move along the arm (lost twist), and a
    force along the arm needs no joint torque (resisted wrench)."""
    fig, axes = plt.subplots(1, 2, figsize=(8, 3))
    for ax, elbow, title in zip(
        axes, (0.9, 0.0), ("regular: elbow bent", "singular: stretched"), strict=True
    ):
        a = np.array([0.0, 0.0])
        b = a + 1.2 * np.array([np.cos(0.35), np.sin(0.35)])
        c = b + 1.0 * np.array([np.cos(0.35 + elbow), np.sin(0.35 + elbow)])
        ax.plot(*zip(a, b, c, strict=True), **LINK)
        _joints(ax, [a, b])
        ax.scatter(*c, s=40, color="0.15", zorder=6)
        _ground(ax, a)
        u = (c - a) / np.linalg.norm(c - a)
        n = np.array([-u[1], u[0]])
        if elbow:
            _arrow(ax, c, 0.5 * u, "tab:blue", "reachable")
            _arrow(ax, c, 0.5 * n, "tab:blue", "")
        else:
            _arrow(ax, c, 0.5 * n, "tab:blue", "reachable")
            _arrow(ax, c, 0.55 * u, "tab:red", "")
            ax.text(
                *(c + 0.75 * u - 0.45 * n),
                "lost twist /\nresisted force",
                color="tab:red",
                ha="center",
                va="center",
            )
        ax.set_title(title)
        ax.set_aspect("equal")
        ax.set_xlim(-0.6, 3.0)
        ax.set_ylim(-0.5, 2.2)
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(HERE / "serial.png", dpi=110)
    plt.close(fig)


def bifurcation() -> None:
    """The change-point four-bar (ground 4, crank 1, coupler 5, rocker 2): its configuration
    curve in (crank angle, rocker angle) crosses itself where the linkage is flat."""
    g, a, b, c = 4.0, 1.0, 5.0, 2.0
    th = np.linspace(-np.pi, np.pi, 4001)
    fig, ax = plt.subplots(figsize=(5.5, 4))
    for sign, color in ((1, "tab:blue"), (-1, "tab:orange")):
        # rocker angle psi (of D->C) from Freudenstein: |B - C| = b with B = a(cos, sin) th
        bx, by = a * np.cos(th), a * np.sin(th)
        dx, dy = bx - g, by
        r2 = dx**2 + dy**2
        k = (r2 + c**2 - b**2) / (2 * c * np.sqrt(r2))
        ok = np.abs(k) <= 1 + 1e-12
        psi = np.arctan2(dy, dx) + sign * np.arccos(np.clip(k, -1, 1))
        psi = np.where(ok, np.angle(np.exp(1j * psi)), np.nan)
        ax.plot(th, psi, color=color, lw=2, label=f"assembly mode {'+' if sign > 0 else '-'}")
    ax.scatter([0, 0], [0, 0], s=80, facecolor="white", edgecolor="tab:red", zorder=5, lw=2)
    ax.annotate(
        "flat: two branches cross\n(rank 2, instantaneous\nmobility 2)",
        xy=(0, 0),
        xytext=(0.35, -1.25),
        arrowprops={"arrowstyle": "->", "color": "tab:red"},
        color="tab:red",
    )
    ax.set_xlabel("crank angle (rad)")
    ax.set_ylabel("rocker angle (rad)")
    ax.set_title("change-point four-bar: 4, 1, 5, 2")
    ax.legend(loc="center left", fontsize=8)
    fig.tight_layout()
    fig.savefig(HERE / "bifurcation.png", dpi=110)
    plt.close(fig)


def five_bar() -> None:
    """The bundled five-bar at its type I pose (leg 1 stretched) and its type II pose
    (distal links in line)."""
    a1, a2 = np.array([-1.5, 0.0]), np.array([1.5, 0.0])
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6))
    # type II: inputs at +-pi/6: B1 = (-5/2, sqrt 3), B2 = (5/2, sqrt 3), P their midpoint
    b1, b2 = np.array([-2.5, np.sqrt(3)]), np.array([2.5, np.sqrt(3)])
    p2 = (b1 + b2) / 2
    # type I: leg 1 stretched towards P with A2 = 0 (B2 = (3/2, 2)); |A1 P| = 9/2, |B2 P| = 5/2
    b2i = np.array([1.5, 2.0])
    d = np.linalg.norm(b2i - a1)
    x = (4.5**2 - 2.5**2 + d**2) / (2 * d)
    u = (b2i - a1) / d
    n = np.array([-u[1], u[0]])
    p1 = a1 + x * u + np.sqrt(4.5**2 - x**2) * n
    b1i = a1 + 2 * (p1 - a1) / 4.5
    poses = (
        (b1i, p1, b2i, "type I: leg 1 stretched", "input singularity"),
        (b1, p2, b2, "type II: distal links in line", "output singularity"),
    )
    for ax, (q1, p, q2, title, what) in zip(axes, poses, strict=True):
        ax.plot(*zip(a1, q1, p, q2, a2, strict=True), **LINK)
        _joints(ax, [a1, q1, p, q2, a2])
        _ground(ax, a1)
        _ground(ax, a2)
        if title.startswith("type I:"):
            v = (p - a1) / np.linalg.norm(p - a1)
            _arrow(ax, p, 0.8 * v, "tab:red", "P cannot\nmove here")
        else:
            _arrow(ax, p, np.array([0, 0.9]), "tab:red", "")
            ax.text(p[0], p[1] + 1.35, "P moves with\ninputs locked", color="tab:red", ha="center")
        ax.set_title(f"{title}\n({what})", fontsize=10)
        ax.set_aspect("equal")
        ax.set_xlim(-3.5, 3.5)
        ax.set_ylim(-0.5, 5.2)
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(HERE / "five_bar.png", dpi=110)
    plt.close(fig)


def three_rpr() -> None:
    """The bundled 3-RPR: regular at the reference; with the platform parallel to the base
    (a homothetic copy) its three leg lines meet at the homothety's centre."""
    base = np.array([[0.0, 0.0], [4.0, 0.0], [0.0, 4.0]])
    c = np.array([1.0, 1.0])
    rho = np.array([[0.8, -0.6], [0.6, 0.8]])
    plats = (c + (rho @ (base - c).T).T / 2, c + (base - c) / 2)
    fig, axes = plt.subplots(1, 2, figsize=(9, 4.2))
    for ax, plat, title in zip(
        axes, plats, ("reference: regular", "parallel platform: type II"), strict=True
    ):
        ax.fill(*plat.T, color="0.85", zorder=1)
        ax.plot(*np.vstack([plat, plat[:1]]).T, color="0.15", lw=2)
        for a, b in zip(base, plat, strict=True):
            ax.plot(*zip(a, b, strict=True), **LINK)
            far = a + 1.6 * (b - a) / np.linalg.norm(b - a) * np.linalg.norm(c - a)
            ax.plot(*zip(a, far, strict=True), color="tab:red", lw=0.8, ls="--")
            _ground(ax, a, 0.25)
        _joints(ax, list(base) + list(plat))
        if "type II" in title:
            ax.scatter(*c, s=90, color="tab:red", zorder=6)
            ax.annotate(
                "legs concurrent:\nthe platform turns\nwith the legs locked",
                xy=c,
                xytext=(2.2, 2.6),
                color="tab:red",
                arrowprops={"arrowstyle": "->", "color": "tab:red"},
            )
        ax.set_title(title)
        ax.set_aspect("equal")
        ax.set_xlim(-0.8, 4.8)
        ax.set_ylim(-0.6, 4.6)
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(HERE / "three_rpr.png", dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    serial()
    bifurcation()
    five_bar()
    three_rpr()
