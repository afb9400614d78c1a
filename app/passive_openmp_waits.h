#pragma once
/// The liftmap executable's OpenMP wait policy (never the library's: a library must not change its host's
/// environment or threads).

namespace liftmap_app {

/// Re-executes the running program (/proc/self/exe, the same arguments) with OMP_WAIT_POLICY=passive, unless the
/// user has chosen a policy or a spin count (OMP_WAIT_POLICY or GOMP_SPINCOUNT set). libgomp reads both once, when
/// it is loaded, so the process must start again to change them. Its default lets a thread that waits at the end of
/// a parallel region spin; when another process wants the same cores, the spinning thread holds a core that the
/// thread it waits for needs. Measured on 2 cores (docs/performance.md): on an idle machine the same wall time and
/// 10% less CPU; beside another process 1.5 times faster (man-homer), up to 15 times on a small pair with many
/// short steps. Returns only if nothing was changed or the exec failed (then with the environment as it was).
void run_with_passive_openmp_waits(char** argv);

}  // namespace liftmap_app
