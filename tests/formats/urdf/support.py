"""What the URDF tests share: the robot files, an independent numpy reference for a URDF
chain's pose (straight from the XML, not through dhsym), and builders of small URDF texts."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

DATA = Path(__file__).resolve().parents[2] / "data" / "urdf"

# (file, tip, number of moving joints): a UR, a 7-joint arm, a 6-joint arm, an education arm
ROBOTS = [
    ("ur5_robot.urdf", "tool0", 6),
    ("panda.urdf", "panda_hand", 7),
    ("kinova.urdf", "j2s6s200_end_effector", 6),
    ("so100.urdf", "gripper", 5),
]


# --- the independent reference: numpy, straight from the XML -------------------------------


def _rot(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rodrigues' formula."""
    u = axis / np.linalg.norm(axis)
    K = np.array([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
    return np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * K @ K


def _origin(joint: ET.Element) -> np.ndarray:
    el = joint.find("origin")
    xyz = [0.0] * 3 if el is None else [float(v) for v in el.get("xyz", "0 0 0").split()]
    r, p, y = [0.0] * 3 if el is None else [float(v) for v in el.get("rpy", "0 0 0").split()]
    ex, ey, ez = np.eye(3)
    T = np.eye(4)
    T[:3, :3] = _rot(ez, y) @ _rot(ey, p) @ _rot(ex, r)
    T[:3, 3] = xyz
    return T


def urdf_pose(path: Path, tip: str, q: np.ndarray) -> np.ndarray:
    """Root link -> tip link at joint values q (moving joints in chain order)."""
    root = ET.parse(path).getroot()
    joints = {j.find("child").get("link"): j for j in root.findall("joint")}
    chain = []
    link = tip
    while link in joints:
        chain.append(joints[link])
        link = joints[link].find("parent").get("link")
    T = np.eye(4)
    k = 0
    for j in reversed(chain):
        T = T @ _origin(j)
        if j.get("type") in ("revolute", "continuous", "prismatic"):
            axis_el = j.find("axis")
            text = axis_el.get("xyz") if axis_el is not None else "1 0 0"
            axis = np.array([float(v) for v in text.split()])
            M = np.eye(4)
            if j.get("type") == "prismatic":
                M[:3, 3] = q[k] * axis / np.linalg.norm(axis)
            else:
                M[:3, :3] = _rot(axis, q[k])
            T = T @ M
            k += 1
    return T


# --- small URDF texts -------------------------------------------------------------------------


def urdf(joints: str, links: str = "abc") -> str:
    return '<robot name="r">' + "".join(f'<link name="{n}"/>' for n in links) + joints + "</robot>"


def joint(name: str, parent: str, child: str, kind: str = "revolute", body: str = "") -> str:
    return (
        f'<joint name="{name}" type="{kind}"><parent link="{parent}"/>'
        f'<child link="{child}"/>{body}</joint>'
    )


def long_chain(n: int, closing: str = "") -> str:
    links = "".join(f'<link name="l{i}"/>' for i in range(n))
    joints = "".join(joint(f"j{i}", f"l{i}", f"l{i + 1}", "fixed") for i in range(n - 1))
    return f'<robot name="r">{links}{joints}{closing}</robot>'
