"""A trajectory with the working mode kept continuous: the Pro-Hep-LCT (004) swept along a
straight line of the lower point Pd, solving every working mode at each sample and keeping,
sample by sample, the mode whose joints are nearest the previous ones (a path that crosses
no singularity stays in its mode; one that passes a leg's boundary would switch).

    .venv/bin/python examples/trajectory_continuous_mode.py
"""

import numpy as np
from bonered_alg.generated import pro_hep_lct as m


def follow_nearest(poses: np.ndarray, start_mode: int = 0):
    """Joints along ``poses`` continuing from ``start_mode`` by nearest neighbour among
    ``ik_all``; returns (joints (n, 4), mode per sample)."""
    every = m.ik_all(poses, limits=False)  # (n, MODES, 4)
    modes = [start_mode]
    for k in range(1, len(poses)):
        step = np.nanmax(np.abs(every[k] - every[k - 1, modes[-1]]), axis=-1)
        modes.append(int(np.nanargmin(step)) if np.isfinite(step).any() else modes[-1])
    modes = np.array(modes)
    return every[np.arange(len(poses)), modes], modes


def main() -> dict:
    s = np.linspace(0.0, 1.0, 101)
    poses = np.column_stack([np.full_like(s, 300.0), np.full_like(s, 180.0),
                             239.09 + 40.0 * s, 180.0 + 30.0 * s])  # (Xu, Yu, Xd, Yd) in mm
    joints, modes = follow_nearest(poses)
    jump = np.abs(np.diff(joints, axis=0)).max()
    print(f"{len(s)} samples, modes used {sorted(set(modes.tolist()))}, largest joint step "
          f"{jump:.4f}; status at the end: {m.STATUS[int(m.ik_status(poses[-1]))]}")
    return {"joints": joints, "modes": modes, "poses": poses}


if __name__ == "__main__":
    main()
