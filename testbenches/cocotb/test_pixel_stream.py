"""cocotb test of an exported stream top, `pixel-stream`, `gouraud-stream` or `cubic-stream`
(cocotbext-axi drives its AXI4-Stream ports; `gouraud-stream` has no `m_axis_tuser`, its
beats' z is 0).

Reads the set-up words and the expected fragment beats that `shadecore stream` wrote (the
rust-hdl simulation's beats), sends the words as one AXI4-Stream frame per record with random
gaps, takes the fragment stream with random back-pressure (long stretches included), and checks
every beat, in order, against the expected ones.

Environment: SHADECORE_STREAM_DIR (the `shadecore stream --out` directory), SHADECORE_SEED.
"""

import logging
import os
import random

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, RisingEdge
from cocotbext.axi import AxiStreamBus, AxiStreamFrame, AxiStreamSink, AxiStreamSource


def read_setup(path):
    records, words = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            w, last = line.split()
            words.append(int(w, 16))
            if last == "1":
                records.append(words)
                words = []
    assert not words, "set-up stream ends inside a record"
    return records


def read_beats(path):
    beats = []
    with open(path) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            x, y, pixel, r, g, b, z, last = (int(v) for v in line.split())
            beats.append((x, y, pixel, r, g, b, z & 0xFFFFFFFF, last))
    return beats


def unpack(tdata, tuser, tlast):
    # The layout of rtl::stream::layout::FRAGMENT (rtl/README.md); no tuser: z = 0.
    tuser = 0 if tuser is None else tuser
    return (
        tdata & 0xFFF,
        (tdata >> 12) & 0xFFF,
        (tdata >> 24) & 1,
        (tdata >> 32) & 0xFF,
        (tdata >> 40) & 0xFF,
        (tdata >> 48) & 0xFF,
        tuser & 0xFFFFFFFF,
        tlast,
    )


def pauses(rng, p, stretch_every):
    """Random pauses: each clock with probability p, and now and then a long stretch."""
    while True:
        if rng.random() < 1.0 / stretch_every:
            for _ in range(rng.randint(40, 300)):
                yield 1
        yield 1 if rng.random() < p else 0


@cocotb.test()
async def fragments_equal_the_rust_hdl_simulation(dut):
    d = os.environ["SHADECORE_STREAM_DIR"]
    seed = int(os.environ.get("SHADECORE_SEED", "1"))
    rng = random.Random(seed)
    dut._log.info("seed %d (SHADECORE_SEED overrides)", seed)
    records = read_setup(os.path.join(d, "setup.txt"))
    expected = read_beats(os.path.join(d, "beats.txt"))

    cocotb.start_soon(Clock(dut.clock, 10, unit="ns").start())
    dut.s_axis_tvalid.value = 0
    dut.m_axis_tready.value = 0
    source = AxiStreamSource(AxiStreamBus.from_prefix(dut, "s_axis"), dut.clock, byte_size=32)
    sink = AxiStreamSink(AxiStreamBus.from_prefix(dut, "m_axis"), dut.clock, byte_size=64)
    source.log.setLevel(logging.WARNING)
    sink.log.setLevel(logging.WARNING)
    source.set_pause_generator(pauses(rng, 0.1, 2000))
    sink.set_pause_generator(pauses(rng, 0.4, 300))
    await ClockCycles(dut.clock, 2)

    for r in records:
        await source.send(AxiStreamFrame(tdata=r))

    got = []
    while len(got) < len(expected):
        frame = await sink.recv()
        tusers = frame.tuser if isinstance(frame.tuser, list) else [frame.tuser] * len(frame.tdata)
        for k, (tdata, tuser) in enumerate(zip(frame.tdata, tusers)):
            got.append(unpack(tdata, tuser, int(k == len(frame.tdata) - 1)))
    for i, (g, e) in enumerate(zip(got, expected)):
        assert g == e, f"beat {i}: got {g}, expected {e} (x y pixel r g b z tlast)"
    assert len(got) == len(expected), f"{len(got)} beats, expected {len(expected)}"
    assert int(dut.error.value) == 0, "error set on a good stream"
    # Nothing more comes.
    await ClockCycles(dut.clock, 50)
    assert sink.empty(), "a beat beyond the expected ones"
    dut._log.info("%d beats equal the rust-hdl simulation's", len(got))
