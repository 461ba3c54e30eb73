"""Configurations on purpose at forward singularities of the 3-RPS mechanisms: where the
generated forward-singularity polynomial changes sign along a vertical line of poses."""

import numpy as np


def singular_heights(m, base, z, count=2):
    """The first ``count`` heights where ``det_forward`` changes sign along the line of poses
    ``base`` with z in the grid ``z``, each bisected to the last bit (60 halvings)."""
    key = next(k for k in m.SINGULARITY_MEANING if k.startswith("det_forward"))

    def value(zz):
        pose = np.array([*base[:2], zz, *base[3:]])
        return m.singularities(pose, m.ik(pose, limits=False))[key]

    poses = np.tile(base, (len(z), 1))
    poses[:, 2] = z
    v = m.singularities(poses, m.ik(poses, limits=False))[key]
    s = np.sign(v)
    out = []
    for i in np.where(np.isfinite(v[:-1]) & np.isfinite(v[1:]) & (s[:-1] != s[1:]))[0][:count]:
        a, b, va = z[i], z[i + 1], v[i]
        for _ in range(60):
            mid = (a + b) / 2
            vm = value(mid)
            a, b, va = (mid, b, vm) if np.sign(vm) == np.sign(va) else (a, mid, va)
        out.append((a + b) / 2)
    return out
