#pragma once
// OpenBLAS's thread pool, stopped at start.

namespace pb::app {

// OpenBLAS, loaded with Siconos, starts its threads when it is loaded, before main, and each
// spins for some 2^28 cycles (about 0.1 s of a core) before it sleeps: measured, a fifth of
// the CPU of a paper-set sweep (0.3 s on 2 cores, 0.27 s without), taken from the cores the
// sweep's workers run on. poundbench has no use for them: Siconos' problems are a few
// contacts, and a sweep's own threads are its parallelism. So BLAS is set to one thread and
// the pool is shut down (it would start again at a BLAS call, without the threads). Found by
// name at run time, so nothing happens where the BLAS is another one, or absent.
void stop_blas_threads();

}  // namespace pb::app
