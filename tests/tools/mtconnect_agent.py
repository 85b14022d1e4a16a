#!/usr/bin/env python3
"""A stand-in MTConnect agent for DriftLab's CNC tests (independent of DriftLab's code).

Serves MTConnectStreams documents laid out like the MTConnect C++ agent's own samples
(cppagent samples/test_current.xml and test_sample.xml: a LinuxCNC device stream with a
Linear X component (Position Xact, subType ACTUAL), an Axes component (PathFeedrate
path_feedrate, mm/s) and a Controller (Execution)), over Python's http.server:

  GET /current                 latest observation of every data item
  GET /sample?from=N&count=C   buffered observations from sequence N (OUT_OF_RANGE error
                               when N has left the buffer)

The axis moves X(t) = 260 + 250 sin(2 pi t / period) mm; path_feedrate = |dX/dt| in mm/s;
observations are produced at --rate Hz into a ring buffer of --buffer entries.

Usage: mtconnect_agent.py [--port 0] [--rate 10] [--buffer 2000] [--period 20] [--instance N]
Prints "ready PORT" when serving. Standard input commands (acknowledged "ok CMD"):
  stall / resume      stop answering requests / answer again
  unavailable / available   X reads UNAVAILABLE / moves again
  quit
"""

import argparse
import datetime
import http.server
import math
import socketserver
import sys
import threading
import time
import urllib.parse

lock = threading.Lock()
state = {"stall": False, "unavailable": False}


def iso(t):
    return datetime.datetime.fromtimestamp(t, datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%S.%fZ")


class Buffer:
    def __init__(self, size, instance):
        self.size = size
        self.instance = instance
        self.items = []  # (sequence, timestamp, component, element, id, name, subtype, value)
        self.next = 1
        self.latest = {}

    def add(self, t, component, element, ident, name, subtype, value):
        obs = (self.next, t, component, element, ident, name, subtype, value)
        self.next += 1
        self.items.append(obs)
        if len(self.items) > self.size:
            self.items.pop(0)
        self.latest[ident] = obs

    def first(self):
        return self.items[0][0] if self.items else self.next


def header(buf, now):
    return ('  <Header creationTime="%s" sender="localhost" instanceId="%d" bufferSize="%d" version="1.3" '
            'nextSequence="%d" firstSequence="%d" lastSequence="%d"/>\n'
            % (iso(now), buf.instance, buf.size, buf.next, buf.first(), buf.next - 1))


COMPONENTS = [("Linear", "X", "7"), ("Axes", "Axes", "5"), ("Controller", "Controller", "11")]


def streams(buf, observations, now, next_seq=None):
    out = ['<?xml version="1.0" encoding="UTF-8"?>\n',
           '<MTConnectStreams xmlns:m="urn:mtconnect.org:MTConnectStreams:1.3" '
           'xmlns="urn:mtconnect.org:MTConnectStreams:1.3">\n']
    h = header(buf, now)
    if next_seq is not None:
        h = h.replace('nextSequence="%d"' % buf.next, 'nextSequence="%d"' % next_seq)
    out.append(h)
    out.append('  <Streams>\n    <DeviceStream name="LinuxCNC" uuid="000">\n')
    for comp, name, cid in COMPONENTS:
        obs = [o for o in observations if o[2] == comp]
        if not obs:
            continue
        out.append('      <ComponentStream component="%s" name="%s" componentId="%s">\n' % (comp, name, cid))
        category = "Events" if comp == "Controller" else "Samples"
        out.append('        <%s>\n' % category)
        for seq, t, _, element, ident, iname, subtype, value in obs:
            sub = ' subType="%s"' % subtype if subtype else ""
            out.append('          <%s dataItemId="%s" name="%s" sequence="%d"%s timestamp="%s">%s</%s>\n'
                       % (element, ident, iname, seq, sub, iso(t), value, element))
        out.append('        </%s>\n      </ComponentStream>\n' % category)
    out.append('    </DeviceStream>\n  </Streams>\n</MTConnectStreams>\n')
    return "".join(out)


def error(buf, now, code, text):
    return ('<?xml version="1.0" encoding="UTF-8"?>\n'
            '<MTConnectError xmlns="urn:mtconnect.org:MTConnectError:1.3">\n' + header(buf, now) +
            '  <Errors>\n    <Error errorCode="%s">%s</Error>\n  </Errors>\n</MTConnectError>\n' % (code, text))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--port", type=int, default=0)
    ap.add_argument("--rate", type=float, default=10.0)
    ap.add_argument("--buffer", type=int, default=2000)
    ap.add_argument("--period", type=float, default=20.0)
    ap.add_argument("--instance", type=int, default=0, help="instanceId (default: the start time in seconds)")
    args = ap.parse_args()
    buf = Buffer(args.buffer, args.instance or int(time.time()))
    t0 = time.time()

    def axis(t):
        phase = 2 * math.pi * (t - t0) / args.period
        x = 260.0 + 250.0 * math.sin(phase)
        v = abs(250.0 * 2 * math.pi / args.period * math.cos(phase))
        return x, v

    def produce():
        n = 0
        while True:
            t = t0 + n / args.rate
            delay = t - time.time()
            if delay > 0:
                time.sleep(delay)
            x, v = axis(t)
            with lock:
                xs = "UNAVAILABLE" if state["unavailable"] else "%.6f" % x
                buf.add(t, "Linear", "Position", "14", "Xact", "ACTUAL", xs)
                buf.add(t, "Axes", "PathFeedrate", "6", "path_feedrate", "ACTUAL", "%.6f" % v)
                if n % int(max(1, args.rate * 5)) == 0:
                    buf.add(t, "Controller", "Execution", "24", "execution", None, "ACTIVE")
            n += 1

    class Handler(http.server.BaseHTTPRequestHandler):
        def log_message(self, *a):
            pass

        def do_GET(self):
            while True:
                with lock:
                    stalled = state["stall"]
                if not stalled:
                    break
                time.sleep(0.05)
            url = urllib.parse.urlparse(self.path)
            q = urllib.parse.parse_qs(url.query)
            now = time.time()
            status = 200
            with lock:
                if url.path.rstrip("/").endswith("/current"):
                    body = streams(buf, sorted(buf.latest.values()), now)
                elif url.path.rstrip("/").endswith("/sample"):
                    start = int(q.get("from", [buf.first()])[0])
                    count = int(q.get("count", ["100"])[0])
                    if start < buf.first() or start > buf.next:
                        status = 404
                        body = error(buf, now, "OUT_OF_RANGE", "'from' must be between %d and %d" % (buf.first(), buf.next))
                    else:
                        obs = [o for o in buf.items if o[0] >= start][:count]
                        nxt = obs[-1][0] + 1 if obs else start
                        body = streams(buf, obs, now, nxt)
                else:
                    status = 400
                    body = error(buf, now, "UNSUPPORTED", "unknown request %s" % url.path)
            data = body.encode()
            self.send_response(status)
            self.send_header("Content-Type", "text/xml")
            self.send_header("Content-Length", str(len(data)))
            self.end_headers()
            self.wfile.write(data)

    class Server(socketserver.ThreadingMixIn, http.server.HTTPServer):
        daemon_threads = True
        allow_reuse_address = True

    server = Server(("127.0.0.1", args.port), Handler)
    threading.Thread(target=produce, daemon=True).start()
    threading.Thread(target=server.serve_forever, daemon=True).start()
    print("ready %d" % server.server_address[1], flush=True)
    for line in sys.stdin:
        cmd = line.strip()
        with lock:
            if cmd == "stall":
                state["stall"] = True
            elif cmd == "resume":
                state["stall"] = False
            elif cmd == "unavailable":
                state["unavailable"] = True
            elif cmd == "available":
                state["unavailable"] = False
        print("ok %s" % cmd, flush=True)
        if cmd == "quit":
            break
    server.shutdown()


if __name__ == "__main__":
    main()
