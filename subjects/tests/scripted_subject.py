#!/usr/bin/env python3
"""A subject for subjects/tests/subject_method_test.cpp, behaving as its MODE says.

    scripted_subject.py MODE [FRAME] [BYE_FILE]

Its ready message is named "scripted-<objects>-objects-<frames>-frames" from the hello, so a test
sees that the hello arrived whole. Frame f is answered with the first f + 1 object ids of the
hello (sorted) and "cull_ms" = the frame's "time" in milliseconds, so a test sees that the frame
index and time arrived. At FRAME (default 0), by MODE:
  good          never misbehaves             approximate  claims approximate, budget 7
  crash         exits with status 3          hang         sleeps for an hour
  wrong-frame   answers frame + 1            unknown-id   names object 99999
  no-timing     answers without "cull_ms"
  garbage-ready answers the hello with a line that is not JSON
  version-2     says it speaks protocol 2    silent       never answers the hello
On {"type":"bye"} it writes "bye" to BYE_FILE (when given) and exits 0.
"""
import json, sys, time

mode = sys.argv[1]
at = int(sys.argv[2]) if len(sys.argv) > 2 else 0
bye_file = sys.argv[3] if len(sys.argv) > 3 else None
hello = json.loads(sys.stdin.readline())
ids = sorted(o["id"] for o in hello["scene"]["objects"])
if mode == "silent":
    time.sleep(3600)
if mode == "garbage-ready":
    print("READY!", flush=True)
    sys.exit(0)
ready = {"type": "ready", "protocol": 1, "projections": ["perspective"],
         "name": "scripted-%d-objects-%d-frames" % (hello["scene"]["object_count"], hello["frames"]),
         "claims": "conservative"}
if mode == "approximate":
    ready.update({"claims": "approximate", "pixel_error_budget": 7})
if mode == "version-2":
    ready["protocol"] = 2
print(json.dumps(ready), flush=True)
for line in sys.stdin:
    request = json.loads(line)
    if request["type"] == "bye":
        if bye_file:
            with open(bye_file, "w") as f:
                f.write("bye")
        sys.exit(0)
    frame = request["frame"]
    answer = {"type": "visible", "frame": frame, "ids": ids[: frame + 1], "cull_ms": request["time"] * 1000}
    if frame >= at:
        if mode == "crash":
            sys.stderr.write("scripted subject: crashing at frame %d\n" % frame)
            sys.stderr.flush()
            sys.exit(3)
        if mode == "hang":
            time.sleep(3600)
        if mode == "wrong-frame":
            answer["frame"] = frame + 1
        if mode == "unknown-id":
            answer["ids"] = ids + [99999]
        if mode == "no-timing":
            del answer["cull_ms"]
    print(json.dumps(answer), flush=True)
