#include "app/blas_threads.hpp"

#include <dlfcn.h>

#include <bit>

namespace pb::app {

void stop_blas_threads() {
  if (void* set = dlsym(RTLD_DEFAULT, "openblas_set_num_threads")) std::bit_cast<void (*)(int)>(set)(1);
  if (void* shutdown = dlsym(RTLD_DEFAULT, "blas_thread_shutdown_")) std::bit_cast<int (*)()>(shutdown)();
}

}  // namespace pb::app
