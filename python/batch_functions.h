#pragma once
/// The file work of `liftmap.batch` (python/liftmap_batch.py): the same library calls as `liftmap batch`, one pair
/// per call, so that the Python side can hand the pairs to threads or to Dask workers.

#include <pybind11/pybind11.h>

namespace liftmap::python {

/// Binds liftmap._batch_plan, _batch_run_pair, _batch_summary and _threads_per_job (private: liftmap.batch is the
/// documented entry point) and liftmap.batch, which forwards to liftmap_batch.batch.
void bind_batch(pybind11::module_& m);

}  // namespace liftmap::python
