"""Provenance of the files the result scripts write, as vbsim records it for its
own outputs (model/provenance/provenance.h): which vbsim (version, revision,
binary checksum), which command line, and the SHA-256 of every input, so a
result names what made it.

    prov = script_provenance(vbsim, inputs)
    JSON:     {"provenance": prov, ...}
    markdown: provenance_comment(prov), an HTML comment line at the end
    CSV:      csv_comment(prov), a first line starting with '#'
    PNG:      stamp_png(path, prov), an iTXt chunk "vbsim-provenance"
"""
import json
import os
import struct
import subprocess
import sys
import zlib

from point_jobs import file_digest


def vbsim_version(vbsim):
    proc = subprocess.run([vbsim, "--version"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    return proc.stdout.strip() if proc.returncode == 0 else "unknown"


def script_provenance(vbsim, inputs):
    files = []
    for path in dict.fromkeys(inputs):
        files.append({"path": os.path.relpath(path), "bytes": os.path.getsize(path), "sha256": file_digest(path)})
    return {"program": os.path.basename(sys.argv[0]), "command": [sys.executable] + sys.argv,
            "vbsim": {"path": vbsim, "version": vbsim_version(vbsim), "sha256": file_digest(vbsim)},
            "inputs": files}


def provenance_comment(prov):
    text = json.dumps(prov, separators=(",", ":")).replace("--", "-\\u002d")  # "--" cannot be in a comment
    return f"<!-- vbsim-provenance {text} -->\n"


def csv_comment(prov):
    return "# vbsim-provenance " + json.dumps(prov, separators=(",", ":")) + "\n"


def stamp_png(path, prov):
    """Inserts an iTXt chunk with the provenance right after the PNG's IHDR chunk."""
    with open(path, "rb") as f:
        png = f.read()
    if png[:8] != b"\x89PNG\r\n\x1a\n" or png[12:16] != b"IHDR":
        raise ValueError(f"{path}: not a PNG file")
    body = b"iTXt" + b"vbsim-provenance\x00\x00\x00\x00\x00" + json.dumps(prov).encode()
    chunk = struct.pack(">I", len(body) - 4) + body + struct.pack(">I", zlib.crc32(body) & 0xffffffff)
    at = 8 + 25  # signature, then IHDR (length, type, 13 bytes, CRC)
    with open(path + ".part", "wb") as f:
        f.write(png[:at] + chunk + png[at:])
    os.replace(path + ".part", path)
