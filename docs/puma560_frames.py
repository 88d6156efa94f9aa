"""Draw the README picture docs/puma560-frames.png: the PUMA 560 with its DH frames at q = 0.

Run from the repository root: ``.venv/bin/python docs/puma560_frames.py``.
"""

from __future__ import annotations

from pathlib import Path

import dhsym

OUT = Path(__file__).resolve().parent / "puma560-frames.png"


def main(path: Path = OUT) -> Path:
    """Write the picture (the pose of the toolbox printout in the IRob2305 lecture)."""
    fig = dhsym.load("puma560").plot(
        scale=0.1,
        title="PUMA 560, standard DH frames at q = 0\n"
        "(the pose of the toolbox printout in IRob2305, Lecture 5)",
    )
    fig.set_size_inches(8.0, 7.2)
    fig.axes[0].view_init(elev=20, azim=-125)
    fig.savefig(path, dpi=110)
    return path


if __name__ == "__main__":
    print(f"wrote {main()}")
