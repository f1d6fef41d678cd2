"""The Python side of the package's speed targets; `cargo bench --bench bindings` times the
same calls in Rust. Prints the median wall time of each call over repeated runs.

    python python/benchmarks/bindings.py
"""

import statistics
import time

import numpy as np

import covga


def resample(path: np.ndarray, n: int) -> np.ndarray:
    """`n` points at equal arc-length steps along `path` (as `benches/bindings.rs`)."""
    steps = np.linalg.norm(np.diff(path, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(steps)])
    at = np.linspace(0.0, s[-1], n)
    return np.column_stack([np.interp(at, s, path[:, 0]), np.interp(at, s, path[:, 1])])


def median_s(call, repeats: int) -> float:
    call()
    times = []
    for _ in range(repeats):
        began = time.perf_counter()
        call()
        times.append(time.perf_counter() - began)
    return statistics.median(times)


def main() -> None:
    world = covga.load_map("thesis-1")
    path = resample(covga.pattern(world, "boustrophedon", start=(1.3, 1.3), width=0.6), 1000)
    score_s = median_s(lambda: covga.score(world, path, width=0.6), 30)
    rng = np.random.default_rng(3)
    genomes = np.stack([rng.uniform(0, 360, (1000, 50)), rng.uniform(0, 3, (1000, 50))], axis=-1)
    evaluate_s = median_s(lambda: covga.thesis.evaluate(world, genomes, width=0.6, projection="f2"), 200)
    print(f"covga.score, 1000-point path: {score_s * 1e3:.2f} ms")
    rate = 1000 / evaluate_s / 1e3
    print(f"covga.thesis.evaluate, 1000 genomes x 50 actions: {evaluate_s * 1e3:.2f} ms ({rate:.1f} k genomes/s)")


if __name__ == "__main__":
    main()
