#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include "support/blas_threads.hpp"

int main(int argc, char* argv[]) {
  bladestab::use_single_threaded_blas();  // as the program does
  return Catch::Session().run(argc, argv);
}
