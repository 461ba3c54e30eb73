"""RCM manipulation with the Pro-Hep-LCT (004 Sect. 4): tilt the tool about the entry point
O by up to 30 degrees (radians in the API), insert 100 mm, and check that the forward
kinematics of the joints puts the tool axis back through O.

    .venv/bin/python examples/rcm_manipulation.py
"""

import numpy as np
from bonered_alg.generated import pro_hep_lct as m

from bonered_alg.surgical import pro_hep_lct_tool as tool

O = np.array([1, 0, 0, 0, 0, -150, -90, 55.0])  # 004 Sect. 4: the entry point (300, 180, -110)


def main() -> dict:
    angles = np.radians([0.0, -10.0, -20.0, -30.0])
    path = tool.rcm_path(O, "x", angles, 100.0)     # 004 eq. (10), (12): tilt, then insert
    joints, status = tool.tool_ik(path, m)          # (t1, w1, q4, q5, n), mode 0
    back = tool.tool_fk(joints, m)                  # every assembly mode of the whole robot
    # the tool pose of the IK's own mode among the FK modes: its distance to the path pose
    err = np.min(np.linalg.norm(back - path[:, None, :], axis=-1), axis=-1)
    for a, q, e in zip(np.degrees(angles), joints, err):
        print(f"tilt {a:6.1f} deg: t1 {q[0]: .4f} w1 {q[1]: .4f} q4 {q[2]:8.3f} "
              f"q5 {q[3]:8.3f} n {q[4]:8.3f} mm; FK(IK) error {e:.1e}")
    return {"joints": joints, "status": status, "fk_error": err}


if __name__ == "__main__":
    main()
