"""The sensor in use: what the tissue, the temperature, the read-out and the jaw do to the K_obj a lab reads.

Reads plans and the mechanics' results (never the CAD kernel, the studies nor the paper);
design, verify and the review page consume it.
"""
