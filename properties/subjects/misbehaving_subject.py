#!/usr/bin/env python3
"""A subject that misbehaves on purpose, for the CLI test of the gate's failure paths.

    misbehaving_subject.py MODE [FRAME]

Answers every frame with every object (conservative and correct) until FRAME (default 0),
then, by MODE:
  crash        exits with status 3              hang        sleeps past any timeout
  segfault     kills itself with SIGSEGV        garbage     prints a line that is not JSON
  wrong-frame  answers frame FRAME + 1          unknown-id  names object 99999999
  cull-all     answers with no object (a miss: the gate must exit 1)
  bad-ready    sends a ready message without "claims"
  no-ready     exits before answering the hello
  everything   never misbehaves (a straw man: passes the conservative check)
  approximate  claims approximate with budget FRAME and culls everything from frame 0
and two that cull boxes against the view volume like minimal_subject.py, from the wrong place:
  shift D      every box moved D metres east; D = origin: by the hello's origin (the scene-local
               vertices taken for world ones while the cameras stay local)
  scene FILE   the boxes of another scene JSON file (same ids), not of the hello's scene
"""
import json, os, signal, sys, time

mode = sys.argv[1]
arg = sys.argv[2] if len(sys.argv) > 2 else "0"
at = int(arg) if mode not in ("shift", "scene") else 0
hello = json.loads(sys.stdin.readline())
ids = [o["id"] for o in hello["scene"]["objects"]]
boxes = {o["id"]: o["bounds"] for o in hello["scene"]["objects"]}
if mode == "shift":
    dx, dy = hello["scene"]["origin"] if arg == "origin" else (float(arg), 0.0)
    boxes = {i: [[x0 + dx, y0 + dy, z0], [x1 + dx, y1 + dy, z1]] for i, ((x0, y0, z0), (x1, y1, z1)) in boxes.items()}
if mode == "scene":
    boxes = {}
    for b in json.load(open(arg))["buildings"]:
        xs, ys = [p[0] for p in b["footprint"]], [p[1] for p in b["footprint"]]
        boxes[b["id"]] = [[min(xs), min(ys), 0.0], [max(xs), max(ys), b["height"]]]


def in_view(frame, box):
    """False when all 8 corners of the box lie beyond one clip plane of projection * view."""
    v, p = frame["view"], frame["projection"]
    m = [[sum(p[r][k] * v[k][c] for k in range(4)) for c in range(4)] for r in range(4)]
    (x0, y0, z0), (x1, y1, z1) = box
    clip = [[sum(m[r][c] * q for c, q in enumerate((x, y, z, 1.0))) for r in range(4)]
            for x in (x0, x1) for y in (y0, y1) for z in (z0, z1)]
    return not any(all(c[a] < -c[3] for c in clip) or all(c[a] > c[3] for c in clip) for a in range(3))

if mode == "no-ready":
    sys.exit(4)
ready = {"type": "ready", "name": "misbehaving-" + mode, "claims": "conservative", "projections": ["perspective", "orthographic"]}
if mode == "bad-ready":
    del ready["claims"]
if mode == "approximate":
    ready.update({"claims": "approximate", "pixel_error_budget": at})
print(json.dumps(ready), flush=True)
for line in sys.stdin:
    request = json.loads(line)
    if request["type"] != "frame":
        break
    frame = request["frame"]
    answer = {"type": "visible", "frame": frame, "ids": ids}
    if mode in ("shift", "scene"):
        answer["ids"] = [i for i in ids if i in boxes and in_view(request, boxes[i])]
    elif mode == "approximate" or (mode == "cull-all" and frame >= at):
        answer["ids"] = []
    elif frame >= at and mode not in ("everything", "cull-all", "shift", "scene"):
        sys.stderr.write("misbehaving subject: %s at frame %d\n" % (mode, frame))
        sys.stderr.flush()
        if mode == "crash":
            sys.exit(3)
        if mode == "segfault":
            os.kill(os.getpid(), signal.SIGSEGV)
        if mode == "hang":
            time.sleep(3600)
        if mode == "garbage":
            print("this is not JSON", flush=True)
            continue
        if mode == "wrong-frame":
            answer["frame"] = frame + 1
        if mode == "unknown-id":
            answer["ids"] = ids + [99999999]
    print(json.dumps(answer), flush=True)
