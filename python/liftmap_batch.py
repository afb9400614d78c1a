"""liftmap.batch: the pairs of a manifest mapped on threads of this process or as tasks of a dask.distributed cluster.

The file work (reading the manifest, mapping a pair into out/<name>/, writing summary.csv) is the library's, through
the module's private per-pair calls, so that every folder equals what `liftmap batch` writes; this module only hands
the pairs out and shows the progress. The documentation is liftmap.batch's (help(liftmap.batch))."""

import concurrent.futures
import os
import sys
import time
import uuid
import warnings

import liftmap

# The keywords of liftmap.map that are options of `liftmap map` (map_argument_specs in src/map/map_arguments.h).
OPTIONS = ("p", "h", "normalize", "tolerance", "max_iterations", "solver", "tree", "samples", "start_relaxation",
           "fix_orientation", "overlay", "pictures", "threads")


def _option_texts(options):
    """The options as the library's texts (set_map_argument): it checks them as it checks the CLI's."""
    texts = {}
    for name, value in options.items():
        if name not in OPTIONS:
            raise TypeError(f"batch() got an unexpected keyword argument '{name}'")
        if value is None and name == "threads":
            continue
        if isinstance(value, bool):
            texts[name] = "true" if value else "false"
        elif isinstance(value, float):
            texts[name] = repr(value)
        else:
            texts[name] = str(value)
    return texts


def _shard(shard):
    """(i, n) from None, (i, n) or "i/n"."""
    if shard is None:
        return 0, 1
    parts = shard.split("/") if isinstance(shard, str) else list(shard)
    try:
        index, count = (int(p) for p in parts)
    except (TypeError, ValueError):
        raise liftmap.UsageError(f"shard: {shard!r} is not i/n with 0 <= i < n") from None
    if not 0 <= index < count:
        raise liftmap.UsageError(f"shard: {shard!r} is not i/n with 0 <= i < n")
    return index, count


# The tasks: module-level functions, so that Dask sends them to its workers by reference.
def _plan(manifest, options, out):
    return liftmap._batch_plan(manifest, options, out)


def _map_pair(manifest, index, out, options, threads):
    return liftmap._batch_run_pair(manifest, index, out, options, threads)


def _summary(manifest, out, options):
    return liftmap._batch_summary(manifest, out, options)


def _duration(seconds):
    s = round(max(0.0, seconds))
    if s < 60:
        return f"{s} s"
    if s < 3600:
        return f"{s // 60} min {s % 60:02d} s"
    return f"{s // 3600} h {s % 3600 // 60:02d} min"


class _Progress:
    """A tqdm bar if tqdm is installed, else the CLI's line per pair on stderr; nothing if not enabled."""

    def __init__(self, total, enabled):
        self.total, self.enabled = total, enabled
        self.done = self.mapped = self.failed = 0
        self.start = time.monotonic()
        self.bar = None
        if enabled:
            try:
                from tqdm.auto import tqdm
                self.bar = tqdm(total=total, unit="pair", desc="liftmap batch")
            except ImportError:
                pass

    def update(self, r):
        self.done += 1
        self.mapped += not r["skipped"]
        self.failed += r["status"] == "failed"
        if self.bar is not None:
            self.bar.set_postfix(failed=self.failed, refresh=False)
            self.bar.update(1)
        elif self.enabled:
            elapsed = time.monotonic() - self.start
            if r["skipped"]:
                what = "complete, skipped"
            elif r["status"] == "failed":
                what = f"failed (exit {r['exit_code']}): {r['message']}"
            else:
                what = f"ok in {_duration(r['seconds'])}"
            line = (f"liftmap: batch: [{self.done}/{self.total}] {r['name']}: {what} | {self.failed} failed, "
                    f"{_duration(elapsed)} elapsed")
            if self.mapped and self.done < self.total:
                line += f", about {_duration(elapsed / self.mapped * (self.total - self.done))} left"
            print(line, file=sys.stderr, flush=True)

    def close(self):
        if self.bar is not None:
            self.bar.close()


def batch(manifest, out, client=None, *, shard=None, jobs=1, progress=True, **options):
    manifest = os.path.abspath(os.fspath(manifest))
    out = os.path.abspath(os.fspath(out))
    texts = _option_texts(options)
    index, count = _shard(shard)
    if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
        raise liftmap.UsageError(f"jobs: {jobs!r} is not an integer >= 1")

    def run(function, *args):  # a call that reads or writes files: on a worker when there is a cluster
        return function(*args) if client is None else client.submit(function, *args, pure=False).result()

    pairs = run(_plan, manifest, texts, out)
    chosen = range(index, len(pairs), count)
    bar = _Progress(len(chosen), progress)
    results = []
    try:
        if client is None:
            threads = liftmap._threads_per_job(options.get("threads"), jobs)
            with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
                futures = [pool.submit(_map_pair, manifest, i, out, texts, threads) for i in chosen]
                for f in concurrent.futures.as_completed(futures):
                    results.append(f.result())
                    bar.update(results[-1])
        else:
            from distributed import as_completed
            tag = uuid.uuid4().hex[:8]
            futures = [client.submit(_map_pair, manifest, i, out, texts, None, pure=False,
                                     key=f"liftmap-batch-{pairs[i]['name']}-{tag}") for i in chosen]
            for f in as_completed(futures):
                results.append(f.result())
                bar.update(results[-1])
    finally:
        bar.close()
    order = {pairs[i]["name"]: k for k, i in enumerate(chosen)}
    results.sort(key=lambda r: order[r["name"]])
    for r in results:
        for w in r["warnings"]:
            warnings.warn(w, stacklevel=2)
    counts = run(_summary, manifest, out, texts)
    counts.update(mapped=sum(not r["skipped"] for r in results), skipped=sum(r["skipped"] for r in results),
                  failures=[{"name": r["name"], "exit_code": r["exit_code"], "message": r["message"]}
                            for r in results if r["status"] == "failed"],
                  summary=os.path.join(out, "summary.csv"))
    return counts
