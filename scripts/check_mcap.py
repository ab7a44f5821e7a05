#!/usr/bin/env python3
"""Independent check of flexrig MCAP logs with the Python `mcap` package.

For each file: CRCs valid, summary present, per-topic message counts equal to the summary's
statistics, log_time monotone per topic and equal to publish_time, every message decodes
(protobuf, with the schemas stored in the file; the `/severity` message as JSON with every
severity key, finite numbers and HIC15 ≤ HIC36), the scene attachment and the metadata present
(`flexrig`, and `view` with the 3D view's deformation scale).
Prints one line per file and exits non-zero on the first problem.

Usage: python3 scripts/check_mcap.py FILE.mcap [...]
Needs: pip install mcap mcap-protobuf-support
"""
import json
import math
import sys
from collections import Counter

from mcap.reader import make_reader
from mcap_protobuf.decoder import DecoderFactory

max_force = {}

REQUIRED_TOPICS = {"/tf", "/scene", "/sensors/force", "/sensors/accel/operator",
                   "/sensors/accel/load", "/sensors/encoders", "/contact", "/energy"}
SEVERITY_KEYS = {"peak_force_n", "time_of_peak_force_s", "pressure", "energy_transferred_j",
                 "contact_work_j", "hic_method", "struck_body"}
# absent only for a struck body that does not move (a driven run's head against a wall)
ACCELERATION_KEYS = {"peak_acceleration_mps2", "peak_acceleration_g", "hic15", "hic36"}


def check_severity(path, s):
    moves = "wall" not in s.get("struck_body", "")
    missing = (SEVERITY_KEYS | (ACCELERATION_KEYS if moves else set())) - set(s)
    if missing:
        raise SystemExit(f"{path}: /severity lacks {sorted(missing)}")
    numbers = [s["peak_force_n"], s["energy_transferred_j"], s["contact_work_j"]]
    if moves:
        numbers += [s["peak_acceleration_mps2"], s["hic15"]["hic"], s["hic36"]["hic"]]
    numbers += [p["peak_pa"] for p in s["pressure"]]
    if not all(isinstance(x, (int, float)) and math.isfinite(x) for x in numbers):
        raise SystemExit(f"{path}: /severity has a value that is not a finite number")
    if len(s["pressure"]) != 2:
        raise SystemExit(f"{path}: /severity: two pressure models expected")
    if not moves:
        return
    if s["hic15"]["hic"] > s["hic36"]["hic"] * (1 + 1e-12):
        raise SystemExit(f"{path}: /severity: HIC15 <= HIC36 expected")
    if abs(s["peak_acceleration_g"] * 9.80665 - s["peak_acceleration_mps2"]) > 1e-9 * s["peak_acceleration_mps2"]:
        raise SystemExit(f"{path}: /severity: peak acceleration in g does not match m/s²")
# a driven run's log (metadata flexrig.kind = "driven"); /drive/command only with a commanded motion
DRIVEN_TOPICS = {"/drive/joint", "/drive/torque", "/link", "/contact"}


def check(path):
    with open(path, "rb") as f:
        reader = make_reader(f, validate_crcs=True, decoder_factories=[DecoderFactory()])
        summary = reader.get_summary()
        if summary is None or summary.statistics is None:
            raise SystemExit(f"{path}: no summary (unfinished file?)")
        topics = {c.id: c.topic for c in summary.channels.values()}
        metadata = {m.name: m.metadata for m in reader.iter_metadata()}
        driven = metadata.get("flexrig", {}).get("kind") == "driven"
        missing = (DRIVEN_TOPICS if driven else REQUIRED_TOPICS) - set(topics.values())
        if missing:
            raise SystemExit(f"{path}: missing topics {sorted(missing)}")
        counts = Counter()
        last = {}
        protobuf = DecoderFactory()
        severities = []
        for schema, channel, message in reader.iter_messages(log_time_order=False):
            topic = channel.topic
            if channel.message_encoding == "json":
                decoded = json.loads(message.data)
                if topic == "/severity":
                    check_severity(path, decoded)
                    severities.append(decoded)
            else:
                decoded = protobuf.decoder_for(channel.message_encoding, schema)(message.data)
            counts[topic] += 1
            if topic == "/contact" and hasattr(decoded, "force_n"):
                max_force[path] = max(max_force.get(path, 0.0), decoded.force_n)
            if message.log_time != message.publish_time:
                raise SystemExit(f"{path}: {topic}: log_time != publish_time")
            if topic in last and message.log_time < last[topic]:
                raise SystemExit(f"{path}: {topic}: log_time goes back at {message.log_time}")
            last[topic] = message.log_time
            ts = getattr(decoded, "timestamp", None)
            if ts is not None and hasattr(ts, "seconds") and ts.ByteSize() > 0:
                nanos = ts.seconds * 1_000_000_000 + ts.nanos
                if nanos != message.log_time:
                    raise SystemExit(f"{path}: {topic}: message timestamp {nanos} != log_time {message.log_time}")
        for cid, expected in summary.statistics.channel_message_counts.items():
            if counts[topics[cid]] != expected:
                raise SystemExit(f"{path}: {topics[cid]}: {counts[topics[cid]]} messages, statistics say {expected}")
        attachments = [a.name for a in reader.iter_attachments()]
        if "scene.toml" not in attachments:
            raise SystemExit(f"{path}: no scene.toml attachment")
        for name in ("flexrig", "view"):
            if name not in metadata:
                raise SystemExit(f"{path}: no {name} metadata")
        state = "error: " + metadata["error"]["message"] if "error" in metadata else "ok"
        if state == "ok" and len(severities) != 1:
            raise SystemExit(f"{path}: {len(severities)} /severity messages, one expected")
        if driven and state == "ok":
            # the logged force never exceeds the summary's located peak, and comes within 1e-3 of it
            peak = float(metadata["summary"]["peak_force_n"])
            logged = max_force.get(path, 0.0)
            if not (logged <= peak and logged >= (1 - 1e-3) * peak):
                raise SystemExit(f"{path}: logged peak force {logged} vs summary {peak}")
        total = sum(counts.values())
        print(f"{path}: {total} messages on {len(counts)} topics, {state}; "
              + ", ".join(f"{t} {n}" for t, n in sorted(counts.items())))
    return 0


if __name__ == "__main__":
    if len(sys.argv) < 2:
        raise SystemExit(__doc__)
    for p in sys.argv[1:]:
        check(p)
