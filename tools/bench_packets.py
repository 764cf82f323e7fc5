"""bench.py packets: what one 16-lane PE packet costs the device, by part.

The bundle kernel (kernels/gridrt_bundles.cl) built with -DGR_PACKET_PROBE=N stops every
packet early: 1 after the work-group's task read (dispatch), 2 after the ray loads and the
masks' store, 3 after the slab test and the interrupt keys, 4 after the packet's culling
box and segment; 0, the kernel itself, adds the triangle tests and the hit stores. Each
stage is one gridrt process (GRIDRT_KERNEL_OPTIONS), the stages in turns for `rounds`
rounds; a part's cost is the difference of two stages' medians of kernel_device_ms over
the frame's packets (kernel_packets). The probes' images are wrong by design: only their
device time is read.
"""
import os
import statistics

from bench_runner import MODELS, gridrt_stats
# Camera rays only: every packet runs the bundle kernel, so every stage cuts all of them.
SCENES = [
    ("bunny 1280x960 primary",
     [os.path.join(MODELS, "bunny.glb"), "--width", "1280", "--height", "960", "--primary-only"]),
    ("bunny_res4 320x240 primary",
     [os.path.join(MODELS, "bunny_res4.glb"), "--width", "320", "--height", "240",
      "--primary-only"]),
]
STAGES = [(1, "dispatch"), (2, "loads and masks"), (3, "slab and interrupt"),
          (4, "culling set-up"), (0, "tests and hit stores")]


def run_stage(args, stage, frames):
    env = dict(os.environ)
    if stage:
        env["GRIDRT_KERNEL_OPTIONS"] = f"-DGR_PACKET_PROBE={stage}"
    else:
        env.pop("GRIDRT_KERNEL_OPTIONS", None)
    return gridrt_stats(args, frames, env=env)


def bench_packets(frames, rounds):
    rows = []
    for label, args in SCENES:
        device_ms = {stage: [] for stage, _ in STAGES}
        packets = None
        for _ in range(rounds):
            for stage, _ in STAGES:
                s = run_stage(args, stage, frames)
                device_ms[stage].append(s["kernel_device_ms"])
                if stage == 0:
                    packets = s["kernel_packets"]
                    rays = s["rays"]["total"]
                    frame_ms = s["frame_ms"]
        previous_ns = 0.0
        for stage, part in STAGES:
            ms = statistics.median(device_ms[stage])
            ns = ms * 1e6 / packets
            rows.append({"scene": label, "stage": stage, "part": part, "device_ms": ms,
                         "packets": packets, "rays": rays, "frame_ms": frame_ms,
                         "ns_per_packet": ns, "part_ns_per_packet": ns - previous_ns})
            print(f"packets {label:27s} stage {stage} {part:22s} device {ms:6.2f} ms, "
                  f"{ns:6.1f} ns a packet (+{ns - previous_ns:5.1f})", flush=True)
            previous_ns = ns
    return rows


def chart_packets(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    fig, ax = plt.subplots(figsize=(7, 4))
    for i, scene in enumerate(scenes):
        bottom = 0.0
        for k, r in enumerate(r for r in rows if r["scene"] == scene):
            ax.barh(i, r["part_ns_per_packet"], left=bottom, color=f"C{k}",
                    label=r["part"] if i == 0 else None)
            bottom += r["part_ns_per_packet"]
    ax.set_yticks(range(len(scenes)), scenes)
    ax.set(xlabel="device ns a 16-lane packet (wall time, all cores)",
           title="A PE packet's cost by part (GR_PACKET_PROBE stages)")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
