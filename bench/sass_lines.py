"""Where a kernel's instructions and stall samples go, by source line (bench/batch_h100.sh PART=profile).

ncu's per-instruction page (`--page source --csv --print-source sass`) has SASS addresses but no source
lines; `nvdisasm -g` of the same build's cubin has both.  Each instruction is charged to the last line of
FOCUS (default small_hull.hpp) seen before it in address order: inlined helpers count toward the line that
called them.

    cuobjdump -xelf all build/cuda/CMakeFiles/cudahull_cuda.dir/batch_cuda.cu.o
    nvdisasm -g -c batch_cuda.sm_90.cubin > kernel.sass
    python3 bench/sass_lines.py kernel.sass batch_warp_kernel_100000x100_ball.sass.csv \\
        batch_warp_kernelINS_6Point3ELi4ELi4ELb1E [--focus small_hull.hpp]
"""
import argparse
import collections
import csv
import re


def lines_by_address(sass, function, focus):
    text = open(sass).read().split("\n")
    start = next(i for i, line in enumerate(text) if line.startswith(".text.") and function in line)
    at, context, seen = {}, ("?", 0), False
    for line in text[start + 1:]:
        if line.startswith(".text.") or line.startswith("//-----"):
            break
        m = re.search(r'//## File "([^"]+)", line (\d+)', line)
        if m:
            seen = True
            if m.group(1).split("/")[-1] == focus:
                context = (focus, int(m.group(2)))
            continue
        m = re.search(r"/\*([0-9a-f]{4,})\*/", line)
        if m and seen:
            at[int(m.group(1), 16)] = context
    return at


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("sass", help="nvdisasm -g -c output")
    ap.add_argument("profile", help="ncu --page source --csv --print-source sass output")
    ap.add_argument("function", help="a substring of the kernel's mangled name")
    ap.add_argument("--focus", default="small_hull.hpp")
    ap.add_argument("--min", type=float, default=0.4, help="lines below this share of samples are left out (%)")
    a = ap.parse_args()
    at = lines_by_address(a.sass, a.function, a.focus)
    rows = list(csv.reader(open(a.profile)))
    head, body = rows[1], [r for r in rows[2:] if len(r) > 3]
    address, samples = head.index("Address"), head.index("Warp Stall Sampling (All Samples)")
    executed = head.index("Instructions Executed")
    stalls = [i for i, h in enumerate(head) if h.startswith("stall_") and "Not Issued" not in h]
    base = int(body[0][address], 16)
    sampled, issued = collections.Counter(), collections.Counter()
    reasons = collections.defaultdict(collections.Counter)
    for r in body:
        line = at.get(int(r[address], 16) - base, ("?", 0))
        sampled[line] += float(r[samples] or 0)
        issued[line] += float(r[executed].replace(",", "") or 0)
        for i in stalls:
            reasons[line][head[i][len("stall_"):]] += float(r[i] or 0)
    total_samples, total_issued = sum(sampled.values()) or 1, sum(issued.values()) or 1
    print(f"{total_issued:.0f} warp instructions, {total_samples:.0f} samples")
    for line in sorted(sampled, key=lambda k: k[1]):
        share = 100 * sampled[line] / total_samples
        if share < a.min:
            continue
        top = ", ".join(f"{k} {100 * v / max(sampled[line], 1):.0f}%" for k, v in reasons[line].most_common(3))
        print(f"{line[0]}:{line[1]:<5d} samples {share:5.1f}%  instructions {100 * issued[line] / total_issued:5.1f}%  {top}")


if __name__ == "__main__":
    main()
