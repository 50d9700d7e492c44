#!/usr/bin/env python3
# The smallest useful subject in Python (README "The subject protocol"): culls each object's
# bounding box against the view volume in clip space (all 8 corners beyond one plane).
import json, sys
objects = json.loads(sys.stdin.readline())["scene"]["objects"]
print(json.dumps({"type": "ready", "name": "minimal-box-py", "claims": "conservative",
                  "projections": ["perspective", "orthographic"]}), flush=True)
for line in sys.stdin:
    frame = json.loads(line)
    if frame["type"] != "frame":
        break
    v, p = frame["view"], frame["projection"]
    m = [[sum(p[r][k] * v[k][c] for k in range(4)) for c in range(4)] for r in range(4)]
    ids = []
    for o in objects:
        (x0, y0, z0), (x1, y1, z1) = o["bounds"]
        clip = [[sum(m[r][c] * q for c, q in enumerate((x, y, z, 1.0))) for r in range(4)]
                for x in (x0, x1) for y in (y0, y1) for z in (z0, z1)]
        if not any(all(c[a] < -c[3] for c in clip) or all(c[a] > c[3] for c in clip) for a in range(3)):
            ids.append(o["id"])
    print(json.dumps({"type": "visible", "frame": frame["frame"], "ids": ids}), flush=True)
