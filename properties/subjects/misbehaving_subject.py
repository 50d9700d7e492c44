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
"""
import json, os, signal, sys, time

mode = sys.argv[1]
at = int(sys.argv[2]) if len(sys.argv) > 2 else 0
hello = json.loads(sys.stdin.readline())
ids = [o["id"] for o in hello["scene"]["objects"]]
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
    if mode == "approximate" or (mode == "cull-all" and frame >= at):
        answer["ids"] = []
    elif frame >= at and mode not in ("everything", "cull-all"):
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
