"""Build an exported stream top's Verilog with Icarus and run test_pixel_stream.py (cocotb).

Usage: python run.py <stream dir> <verilog file> <build dir> [<top module>]
The top module is pixel_stream unless given (gouraud_stream: the same AXI4-Stream ports
without m_axis_tuser; cubic_stream: the same ports as pixel_stream). Exit status 0 when the cocotb test passes, 1 when it fails.
"""

import os
import sys
import xml.etree.ElementTree as ET

from cocotb_tools.runner import get_runner


def main():
    stream_dir, verilog, build_dir = (os.path.abspath(a) for a in sys.argv[1:4])
    top = sys.argv[4] if len(sys.argv) > 4 else "pixel_stream"
    here = os.path.dirname(os.path.abspath(__file__))
    runner = get_runner("icarus")
    runner.build(
        sources=[verilog],
        hdl_toplevel=top,
        build_dir=build_dir,
        always=True,
        timescale=("1ns", "1ps"),
    )
    results = runner.test(
        hdl_toplevel=top,
        test_module="test_pixel_stream",
        test_dir=here,
        build_dir=build_dir,
        results_xml=os.path.join(build_dir, "results.xml"),
        extra_env={
            "SHADECORE_STREAM_DIR": stream_dir,
            "SHADECORE_SEED": os.environ.get("SHADECORE_SEED", "1"),
        },
    )
    tree = ET.parse(results)
    cases = tree.findall(".//testcase")
    failed = [c for c in cases if c.find("failure") is not None or c.find("error") is not None]
    print(f"cocotb: {len(cases)} test(s), {len(failed)} failed")
    sys.exit(1 if failed or not cases else 0)


if __name__ == "__main__":
    main()
